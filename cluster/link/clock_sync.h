#pragma once
// A node's estimate of the master's steady clock (docs/cluster.md, "Clocks"),
// from ClockPing / ClockPong exchanges, as NTP estimates a server's (RFC 5905,
// the on-wire protocol and the clock filter, simplified):
//
//   one exchange: t1 the node sends, t2 the master receives, t3 the master
//   answers, t4 the node receives (t1, t4 on the node's clock; t2, t3 on the
//   master's). Then
//       offset θ = ((t2 − t1) + (t3 − t4)) / 2      master − node, in ns
//       delay  δ = (t4 − t1) − (t3 − t2)           the round trip on the wire
//   and the true offset lies within θ ± δ/2 whatever the two legs' delays.
//
// Samples with a long round trip (a queue, a retransmission, a busy host) are
// the worst bounded, so of each group of kGroupSamples exchanges only the one
// with the least δ is kept (the clock filter). The kept samples of the last
// minute or so give the offset and the drift (the clocks' rate difference, in
// ppm) by a least-squares line θ(t) = θ0 + drift · (t − t0), its slope shrunk
// toward 0 while the samples cannot pin it down (clock_sync.cpp: a drift of
// thousands of ppm from a second of jittery samples is noise, not a clock);
// until two of them span a second, the latest kept sample's offset alone, and
// before any exchange the one-way estimate of the Welcome (good to the one-way delay).
//
// A node whose clock steps (or a master replaced by a standby on another
// machine) shows samples far off the line: kStepConfirmations in a row whose
// bounds miss the line's by more than kStepThresholdNs (and that lie several
// δ away) start the estimate afresh, and steps() counts it. The line's own
// bound counts: a first exchange held up 10 ms on a busy host is a poor
// estimate, not a clock that stepped when the clean exchanges disagree. Pure bookkeeping: time is passed in (tests
// drive it with clocks that drift and step).
#include <cstdint>
#include <deque>
#include <optional>

namespace zenith::cluster {

class ClockSync {
 public:
  /// One exchange, all in ns: t1, t4 the node's clock; t2, t3 the master's.
  struct Exchange {
    std::int64_t node_sent_ns = 0, master_received_ns = 0, master_sent_ns = 0, node_received_ns = 0;
  };
  static constexpr int kGroupSamples = 4;                      ///< exchanges per kept sample (the least δ of them)
  static constexpr std::size_t kKeptSamples = 64;              ///< kept samples the line is fitted to
  static constexpr std::int64_t kStepThresholdNs = 2'000'000;  ///< 2 ms between the bounds, and 4 δ: a step
  static constexpr int kStepConfirmations = 3;

  /// The Welcome's one-way estimate: the master's clock read `master_ns` when
  /// the node's read `node_ns` (the master's is then ahead by the one-way delay).
  void seed(std::int64_t master_ns, std::int64_t node_ns);
  /// A ClockPong arrived. Exchanges with t4 < t1 or t3 < t2 are ignored.
  void add(const Exchange& exchange);

  /// Whether any exchange completed (else only the seed, or nothing).
  bool synchronized() const { return !kept_.empty() || group_best_.has_value(); }
  /// Whether there is any estimate (a seed or an exchange).
  bool has_estimate() const { return synchronized() || seed_.has_value(); }
  /// master − node at the node's time `node_ns` (0 without any estimate).
  std::int64_t offset_ns(std::int64_t node_ns) const;
  /// The node's time at which the master's clock reads `master_ns`.
  std::int64_t to_node(std::int64_t master_ns) const;
  /// The master's time when the node's clock reads `node_ns`.
  std::int64_t to_master(std::int64_t node_ns) const { return node_ns + offset_ns(node_ns); }
  /// The fitted rate difference (master − node) in parts per million; 0 until fitted.
  double drift_ppm() const { return drift_ * 1e6; }
  /// The least round trip among the recent exchanges (ns); nothing before one.
  std::optional<std::int64_t> round_trip_ns() const;
  /// How often the estimate started afresh because the clocks stepped apart.
  std::uint64_t steps() const { return steps_; }
  /// Exchanges taken (not counting ignored ones).
  std::uint64_t exchanges() const { return exchanges_; }

 private:
  struct Sample {
    std::int64_t node_ns;    ///< the node's time of the sample (midpoint of t1, t4)
    std::int64_t offset_ns;  ///< θ
    std::int64_t delay_ns;   ///< δ
  };
  /// What the kept samples say of the offset at one time: θ, and the
  /// half-width of its bound (half the δ of the samples it rests on).
  struct Prediction {
    std::int64_t offset_ns;
    std::int64_t bound_ns;
  };
  void keep(const Sample& sample);
  void fit();
  std::int64_t least_kept_delay() const;  ///< precondition: kept_ not empty
  /// The offset the current line predicts at `node_ns` (no fallback to the group's best).
  std::optional<Prediction> predicted(std::int64_t node_ns) const;

  std::optional<Sample> seed_;
  std::optional<Sample> group_best_;
  int group_count_ = 0;
  std::deque<Sample> kept_;
  std::deque<std::int64_t> recent_delays_;  ///< the last 16 exchanges' δ
  int off_line_ = 0;                        ///< consecutive exchanges far off the line
  // The fitted line: θ(t) = offset0_ + drift_ · (t − t0_).
  std::int64_t t0_ = 0;
  double offset0_ = 0.0, drift_ = 0.0;
  std::int64_t fitted_delay_ns_ = 0;  ///< the largest δ among the samples the line was fitted to
  bool fitted_ = false;
  std::uint64_t steps_ = 0, exchanges_ = 0;
};

}  // namespace zenith::cluster
