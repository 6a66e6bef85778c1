#include "cluster/node/thumbnail.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/strings.h"
#include "image/tone_mapping.h"

namespace zenith::cluster {

using core::cat;

Thumbnail make_thumbnail(std::uint64_t frame, const std::string& output, std::span<const float> display_rgb,
                         int width_px, int height_px, int edge_px) {
  if (width_px < 1 || height_px < 1 || edge_px < 1 || edge_px > kMaxThumbnailEdgePx)
    throw std::invalid_argument(cat("thumbnail of '", output, "': ", width_px, "x", height_px, " pixels, edge ",
                                    edge_px, " px (sizes at least 1, edge in [1, ", kMaxThumbnailEdgePx, "])"));
  const std::size_t w = static_cast<std::size_t>(width_px), h = static_cast<std::size_t>(height_px);
  if (display_rgb.size() != w * h * 3)
    throw std::invalid_argument(cat("thumbnail of '", output, "': ", display_rgb.size(), " values for ", width_px, "x",
                                    height_px, " RGB pixels"));
  const auto [thumbnail_width, thumbnail_height] = render::display::thumbnail_size(width_px, height_px, edge_px);
  const auto tw = static_cast<std::size_t>(thumbnail_width), th = static_cast<std::size_t>(thumbnail_height);
  Thumbnail t;
  t.frame = frame;
  t.output = output;
  t.width_px = static_cast<std::uint16_t>(tw);
  t.height_px = static_cast<std::uint16_t>(th);
  t.rgb.resize(tw * th * 3);
  // Thumbnail pixel (x, y) covers output columns [x·w/tw, (x+1)·w/tw) and rows likewise (at least one each).
  const auto span_of = [](std::size_t i, std::size_t n, std::size_t total) {
    const std::size_t begin = i * total / n;
    return std::pair{begin, std::max(begin + 1, (i + 1) * total / n)};
  };
  for (std::size_t y = 0; y < th; ++y) {
    const auto [y0, y1] = span_of(y, th, h);
    for (std::size_t x = 0; x < tw; ++x) {
      const auto [x0, x1] = span_of(x, tw, w);
      double sum[3] = {0.0, 0.0, 0.0};
      for (std::size_t sy = y0; sy < y1; ++sy)
        for (std::size_t sx = x0; sx < x1; ++sx)
          for (std::size_t c = 0; c < 3; ++c) {
            const float v = display_rgb[(sy * w + sx) * 3 + c];
            sum[c] += v > 1.0f ? 1.0 : v > 0.0f ? static_cast<double>(v) : 0.0;  // NaN counts as 0
          }
      const double count = static_cast<double>((y1 - y0) * (x1 - x0));
      for (std::size_t c = 0; c < 3; ++c)
        t.rgb[(y * tw + x) * 3 + c] =
            image::display_byte(static_cast<float>(sum[c] / count), image::ToneMapping::clamp);
    }
  }
  return t;
}

Thumbnail make_thumbnail(std::uint64_t frame, const std::string& output, const render::display::ThumbnailMeans& means) {
  static_assert(render::display::kMaxThumbnailEdgePx == kMaxThumbnailEdgePx);
  if (means.width_px < 1 || means.height_px < 1 || means.width_px > kMaxThumbnailEdgePx ||
      means.height_px > kMaxThumbnailEdgePx ||
      means.rgb.size() != static_cast<std::size_t>(means.width_px) * static_cast<std::size_t>(means.height_px) * 3)
    throw std::invalid_argument(cat("thumbnail of '", output, "': ", means.width_px, "x", means.height_px, " pixels, ",
                                    means.rgb.size(), " values (sizes in [1, ", kMaxThumbnailEdgePx,
                                    "], 3 values a pixel)"));
  Thumbnail t;
  t.frame = frame;
  t.output = output;
  t.width_px = static_cast<std::uint16_t>(means.width_px);
  t.height_px = static_cast<std::uint16_t>(means.height_px);
  t.rgb.resize(means.rgb.size());
  for (std::size_t i = 0; i < means.rgb.size(); ++i)
    t.rgb[i] = image::display_byte(means.rgb[i], image::ToneMapping::clamp);
  return t;
}

}  // namespace zenith::cluster
