#include "cluster/standby/standby_follower.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "core/strings.h"

namespace zenith::cluster {

using core::cat;

void StandbyFollower::on_welcome() { receiver_ = TableReceiver{}; }

void StandbyFollower::on_message(const Message& message) {
  if (const auto* d = std::get_if<AtmosphereDefinition>(&message)) {
    definitions_[d->table_hash] = *d;
  } else if (const auto* a = std::get_if<TableAnnounce>(&message)) {
    if (!definitions_.count(a->table_hash))
      throw std::runtime_error(
          cat("TableAnnounce of table set ", short_hex(a->table_hash),
              " without its AtmosphereDefinition: a standby cannot serve a set it cannot describe"));
    receiver_.on_announce(*a);
  } else if (const auto* c = std::get_if<TableChunk>(&message)) {
    std::optional<std::vector<std::uint8_t>> bytes = receiver_.on_chunk(*c);  // verified once complete
    if (!bytes) return;
    const AtmosphereDefinition& definition = definitions_.at(c->table_hash);
    TakeoverState::Version version{
        definition, make_table_set(definition.body_name, c->table_hash,
                                   std::make_shared<const std::vector<std::uint8_t>>(std::move(*bytes)))};
    const auto held = std::find_if(versions_.begin(), versions_.end(),
                                   [&](const auto& v) { return v.definition.table_hash == c->table_hash; });
    if (held != versions_.end())
      *held = std::move(version);  // sent again after a new Welcome
    else
      versions_.push_back(std::move(version));
  } else if (const auto* f = std::get_if<FrameState>(&message)) {
    std::optional<double> step_s;
    if (last_ && f->frame == last_->frame + 1) step_s = f->show_time_s - last_->show_time_s;
    // A step seen twice in a row is the playback's (rate / fps, or 0 paused); a
    // one-off step is a seek or a loop's wrap, and changes nothing.
    if (step_s && last_step_s_ && std::abs(*step_s - *last_step_s_) <= 1e-9) steady_step_s_ = *step_s;
    last_step_s_ = step_s;
    last_ = *f;
    ++frames_seen_;
  } else if (const auto* p = std::get_if<Present>(&message)) {
    last_presented_ = p->frame;
  } else {
    throw std::runtime_error(cat(to_string(message_type(message)), " is not sent to a standby master"));
  }
}

std::optional<std::string> StandbyFollower::takeover_problem() const {
  if (!last_) return std::nullopt;
  for (const AtmosphereTableRef& ref : last_->atmospheres) {
    const bool held = std::any_of(versions_.begin(), versions_.end(),
                                  [&](const auto& v) { return v.definition.table_hash == ref.table_hash; });
    if (!held)
      return cat("frame ", last_->frame, " uses table set ", short_hex(ref.table_hash), " of '", ref.body_name,
                 "', which this standby has not received in full");
  }
  return std::nullopt;
}

TakeoverState StandbyFollower::takeover_state() const {
  if (const std::optional<std::string> problem = takeover_problem())
    throw std::logic_error(cat("StandbyFollower::takeover_state: ", *problem));
  TakeoverState state;
  state.last_frame = last_;
  state.show_time_step_s = steady_step_s_;
  state.last_presented = last_presented_;
  state.versions = versions_;
  return state;
}

}  // namespace zenith::cluster
