#include "warp/blending.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/files.h"
#include "warp/blend_map.h"
#include "warp/mpcdi_blend.h"
#include "warp/warped_projection.h"

namespace zenith::warp {
namespace {

/// Concatenation through a stream (GCC 12 warns falsely on chains of std::string +).
template <typename... T>
std::string cat(const T&... parts) {
  std::ostringstream s;
  (s << ... << parts);
  return s.str();
}

/// The ramp: 3t² − 2t³ on [0, 1], 0 below, 1 above (C1, slope ≤ 1.5).
double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// Felzenszwalb & Huttenlocher's 1D squared Euclidean distance transform of the
/// samples f[0, n) (0 at features, "infinity" elsewhere), into d[0, n).
void distance_transform_1d(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v,
                           std::vector<double>& z) {
  const int n = static_cast<int>(f.size());
  int k = 0;
  v[0] = 0;
  z[0] = -std::numeric_limits<double>::infinity();
  z[1] = std::numeric_limits<double>::infinity();
  auto intersection = [&](int q, int p) { return ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * (q - p)); };
  for (int q = 1; q < n; ++q) {
    double s = intersection(q, v[k]);
    while (s <= z[k]) {  // z[0] = −∞ stops this at k = 0
      --k;
      s = intersection(q, v[k]);
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = std::numeric_limits<double>::infinity();
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    const double dq = q - v[k];
    d[q] = dq * dq + f[v[k]];
  }
}

/// Per pixel centre of a width × height image, the Euclidean distance (px) to
/// the nearest centre where `feature` is true; infinity when there is none.
std::vector<float> distance_transform(const std::vector<bool>& feature, int width, int height) {
  // Large but finite, so the parabola intersections stay finite.
  const double far = 4.0 * (double(width) * width + double(height) * height) + 1.0;
  std::vector<double> grid(static_cast<std::size_t>(width) * height);
  for (std::size_t k = 0; k < grid.size(); ++k) grid[k] = feature[k] ? 0.0 : far;
  const int n = std::max(width, height);
  std::vector<double> f, d;
  std::vector<int> v(static_cast<std::size_t>(n));
  std::vector<double> z(static_cast<std::size_t>(n) + 1);
  f.reserve(n);
  d.reserve(n);
  // Columns, then rows.
  f.resize(height);
  d.resize(height);
  for (int x = 0; x < width; ++x) {
    for (int y = 0; y < height; ++y) f[y] = grid[static_cast<std::size_t>(y) * width + x];
    distance_transform_1d(f, d, v, z);
    for (int y = 0; y < height; ++y) grid[static_cast<std::size_t>(y) * width + x] = d[y];
  }
  f.resize(width);
  d.resize(width);
  for (int y = 0; y < height; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * width;
    std::copy(grid.begin() + static_cast<std::ptrdiff_t>(row), grid.begin() + static_cast<std::ptrdiff_t>(row + width),
              f.begin());
    distance_transform_1d(f, d, v, z);
    std::copy(d.begin(), d.end(), grid.begin() + static_cast<std::ptrdiff_t>(row));
  }
  std::vector<float> out(grid.size());
  for (std::size_t k = 0; k < grid.size(); ++k)
    out[k] = grid[k] >= far * 0.5 ? std::numeric_limits<float>::infinity() : static_cast<float>(std::sqrt(grid[k]));
  return out;
}

}  // namespace

AutoBlend::AutoBlend(const ViewportConfig& config) : config_(config), outputs_(config.outputs.size()) {
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    const OutputConfig& oc = config.outputs[i];
    Output& o = outputs_[i];
    o.config = &oc;
    o.participates = oc.blend.mode == BlendMode::automatic;
    if (!o.participates) continue;
    if (oc.warp_error) config.require_renderable(i);  // a broken warp has no coverage to blend with
    o.ramp_px = std::max(1.0, oc.blend.width_fraction * std::min(oc.width_px, oc.height_px));
    // Pixels without a ray (a fisheye's corners, unmapped parts of a mesh)
    // bound the coverage like the image border does.
    const int w = oc.width_px, h = oc.height_px;
    std::vector<bool> no_ray(static_cast<std::size_t>(w) * h);
    bool any = false;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const bool missing = !oc.projection->ray(x + 0.5, y + 0.5).has_value();
        no_ray[static_cast<std::size_t>(y) * w + x] = missing;
        any = any || missing;
      }
    if (!any) continue;
    o.ray_border_px = distance_transform(no_ray, w, h);
    for (float& dist : o.ray_border_px) dist = std::max(0.0f, dist - 0.5f);
  }
}

double AutoBlend::border_distance_px(std::size_t output, double x_px, double y_px) const {
  const Output& o = outputs_[output];
  const int w = o.config->width_px, h = o.config->height_px;
  const double rect = std::min(std::min(x_px, w - x_px), std::min(y_px, h - y_px));
  if (!(rect > 0.0)) return 0.0;  // outside, or NaN
  if (o.ray_border_px.empty()) return rect;
  // Bilinear between pixel centres, clamped at the image's edge.
  const double fx = std::clamp(x_px - 0.5, 0.0, double(w - 1)), fy = std::clamp(y_px - 0.5, 0.0, double(h - 1));
  const int x0 = std::min(static_cast<int>(fx), std::max(w - 2, 0)),
            y0 = std::min(static_cast<int>(fy), std::max(h - 2, 0));
  const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
  const double tx = fx - x0, ty = fy - y0;
  auto at = [&](int x, int y) { return double(o.ray_border_px[static_cast<std::size_t>(y) * w + x]); };
  auto lerp = [](double a, double b, double t) {
    // Infinity (no ray-less pixel in reach) must not turn into NaN.
    if (std::isinf(a) || std::isinf(b)) return t <= 0.0 ? a : t >= 1.0 ? b : std::max(a, b);
    return a + (b - a) * t;
  };
  const double field = lerp(lerp(at(x0, y0), at(x1, y0), tx), lerp(at(x0, y1), at(x1, y1), tx), ty);
  return std::min(rect, field);
}

double AutoBlend::raw_weight_at(std::size_t output, double x_px, double y_px) const {
  const Output& o = outputs_[output];
  if (!o.participates) return 0.0;
  return smoothstep(border_distance_px(output, x_px, y_px) / o.ramp_px);
}

double AutoBlend::raw_weight(std::size_t output, const glm::dvec3& direction) const {
  if (!outputs_[output].participates) return 0.0;
  const std::optional<glm::dvec2> p = outputs_[output].config->projection->pixel(direction);
  if (!p) return 0.0;
  return raw_weight_at(output, p->x, p->y);
}

double AutoBlend::weights(const glm::dvec3& direction, std::span<double> weights) const {
  if (weights.size() != outputs_.size())
    throw std::invalid_argument(
        cat("AutoBlend::weights: ", weights.size(), " values for ", outputs_.size(), " outputs"));
  double sum = 0.0;
  for (std::size_t j = 0; j < outputs_.size(); ++j) {
    weights[j] = raw_weight(j, direction);
    sum += weights[j];
  }
  for (double& w : weights) w = sum > 0.0 ? w / sum : 0.0;
  return sum;
}

BlendMask AutoBlend::mask(std::size_t output) const {
  if (output >= outputs_.size() || !outputs_[output].participates)
    throw std::invalid_argument(cat(config_.source, ": output ", output, " has no automatic blend"));
  const OutputConfig& oc = *outputs_[output].config;
  BlendMask mask{oc.width_px, oc.height_px, std::vector<float>(static_cast<std::size_t>(oc.width_px) * oc.height_px)};
  for (int y = 0; y < oc.height_px; ++y)
    for (int x = 0; x < oc.width_px; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const std::optional<glm::dvec3> d = oc.projection->ray(px, py);
      if (!d) continue;
      // The own weight from the pixel position itself (no round trip through pixel()).
      const double own = raw_weight_at(output, px, py);
      if (own <= 0.0) continue;
      double sum = own;
      for (std::size_t j = 0; j < outputs_.size(); ++j)
        if (j != output) sum += raw_weight(j, *d);
      mask.alpha[static_cast<std::size_t>(y) * oc.width_px + x] = static_cast<float>(own / sum);
    }
  return mask;
}

BlendMask compute_auto_blend(const ViewportConfig& config, std::size_t output_index) {
  return AutoBlend(config).mask(output_index);
}

BlendMask load_blend_mask(const std::filesystem::path& path, double gamma, int width_px, int height_px) {
  const BlendMap map = decode_png_map(core::file_bytes(path), path.string());
  if (map.width != width_px || map.height != height_px)
    throw std::runtime_error(cat(path.string(), ": blend mask is ", map.width, "x", map.height, " px, the output ",
                                 width_px, "x", height_px));
  BlendMask mask{width_px, height_px, std::vector<float>(static_cast<std::size_t>(width_px) * height_px)};
  for (int y = 0; y < height_px; ++y)
    for (int x = 0; x < width_px; ++x)
      mask.alpha[static_cast<std::size_t>(y) * width_px + x] =
          static_cast<float>(std::pow(double(map.at(x, y, 0)), gamma));
  return mask;
}

BlendMask output_blend_mask(const ViewportConfig& config, std::size_t output_index) {
  const OutputConfig& oc = config.outputs.at(output_index);
  config.require_renderable(output_index);
  BlendMask mask;
  switch (oc.blend.mode) {
    case BlendMode::none:
      mask = {oc.width_px, oc.height_px,
              std::vector<float>(static_cast<std::size_t>(oc.width_px) * oc.height_px, 1.0f)};
      break;
    case BlendMode::automatic: mask = compute_auto_blend(config, output_index); break;
    case BlendMode::file: mask = load_blend_mask(oc.blend.file, oc.blend.gamma, oc.width_px, oc.height_px); break;
    case BlendMode::mpcdi:
      if (!oc.blend.alpha_map)
        throw std::invalid_argument(cat(config.source, ": output '", oc.name, "': blend \"mpcdi\" without a map"));
      mask = {oc.width_px, oc.height_px, sample_mpcdi_blend_map(*oc.blend.alpha_map, oc.width_px, oc.height_px)};
      if (oc.blend.beta_map) mask.beta = sample_mpcdi_blend_map(*oc.blend.beta_map, oc.width_px, oc.height_px);
      break;
  }
  if (const auto* warped = dynamic_cast<const WarpedProjection*>(oc.projection.get())) {
    for (int y = 0; y < oc.height_px; ++y)
      for (int x = 0; x < oc.width_px; ++x)
        mask.alpha[static_cast<std::size_t>(y) * oc.width_px + x] *=
            static_cast<float>(warped->intensity(x + 0.5, y + 0.5));
  }
  return mask;
}

std::vector<float> black_level_map(const OutputConfig& output, const BlendMask& mask) {
  if (!mask.beta.empty()) return mask.beta;
  return std::vector<float>(static_cast<std::size_t>(output.width_px) * static_cast<std::size_t>(output.height_px),
                            static_cast<float>(output.black_level));
}

void apply_blend(std::span<float> rgb, int first_row, int row_count, const BlendMask& mask, double black_level) {
  if (first_row < 0 || row_count < 0 || first_row + row_count > mask.height ||
      rgb.size() != static_cast<std::size_t>(row_count) * mask.width * 3)
    throw std::invalid_argument(cat("apply_blend: rows ", first_row, "+", row_count, " (", rgb.size(),
                                    " floats) do not fit a ", mask.width, "x", mask.height, " mask"));
  for (int r = 0; r < row_count; ++r)
    for (int x = 0; x < mask.width; ++x) {
      const double alpha = mask.at(x, first_row + r);
      const double beta = mask.black_level_at(x, first_row + r, black_level);
      float* p = &rgb[(static_cast<std::size_t>(r) * mask.width + x) * 3];
      for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(blend_display_value(p[c], alpha, beta));
    }
}

}  // namespace zenith::warp
