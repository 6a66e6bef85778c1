#include "cluster/check/link_verdict.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace zenith::cluster {

namespace {
/// A clock estimate this uncertain lets two nodes swap up to twice as far
/// apart; the schedule's target is 1 ms between nodes.
constexpr double kClockWarnMs = 0.5;
/// Crystals differ by tens of ppm; far more is a clock being slewed or broken.
constexpr double kDriftWarnPpm = 500.0;
/// Wall clocks this far apart make logs and recordings of different PCs disagree (not the frames).
constexpr double kWallClockWarnMs = 1000.0;
/// Held frames an hour that warn (one) and fail (one a minute).
constexpr double kHeldWarnPerHour = 1.0, kHeldFailPerHour = 60.0;
/// Datagram loss that warns even where the frames' copies hide it: a link of a
/// dedicated switch loses none, so this much is a cable or port failing.
constexpr double kLossWarn = 0.02;
/// A retransmission timeout on Linux: what a lost TCP segment costs the barrier.
constexpr double kRetransmissionMs = 200.0;

/// The findings, graded; into the verdict worst first.
struct Findings {
  LinkVerdict& v;
  std::vector<std::pair<LinkGrade, std::string>> found;
  void add(LinkGrade grade, std::string reason) { found.emplace_back(grade, std::move(reason)); }
  LinkVerdict& done() {
    std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    for (auto& [grade, reason] : found) {
      v.grade = std::max(v.grade, grade);
      v.reasons.push_back(std::move(reason));
    }
    return v;
  }
};
}  // namespace

std::optional<double> LinkMeasurement::loss_to_node() const {
  if (pings_heard == 0) return std::nullopt;
  return std::clamp(1.0 - static_cast<double>(pongs) / pings_heard, 0.0, 1.0);
}
std::optional<double> LinkMeasurement::loss_from_node() const {
  if (pings_sent == 0) return std::nullopt;
  return std::clamp(1.0 - static_cast<double>(pings_heard) / pings_sent, 0.0, 1.0);
}

const char* to_string(LinkGrade grade) {
  switch (grade) {
    case LinkGrade::ok: return "ok";
    case LinkGrade::warn: return "warn";
    case LinkGrade::fail: return "FAIL";
  }
  return "?";
}

int copies_in_time(double one_way_ms, const LinkTarget& target) {
  const double period_ms = 1000.0 / target.frame_rate_hz;
  int copies = 0;
  for (int j = 1; j <= 2 * target.lookahead_frames; ++j)  // copy j leaves j half periods ahead
    if (j * period_ms / 2 - one_way_ms >= period_ms / 2) ++copies;
  return copies;
}

LinkVerdict judge(const LinkMeasurement& link, const LinkTarget& target) {
  LinkVerdict v;
  Findings f{v, {}};
  if (!link.connected) {
    f.add(LinkGrade::fail, fmt::format("never connected: {}", link.problem));
    return f.done();
  }
  if (!link.reported) {
    f.add(LinkGrade::fail, fmt::format("no report: {}", link.problem));
    return f.done();
  }
  const double period_ms = 1000.0 / target.frame_rate_hz;
  const bool scheduled = target.lookahead_frames > 0;
  if (link.pings_heard == 0 && link.pongs == 0) {
    f.add(scheduled ? LinkGrade::fail : LinkGrade::warn,
          scheduled ? std::string("no datagram got through (the UDP port closed by a firewall?): its frames would go "
                                  "over TCP, where a lost packet holds the node 200 ms")
                    : std::string("no datagram got through (the UDP port closed by a firewall?): no clock estimate"));
    return f.done();
  }
  // A cable or port that loses one way loses the other; and while a link is
  // cut the master hears no ping to answer, so the loss toward the node alone
  // would miss a partition. The frames' loss is taken as the larger.
  const double p = std::max(link.loss_to_node().value_or(1.0), link.loss_from_node().value_or(0.0));
  const double one_way_ms = link.round_trip_p99_ms / 2;
  if (scheduled) {
    v.copies_in_time = copies_in_time(one_way_ms, target);
    // Copy j is in time from j ≥ 1 + 2d/T on; two copies need copies up to one more, j ≤ 2L.
    const double first_in_time = std::min(std::ceil(1.0 + 2.0 * one_way_ms / period_ms), 1e6);
    const int lookahead = static_cast<int>(std::ceil((first_in_time + 1.0) / 2.0));
    v.lookahead_for_two_copies = lookahead;
    v.held_frames_per_hour = v.copies_in_time == 0 ? 3600.0 * target.frame_rate_hz
                                                   : 3600.0 * target.frame_rate_hz * std::pow(p, v.copies_in_time);
    if (v.copies_in_time == 0)
      f.add(LinkGrade::fail, fmt::format("round trips up to {:.1f} ms (99th percentile) leave no copy of a frame in "
                                         "time with {} frames of lookahead: every frame late; use {}",
                                         link.round_trip_p99_ms, target.lookahead_frames, lookahead));
    else if (v.held_frames_per_hour >= kHeldWarnPerHour || p >= kLossWarn)
      f.add(v.held_frames_per_hour >= kHeldFailPerHour ? LinkGrade::fail : LinkGrade::warn,
            fmt::format("{:.1f} % of the datagrams lost (toward it {:.1f} %, from it {:.1f} %): about {:.3g} frames "
                        "an hour held a period longer ({} of {} copies in time); look for a bad cable or switch "
                        "port{}",
                        100 * p, 100 * link.loss_to_node().value_or(1.0), 100 * link.loss_from_node().value_or(0.0),
                        v.held_frames_per_hour, v.copies_in_time, 2 * target.lookahead_frames,
                        lookahead > target.lookahead_frames ? fmt::format(", or use a lookahead of {}", lookahead)
                                                            : std::string()));
  } else {
    if (p > 0)
      f.add(LinkGrade::fail,
            fmt::format("{:.2f} % of the packets toward it lost: under the barrier each loss freezes every projector "
                        "for a retransmission (~{:.0f} ms); use the schedule (timing.lookahead_frames ≥ 1)",
                        100 * p, kRetransmissionMs));
    if (link.round_trip_p99_ms > period_ms / 2)
      f.add(LinkGrade::warn, fmt::format("round trips up to {:.1f} ms (99th percentile): the barrier waits that long "
                                         "every frame of {:.1f} ms",
                                         link.round_trip_p99_ms, period_ms));
  }
  if (link.clock_uncertainty_ms > period_ms / 2)
    f.add(LinkGrade::fail,
          fmt::format("its clock estimate is only good to ±{:.2f} ms, half a frame", link.clock_uncertainty_ms));
  else if (link.clock_uncertainty_ms > kClockWarnMs)
    f.add(LinkGrade::warn, fmt::format("its clock estimate is good to ±{:.2f} ms: projectors may swap up to {:.1f} ms "
                                       "apart",
                                       link.clock_uncertainty_ms, 2 * link.clock_uncertainty_ms));
  if (link.clock_steps > 0)
    f.add(LinkGrade::warn, fmt::format("its clock stepped {} time{} during the check", link.clock_steps,
                                       link.clock_steps == 1 ? "" : "s"));
  if (std::abs(link.clock_drift_ppm) > kDriftWarnPpm)
    f.add(LinkGrade::warn, fmt::format("its clock runs {:.0f} ppm off the master's", link.clock_drift_ppm));
  if (std::abs(link.wall_clock_offset_ms) > kWallClockWarnMs)
    f.add(LinkGrade::warn,
          fmt::format("its wall clock is {:.1f} s off the master's: logs will not line up (NTP or PTP on the PCs); "
                      "frames are not affected",
                      link.wall_clock_offset_ms / 1000));
  if (link.throughput_bits_per_s && *link.throughput_bits_per_s < target.min_throughput_bits_per_s)
    f.add(LinkGrade::warn,
          fmt::format("{:.0f} Mbit/s toward it: a paper-size table set (~36 MB) takes {:.1f} s to reach it",
                      *link.throughput_bits_per_s / 1e6, 36e6 * 8 / *link.throughput_bits_per_s));
  return f.done();
}

LinkGrade worst(const std::vector<LinkVerdict>& verdicts) {
  LinkGrade g = LinkGrade::ok;
  for (const LinkVerdict& v : verdicts) g = std::max(g, v.grade);
  return g;
}

}  // namespace zenith::cluster
