#pragma once
// Whether a node's link can carry the show (docs/cluster.md, "Checking the
// network"): what `zenith cluster check` measured of it, and the verdict at
// the cluster's frame rate and lookahead. Pure: the numbers in, the grade and
// its reasons out.
//
// The schedule sends frame N at every tick and half a period after it, from
// lookahead_frames periods before its moment until half a period before it
// (docs/cluster.md, "The frame schedule"). A copy helps when it arrives at
// least half a period before the moment (the node renders it meanwhile): with
// T the period and d the one-way delay (half the 99th-percentile round trip),
// copy j (sent j·T/2 ahead) is in time when j·T/2 − d ≥ T/2. A frame is held — the projector
// shows the last one a period longer — when every copy in time is lost:
// with a fraction p of the datagrams lost independently, held frames an
// hour = 3600 · f · p^(copies in time). p is the larger of the losses toward
// and from the node: a cut link loses both ways, but the master answers only
// the pings it hears, so the loss toward the node alone would not see it.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace zenith::cluster {

/// What the check measured of one node's link. Times in ms.
struct LinkMeasurement {
  std::string node;
  std::string address;            ///< the node's address as the master saw it ("" when it never connected)
  bool connected = false;         ///< authenticated within the check's wait
  bool reported = false;          ///< its LinkReport came; the fields below are set only then
  std::string problem;            ///< why not (never connected, the connection closed: why)
  std::uint32_t pings_sent = 0;   ///< the node's ClockPings of the check
  std::uint32_t pings_heard = 0;  ///< of those, the distinct ones the master received
  std::uint32_t pongs = 0;        ///< the distinct answers the node received
  double round_trip_min_ms = 0, round_trip_p50_ms = 0, round_trip_p99_ms = 0, round_trip_max_ms = 0;
  double clock_uncertainty_ms = 0;  ///< half the least round trip: the bound on the node's clock estimate
  double clock_drift_ppm = 0;
  std::uint32_t clock_steps = 0;
  double clock_offset_ms = 0;       ///< master − node steady clocks, the node's estimate (arbitrary across machines)
  double wall_clock_offset_ms = 0;  ///< node − master wall clocks (CLOCK_REALTIME)
  std::uint64_t fill_bytes = 0;
  double fill_seconds = 0;
  std::optional<double> throughput_bits_per_s;  ///< toward the node; nothing without a timed fill

  /// Datagrams lost toward the node (the master answers every ping it hears) / from it; nothing without any.
  std::optional<double> loss_to_node() const;
  std::optional<double> loss_from_node() const;
  /// The 99th-percentile round trip minus the least (ms).
  double jitter_ms() const { return round_trip_p99_ms - round_trip_min_ms; }
};

/// What the cluster must hold: its frame rate and lookahead (the config's timing).
struct LinkTarget {
  double frame_rate_hz = 30.0;
  int lookahead_frames = 3;  ///< 0: the barrier
  double min_throughput_bits_per_s = 100e6;
};

enum class LinkGrade { ok, warn, fail };
/// "ok", "warn", "FAIL".
const char* to_string(LinkGrade grade);

struct LinkVerdict {
  LinkGrade grade = LinkGrade::ok;
  std::vector<std::string> reasons;  ///< one sentence per finding, worst first; empty when ok
  int copies_in_time = 0;            ///< of each scheduled frame (0 under the barrier)
  double held_frames_per_hour = 0;   ///< expected, from the measured loss (scheduled frames)
  /// The least lookahead that leaves two copies in time at the measured delay (nothing under the barrier).
  std::optional<int> lookahead_for_two_copies;
};

/// Copies of a scheduled frame that arrive in time at one-way delay `one_way_ms`.
int copies_in_time(double one_way_ms, const LinkTarget& target);
LinkVerdict judge(const LinkMeasurement& link, const LinkTarget& target);
/// The worst of the verdicts (ok for none).
LinkGrade worst(const std::vector<LinkVerdict>& verdicts);

}  // namespace zenith::cluster
