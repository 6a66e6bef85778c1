#include "render/night/moon_albedo_map.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/units.h"
#include "image/image_io.h"
#include "image/tone_mapping.h"

namespace zenith::render {
namespace {

constexpr int kCoarseBox = 4;       // the coarse copy: 4 × 4 texels of the full map per texel
constexpr int kDiscGrid = 96;       // moon_disc_mean_albedo's samples across the disc
constexpr int kNearSideGrid = 256;  // the near side's mean at load

/// Bilinear lookup of an equirectangular grid (longitude wraps, latitude clamps).
double bilinear(const std::vector<float>& t, int w, int h, double longitude_rad, double latitude_rad) {
  const double x = (longitude_rad / (2.0 * core::kPi) + 0.5) * w - 0.5;
  const double y = std::clamp((0.5 - latitude_rad / core::kPi) * h - 0.5, 0.0, h - 1.0);
  const double fx = std::floor(x), fy = std::floor(y);
  const double ax = x - fx, ay = y - fy;
  const int x0 = ((static_cast<int>(fx) % w) + w) % w, x1 = (x0 + 1) % w;
  const int y0 = static_cast<int>(fy), y1 = std::min(y0 + 1, h - 1);
  const auto at = [&](int i, int j) { return double(t[static_cast<std::size_t>(j) * w + i]); };
  return (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x1, y0)) + ay * ((1 - ax) * at(x0, y1) + ax * at(x1, y1));
}

}  // namespace

MoonAlbedoMap MoonAlbedoMap::uniform() { return MoonAlbedoMap{}; }

MoonAlbedoMap MoonAlbedoMap::load(const std::filesystem::path& path) {
  const image::LinearImage image = image::read_image(path);  // throws "<path>: …"
  if (image.width != 2 * image.height || image.width % kCoarseBox != 0)
    throw std::runtime_error(
        fmt::format("{}: the Moon's map is {} × {} px; an equirectangular map is twice as wide as "
                    "high, a multiple of {} px wide",
                    path.string(), image.width, image.height, 2 * kCoarseBox));
  MoonAlbedoMap m;
  m.width_ = image.width;
  m.height_ = image.height;
  m.texels_.resize(static_cast<std::size_t>(m.width_) * m.height_);
  // The file's code values / 255 (read_image decoded them as sRGB), as linear albedo.
  for (std::size_t i = 0; i < m.texels_.size(); ++i)
    m.texels_[i] = 0.2126f * image::srgb_encode(image.rgb[3 * i]) + 0.7152f * image::srgb_encode(image.rgb[3 * i + 1]) +
                   0.0722f * image::srgb_encode(image.rgb[3 * i + 2]);
  // The coarse copy: box means.
  m.coarse_width_ = m.width_ / kCoarseBox;
  m.coarse_height_ = m.height_ / kCoarseBox;
  m.coarse_.assign(static_cast<std::size_t>(m.coarse_width_) * m.coarse_height_, 0.0f);
  for (int y = 0; y < m.height_; ++y)
    for (int x = 0; x < m.width_; ++x)
      m.coarse_[static_cast<std::size_t>(y / kCoarseBox) * m.coarse_width_ + x / kCoarseBox] +=
          m.texels_[static_cast<std::size_t>(y) * m.width_ + x] / float(kCoarseBox * kCoarseBox);
  // The near side's photometric mean at full Moon without libration: a uniform
  // grid over the projected disc (dA⊥ = μ dA) centred on (0°, 0°).
  double sum = 0.0, count = 0.0;
  for (int j = 0; j < kNearSideGrid; ++j)
    for (int i = 0; i < kNearSideGrid; ++i) {
      const double u = 2.0 * (i + 0.5) / kNearSideGrid - 1.0, v = 2.0 * (j + 0.5) / kNearSideGrid - 1.0;
      if (u * u + v * v >= 1.0) continue;
      const double mu = std::sqrt(1.0 - u * u - v * v);  // x: toward the observer, u: east, v: north
      sum += m.coarse_at(std::atan2(u, mu), std::asin(v));
      count += 1.0;
    }
  const double mean = sum / count;
  if (!(mean > 0.0) || !std::isfinite(mean))
    throw std::runtime_error(fmt::format("{}: the Moon's map is black on the near side", path.string()));
  const float scale = static_cast<float>(1.0 / mean);
  for (float& t : m.texels_) t *= scale;
  for (float& t : m.coarse_) t *= scale;
  m.largest_ = *std::max_element(m.texels_.begin(), m.texels_.end());
  m.identity_sha256_ = astro::moon_map_identity(path);
  return m;
}

double MoonAlbedoMap::coarse_at(double longitude_rad, double latitude_rad) const {
  return bilinear(coarse_, coarse_width_, coarse_height_, longitude_rad, latitude_rad);
}

double moon_disc_mean_albedo(const MoonAlbedoMap& map, const MoonWorldAxes& axes, const glm::dvec3& toward_moon,
                             const glm::dvec3& toward_sun) {
  if (map.is_uniform()) return 1.0;
  // The disc's plane: two unit vectors across the line of sight.
  const glm::dvec3 helper = std::abs(toward_moon.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  const glm::dvec3 a = glm::normalize(glm::cross(toward_moon, helper)), b = glm::cross(toward_moon, a);
  double weighted = 0.0, weights = 0.0;
  for (int j = 0; j < kDiscGrid; ++j)
    for (int i = 0; i < kDiscGrid; ++i) {
      const double u = 2.0 * (i + 0.5) / kDiscGrid - 1.0, v = 2.0 * (j + 0.5) / kDiscGrid - 1.0;
      if (u * u + v * v >= 1.0) continue;
      const double mu = std::sqrt(1.0 - u * u - v * v);
      const glm::dvec3 n = -toward_moon * mu + a * u + b * v;
      const double mu0 = glm::dot(n, toward_sun);
      if (mu0 <= 0.0) continue;
      const double w = mu0 / (mu0 + mu);
      const double longitude = std::atan2(glm::dot(n, axes[1]), glm::dot(n, axes[0]));
      const double latitude = std::asin(std::clamp(glm::dot(n, axes[2]), -1.0, 1.0));
      weighted += w * map.coarse_at(longitude, latitude);
      weights += w;
    }
  return weights > 0.0 ? weighted / weights : 1.0;
}

}  // namespace zenith::render
