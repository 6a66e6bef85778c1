#pragma once
// The operator console's live dome preview (docs/operator.md, "Dome preview"):
// the nodes' thumbnails of their outputs (docs/protocol.md, PreviewRequest and
// Thumbnail) put together into one small picture. Outputs that are tiles of
// one fisheye dome master (warp/dome_tiles.h, as dome-quadrants.json) are
// placed where they sit in it, scaled alike; any other outputs (planar
// projectors, warped outputs) are shown side by side in a grid, in the
// configuration's order, each in a cell of kMaxThumbnailEdgePx. No sockets,
// no clock.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cluster/link/cluster_config.h"
#include "cluster/protocol/messages.h"
#include "warp/viewport_config.h"

namespace zenith::cluster {

/// Invariant: every kept thumbnail is of an output of the node that sent it,
/// within the size asked for (kMaxThumbnailEdgePx).
class DomePreview {
 public:
  enum class Layout { dome, grid };
  /// 8-bit sRGB pixels, rows top to bottom, RGB interleaved.
  struct Picture {
    int width_px = 0, height_px = 0;
    std::vector<std::uint8_t> rgb;
  };

  /// Every output of every node of `config`, as `viewports` (the config's) defines them.
  DomePreview(const ClusterConfig& config, const warp::ViewportConfig& viewports);

  Layout layout() const { return layout_; }
  int width_px() const { return width_px_; }
  int height_px() const { return height_px_; }

  /// Keeps `thumbnail` of node `node` in place of its output's earlier one.
  /// Throws std::invalid_argument, naming the node and the output, when the
  /// output is not one of the node's or the thumbnail's size or bytes are wrong.
  void add(const std::string& node, Thumbnail thumbnail);
  /// Forgets every thumbnail (the preview is turned off).
  void clear() { thumbnails_.clear(); }
  bool empty() const { return thumbnails_.empty(); }
  /// Outputs with a thumbnail, of how many.
  std::size_t tiles() const { return thumbnails_.size(); }
  std::size_t outputs() const { return slots_.size(); }
  /// The newest and the oldest frame among the thumbnails kept (nullopt: none).
  std::optional<std::uint64_t> newest_frame() const;
  std::optional<std::uint64_t> oldest_frame() const;

  /// The preview: every kept thumbnail in its place (nearest-neighbour scaled
  /// into its rectangle), black where none is (and grey between grid cells).
  Picture compose() const;

 private:
  /// Where one output goes: its rectangle in the preview, in pixels.
  struct Slot {
    std::string node;
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< [x0, x1) × [y0, y1); grid: the cell
  };
  Layout layout_ = Layout::grid;
  int width_px_ = 0, height_px_ = 0;
  std::map<std::string, Slot> slots_;            ///< by output name
  std::map<std::string, Thumbnail> thumbnails_;  ///< by output name
};

}  // namespace zenith::cluster
