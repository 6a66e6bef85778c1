#include "cluster/link/clock_sync.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace zenith::cluster {

namespace {
constexpr std::size_t kRecentDelays = 16;
constexpr std::int64_t kMinFitSpanNs = 1'000'000'000;  // a line needs samples a second apart
/// The clocks' rate difference a node may believe without evidence: NTP's
/// largest frequency correction (RFC 5905, MAXFREQ = 500 ppm). Crystals
/// differ by tens of ppm; a fitted slope beyond this is noise.
constexpr double kDriftPrior = 500e-6;
}  // namespace

void ClockSync::seed(std::int64_t master_ns, std::int64_t node_ns) { seed_ = Sample{node_ns, master_ns - node_ns, 0}; }

void ClockSync::add(const Exchange& e) {
  const std::int64_t on_master = e.master_sent_ns - e.master_received_ns;
  const std::int64_t on_node = e.node_received_ns - e.node_sent_ns;
  if (on_master < 0 || on_node < 0 || on_node < on_master) return;  // not a real exchange
  ++exchanges_;
  const Sample s{e.node_sent_ns + on_node / 2,
                 ((e.master_received_ns - e.node_sent_ns) + (e.master_sent_ns - e.node_received_ns)) / 2,
                 on_node - on_master};
  recent_delays_.push_back(s.delay_ns);
  if (recent_delays_.size() > kRecentDelays) recent_delays_.pop_front();

  // A step: the clocks jumped apart (a clock set by hand, another master). The
  // line no longer holds; kStepConfirmations exchanges in a row say so. The
  // true offset lies within both bounds (the sample's and the line's) unless
  // the clocks moved, so only a gap between the bounds is evidence.
  if (const std::optional<Prediction> line = predicted(s.node_ns)) {
    const std::int64_t off = std::llabs(s.offset_ns - line->offset_ns);
    const std::int64_t gap = off - line->bound_ns - s.delay_ns / 2;
    if (gap > kStepThresholdNs && off > 4 * s.delay_ns) {
      if (++off_line_ >= kStepConfirmations) {
        ++steps_;
        kept_.clear();
        fitted_ = false;
        group_best_.reset();
        group_count_ = 0;
        off_line_ = 0;
        keep(s);
      }
      return;
    }
  }
  off_line_ = 0;
  if (!group_best_ || s.delay_ns < group_best_->delay_ns) group_best_ = s;
  if (++group_count_ >= kGroupSamples || kept_.empty()) {
    keep(*group_best_);
    group_best_.reset();
    group_count_ = 0;
  }
}

void ClockSync::keep(const Sample& sample) {
  kept_.push_back(sample);
  if (kept_.size() > kKeptSamples) kept_.pop_front();
  fit();
}

/// The kept samples bounded nearly as tightly as the best one: δ at most
/// 1.5 δ_min + 50 µs. The others (every exchange of their group was held up)
/// are left out, as NTP's clock filter leaves out the popcorn spikes.
static bool tight(std::int64_t delay_ns, std::int64_t least_ns) { return delay_ns <= least_ns * 3 / 2 + 50'000; }

std::int64_t ClockSync::least_kept_delay() const {
  std::int64_t least = kept_.front().delay_ns;
  for (const Sample& s : kept_) least = std::min(least, s.delay_ns);
  return least;
}

/// Least squares of θ against the node's time over the tight kept samples,
/// each weighted by 1 / δ² (δ floored at 10 µs so that one lucky sample does
/// not rule). A sample's θ is off by at most δ/2, so the slope is known to
/// about σ_d = 1 / (2 √(Σ w (t − t̄)²)); over a short span of noisy samples
/// (a second of 5 ± 1 ms legs: σ_d of thousands of ppm) it would invent a
/// drift that the prediction then carries forward. So the slope is shrunk
/// toward 0 by a prior of width kDriftPrior, as a Gaussian prior's posterior
/// mean is: d · D² / (D² + σ_d²) — the full slope once the span pins it down
/// (a minute of clean exchanges: σ_d of a few ppm), none while it cannot.
void ClockSync::fit() {
  fitted_ = false;
  if (kept_.size() < 2) return;
  const std::int64_t least = least_kept_delay();
  std::int64_t first = 0, last = 0;
  int used = 0;
  t0_ = kept_.back().node_ns;
  double sw = 0, st = 0, so = 0, stt = 0, sto = 0;
  std::int64_t widest = 0;
  for (const Sample& s : kept_) {
    if (!tight(s.delay_ns, least)) continue;
    if (used++ == 0) first = s.node_ns;
    last = s.node_ns;
    widest = std::max(widest, s.delay_ns);
    const double d = std::max<double>(static_cast<double>(s.delay_ns), 1e4);
    const double w = 1.0 / (d * d);
    const double t = static_cast<double>(s.node_ns - t0_);
    const double o = static_cast<double>(s.offset_ns);
    sw += w, st += w * t, so += w * o, stt += w * t * t, sto += w * t * o;
  }
  if (used < 2 || last - first < kMinFitSpanNs) return;
  const double det = sw * stt - st * st;
  if (!(det > 0.0)) return;
  const double spread = det / sw;  // Σ w (t − t̄)², ns⁰ (w in 1/ns²)
  const double slope_variance = 1.0 / (4.0 * spread);
  const double prior = kDriftPrior * kDriftPrior;
  drift_ = (sw * sto - st * so) / det * prior / (prior + slope_variance);
  offset0_ = (so - drift_ * st) / sw;  // the weighted mean's line through that slope
  fitted_delay_ns_ = widest;
  fitted_ = true;
}

std::optional<ClockSync::Prediction> ClockSync::predicted(std::int64_t node_ns) const {
  if (fitted_)
    return Prediction{static_cast<std::int64_t>(std::llround(offset0_ + drift_ * static_cast<double>(node_ns - t0_))),
                      fitted_delay_ns_ / 2};
  if (kept_.empty()) return std::nullopt;
  // Before a line: the latest of the tightest kept samples.
  const std::int64_t least = least_kept_delay();
  for (auto s = kept_.rbegin(); s != kept_.rend(); ++s)
    if (tight(s->delay_ns, least)) return Prediction{s->offset_ns, s->delay_ns / 2};
  return Prediction{kept_.back().offset_ns, kept_.back().delay_ns / 2};
}

std::int64_t ClockSync::offset_ns(std::int64_t node_ns) const {
  if (const std::optional<Prediction> line = predicted(node_ns)) return line->offset_ns;
  if (group_best_) return group_best_->offset_ns;
  if (seed_) return seed_->offset_ns;
  return 0;
}

std::int64_t ClockSync::to_node(std::int64_t master_ns) const {
  // θ depends on the node's time only through the drift (ppm): two rounds
  // of t = m − θ(t) converge to well below a nanosecond.
  std::int64_t t = master_ns - offset_ns(master_ns);
  t = master_ns - offset_ns(t);
  return t;
}

std::optional<std::int64_t> ClockSync::round_trip_ns() const {
  if (recent_delays_.empty()) return std::nullopt;
  return *std::min_element(recent_delays_.begin(), recent_delays_.end());
}

}  // namespace zenith::cluster
