#pragma once
// What the master has seen of each node over the whole run, by node name, so
// that it survives reconnections (docs/operator.md, "Status"): frames
// rendered and the last render time (RenderDone), how often the barrier
// waited for the node (its RenderDone came last), dropped it (barrier
// timeout) or took it back (its late report), and how often it joined.
// Bookkeeping only: the master reports, the operator console reads.
#include <cstdint>
#include <map>
#include <optional>
#include <string>

namespace zenith::cluster {

class NodeStatistics {
 public:
  struct Counts {
    std::uint64_t frames_rendered = 0;
    std::optional<double> last_render_ms;  ///< the node's own render time of its latest frame
    std::uint64_t barrier_waits = 0;       ///< frames whose barrier the node completed last (others waited for it)
    std::uint64_t drops = 0;               ///< frames it missed the barrier of (timeout)
    std::uint64_t rejoins = 0;             ///< late reports that brought it back
    std::uint64_t joins = 0;               ///< times it became ready (1 + rejoins after reconnecting)
    // Its presents in windows (RenderDone's counts, render/window/present_clock.h),
    // summed over the node's processes (a restarted node counts from 0 again).
    std::uint64_t presents = 0;             ///< frames presented in windows (0: headless)
    std::uint64_t late_presents = 0;        ///< of those, late: a missed vblank
    std::optional<double> last_present_ms;  ///< its latest present: Present's arrival to the completed swap
    /// Scheduled frames it did not present (they reached it after their moment,
    /// or not at all: a cut link), summed over its processes (RenderDone.missed_frames).
    std::uint64_t missed_frames = 0;
    /// Its latest join: the table bytes sent to it and the time from its
    /// inventory to ready (transfer, verification, caching and loading).
    std::uint64_t tables_bytes = 0;
    std::optional<double> tables_s;
  };

  /// RenderDone for the frame in flight took `render_ms` on the node;
  /// `completed_barrier`: it was the last of two or more participants.
  void rendered(const std::string& node, double render_ms, bool completed_barrier);
  void dropped(const std::string& node) { counts_[node].drops += 1; }
  void rejoined(const std::string& node) { counts_[node].rejoins += 1; }
  void joined(const std::string& node) { counts_[node].joins += 1; }
  /// It became ready `seconds` after its inventory, `bytes` of tables sent to it.
  void tables_received(const std::string& node, std::uint64_t bytes, double seconds) {
    counts_[node].tables_bytes = bytes;
    counts_[node].tables_s = seconds;
  }
  /// A RenderDone's present counts (the node process's totals so far);
  /// returns how many late presents are new since the node's previous report.
  std::uint64_t presented(const std::string& node, std::uint64_t presents, std::uint64_t late_presents,
                          double present_ms);

  /// A RenderDone's missed scheduled frames (the node process's total so far);
  /// returns how many are new since its previous report.
  std::uint64_t missed(const std::string& node, std::uint64_t missed_frames);

  /// The counts of `node`; all zero for a node never seen.
  Counts of(const std::string& node) const;

 private:
  /// The counts of a node's earlier processes, and its current process's last report.
  struct PresentBase {
    std::uint64_t presents = 0, late = 0;                    ///< summed over earlier processes
    std::uint64_t reported_presents = 0, reported_late = 0;  ///< the current process's last report
    std::uint64_t missed = 0, reported_missed = 0;
  };
  std::map<std::string, Counts> counts_;
  std::map<std::string, PresentBase> present_bases_;
};

}  // namespace zenith::cluster
