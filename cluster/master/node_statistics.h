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
  };

  /// RenderDone for the frame in flight took `render_ms` on the node;
  /// `completed_barrier`: it was the last of two or more participants.
  void rendered(const std::string& node, double render_ms, bool completed_barrier);
  void dropped(const std::string& node) { counts_[node].drops += 1; }
  void rejoined(const std::string& node) { counts_[node].rejoins += 1; }
  void joined(const std::string& node) { counts_[node].joins += 1; }

  /// The counts of `node`; all zero for a node never seen.
  Counts of(const std::string& node) const;

 private:
  std::map<std::string, Counts> counts_;
};

}  // namespace zenith::cluster
