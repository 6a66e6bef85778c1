#include "cluster/operator/dome_preview.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/strings.h"
#include "warp/dome_tiles.h"

namespace zenith::cluster {

using core::cat;

namespace {

/// Between the cells of a grid: pixels and their grey value.
constexpr int kGridGapPx = 2;
constexpr std::uint8_t kGridGapGrey = 48;

}  // namespace

DomePreview::DomePreview(const ClusterConfig& config, const warp::ViewportConfig& viewports) {
  std::vector<const warp::OutputConfig*> outputs;
  std::vector<std::string> nodes;
  for (const ClusterNodeConfig& node : config.nodes)
    for (const std::string& name : node.outputs)
      if (const warp::OutputConfig* o = viewports.find(name)) {
        outputs.push_back(o);
        nodes.push_back(node.name);
      }
  if (outputs.empty()) {
    width_px_ = height_px_ = 1;
    return;
  }
  if (const auto origins = warp::dome_tile_origins(outputs)) {
    // Tiles of one dome master: all scaled alike, the largest output side to kMaxThumbnailEdgePx.
    layout_ = Layout::dome;
    int width = 0, height = 0, longest = 1;
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      width = std::max(width, (*origins)[i][0] + outputs[i]->width_px);
      height = std::max(height, (*origins)[i][1] + outputs[i]->height_px);
      longest = std::max({longest, outputs[i]->width_px, outputs[i]->height_px});
    }
    const double scale = std::min(1.0, static_cast<double>(kMaxThumbnailEdgePx) / longest);
    const auto scaled = [&](int v) { return static_cast<int>(std::lround(v * scale)); };
    width_px_ = std::max(1, scaled(width));
    height_px_ = std::max(1, scaled(height));
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      const int x = (*origins)[i][0], y = (*origins)[i][1];
      slots_[outputs[i]->name] =
          Slot{nodes[i], scaled(x), scaled(y), std::max(scaled(x) + 1, scaled(x + outputs[i]->width_px)),
               std::max(scaled(y) + 1, scaled(y + outputs[i]->height_px))};
    }
    return;
  }
  // Anything else: a grid of cells, in the configuration's order.
  const int count = static_cast<int>(outputs.size());
  const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
  const int rows = (count + columns - 1) / columns;
  const int cell = kMaxThumbnailEdgePx;
  width_px_ = columns * cell + (columns - 1) * kGridGapPx;
  height_px_ = rows * cell + (rows - 1) * kGridGapPx;
  for (int i = 0; i < count; ++i) {
    const int x = (i % columns) * (cell + kGridGapPx), y = (i / columns) * (cell + kGridGapPx);
    slots_[outputs[static_cast<std::size_t>(i)]->name] =
        Slot{nodes[static_cast<std::size_t>(i)], x, y, x + cell, y + cell};
  }
}

void DomePreview::add(const std::string& node, Thumbnail thumbnail) {
  const auto slot = slots_.find(thumbnail.output);
  if (slot == slots_.end() || slot->second.node != node)
    throw std::invalid_argument(
        cat("a thumbnail of output '", thumbnail.output, "', which is not one of node '", node, "''s outputs"));
  if (thumbnail.width_px < 1 || thumbnail.width_px > kMaxThumbnailEdgePx || thumbnail.height_px < 1 ||
      thumbnail.height_px > kMaxThumbnailEdgePx ||
      thumbnail.rgb.size() != static_cast<std::size_t>(thumbnail.width_px) * thumbnail.height_px * 3)
    throw std::invalid_argument(cat("a thumbnail of output '", thumbnail.output, "' of ", thumbnail.width_px, "x",
                                    thumbnail.height_px, " pixels in ", thumbnail.rgb.size(), " bytes"));
  const std::string output = thumbnail.output;
  thumbnails_.insert_or_assign(output, std::move(thumbnail));
}

std::optional<std::uint64_t> DomePreview::newest_frame() const {
  std::optional<std::uint64_t> frame;
  for (const auto& [output, t] : thumbnails_) frame = std::max(frame.value_or(t.frame), t.frame);
  return frame;
}

std::optional<std::uint64_t> DomePreview::oldest_frame() const {
  std::optional<std::uint64_t> frame;
  for (const auto& [output, t] : thumbnails_) frame = std::min(frame.value_or(t.frame), t.frame);
  return frame;
}

DomePreview::Picture DomePreview::compose() const {
  Picture p;
  p.width_px = width_px_;
  p.height_px = height_px_;
  p.rgb.assign(static_cast<std::size_t>(width_px_) * height_px_ * 3, layout_ == Layout::grid ? kGridGapGrey : 0);
  const auto put = [&](int x, int y, const std::uint8_t* rgb) {
    std::copy_n(rgb, 3, p.rgb.begin() + (static_cast<std::ptrdiff_t>(y) * width_px_ + x) * 3);
  };
  for (const auto& [output, slot] : slots_) {
    // The cell (grid) or the tile's rectangle (dome), black until a thumbnail comes.
    for (int y = slot.y0; y < slot.y1; ++y)
      for (int x = slot.x0; x < slot.x1; ++x) {
        static constexpr std::uint8_t kBlack[3] = {0, 0, 0};
        put(x, y, kBlack);
      }
    const auto found = thumbnails_.find(output);
    if (found == thumbnails_.end()) continue;
    const Thumbnail& t = found->second;
    // Dome: stretched over the tile's rectangle. Grid: its own size, centred in the cell.
    int x0 = slot.x0, y0 = slot.y0, w = slot.x1 - slot.x0, h = slot.y1 - slot.y0;
    if (layout_ == Layout::grid) {
      x0 += (w - t.width_px) / 2;
      y0 += (h - t.height_px) / 2;
      w = t.width_px;
      h = t.height_px;
    }
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t sx = static_cast<std::size_t>(x) * t.width_px / static_cast<std::size_t>(w);
        const std::size_t sy = static_cast<std::size_t>(y) * t.height_px / static_cast<std::size_t>(h);
        put(x0 + x, y0 + y, &t.rgb[(sy * t.width_px + sx) * 3]);
      }
  }
  return p;
}

}  // namespace zenith::cluster
