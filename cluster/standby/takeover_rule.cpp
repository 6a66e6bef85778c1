#include "cluster/standby/takeover_rule.h"

namespace zenith::cluster {

bool TakeoverRule::welcomed() {
  const bool was_checking = phase_ == Phase::checking;
  if (phase_ != Phase::taking_over) phase_ = Phase::following;
  if (was_checking) ++false_alarms_;
  return was_checking;
}

void TakeoverRule::lost() {
  if (phase_ == Phase::following) phase_ = Phase::checking;
}

bool TakeoverRule::attempt_failed() {
  if (phase_ != Phase::checking) return false;
  phase_ = Phase::taking_over;
  return true;
}

}  // namespace zenith::cluster
