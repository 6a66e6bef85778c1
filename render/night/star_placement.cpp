#include "render/night/star_placement.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "astro/scintillation.h"
#include "core/parallel_for.h"
#include "core/units.h"

namespace zenith::render {

namespace {

/// Distance along unit d from p (relative to the sphere's centre) to where the
/// ray enters a sphere of radius R, or a negative value where it misses it or
/// starts inside.
bool ray_meets_sphere(const glm::dvec3& p, const glm::dvec3& d, double radius_m) {
  const double b = glm::dot(p, d);
  const double c = glm::dot(p, p) - radius_m * radius_m;
  if (c <= 0.0) return true;  // inside
  if (b >= 0.0) return false;
  return b * b - c >= 0.0;
}

}  // namespace

glm::dvec2 on_splat_grid(const glm::dvec2& pixel) {
  return {std::round(pixel.x * kSplatGridPerPixel) / kSplatGridPerPixel,
          std::round(pixel.y * kSplatGridPerPixel) / kSplatGridPerPixel};
}

bool splat_touches_image(const glm::dvec2& pixel, double width, double height) {
  return pixel.x >= -0.5 && pixel.x < width + 0.5 && pixel.y >= -0.5 && pixel.y < height + 0.5;
}

std::pair<glm::dvec3, double> view_cone(const warp::Projection& projection, double margin_rad) {
  const double w = projection.width(), h = projection.height();
  const auto centre = projection.ray(0.5 * w, 0.5 * h);
  if (!centre) return {glm::dvec3(0, 0, -1), -1.0};
  const glm::dvec3 axis = glm::normalize(*centre);
  double widest = 0.0;
  constexpr int kSteps = 64;
  for (int i = 0; i <= kSteps; ++i) {
    const double t = static_cast<double>(i) / kSteps;
    for (const glm::dvec2 p : {glm::dvec2(t * w, 0.0), glm::dvec2(t * w, h), glm::dvec2(0.0, t * h),
                               glm::dvec2(w, t * h), glm::dvec2(t * w, 0.5 * h), glm::dvec2(0.5 * w, t * h)}) {
      const auto r = projection.ray(p.x, p.y);
      if (!r) {
        widest = std::max(widest, 0.5 * core::kPi);  // a fisheye's circle: at least its field
        continue;
      }
      widest = std::max(widest, std::acos(std::clamp(glm::dot(glm::normalize(*r), axis), -1.0, 1.0)));
    }
  }
  const double limit = widest + margin_rad;
  return {axis, limit >= core::kPi ? -1.0 : std::cos(limit)};
}

bool star_rejected(const glm::dvec3& enu, const StarFrame& frame) {
  if (enu.z < frame.lowest_sin_altitude) return true;  // under the ground
  const glm::dvec3 d = enu.x * frame.east + enu.y * frame.north + enu.z * frame.up;
  return glm::dot(d, frame.view_axis) < frame.view_cos_limit;  // outside the view
}

glm::dvec3 star_apparent_direction(const glm::dvec3& enu, const StarFrame& frame) {
  const glm::dvec3 level = enu.x * frame.east + enu.y * frame.north;
  if (frame.refraction) {
    // Lifted by R in its vertical: sin(h + R) = z cos R + l sin R, cos(h + R)
    // = l cos R − z sin R with z = sin h and l = cos h the level part's length.
    const double z = std::clamp(enu.z, -1.0, 1.0);
    const double h = std::asin(z);
    const double lift = frame.refraction->apparent_from_true_rad(h) - h;
    const double l = glm::length(level);
    if (l > 0.0) {
      const double c = std::cos(lift), s = std::sin(lift);
      return glm::normalize(level / l * (l * c - z * s) + frame.up * (z * c + l * s));
    }
  }
  return glm::normalize(level + enu.z * frame.up);
}

bool star_hidden(const glm::dvec3& d, const StarFrame& frame) {
  for (const auto& [centre, radius] : frame.occluders)
    if (ray_meets_sphere(frame.camera_m - centre, d, radius)) return true;
  return false;
}

std::optional<glm::dvec2> star_pixel(const glm::dvec3& d, const StarFrame& frame) {
  const warp::Projection& projection = *frame.projection;
  const auto exact = projection.pixel(frame.world_to_camera * d);
  if (!exact) return std::nullopt;
  const glm::dvec2 pixel = on_splat_grid(*exact);
  if (!splat_touches_image(pixel, projection.width(), projection.height())) return std::nullopt;
  return pixel;
}

void star_line_of_sight_transmittance(const glm::dvec3& d, const StarFrame& frame, double* out, double* scratch) {
  const std::size_t n = frame.rgb_weights.size();
  std::fill(out, out + n, 1.0);
  for (std::size_t j = 0; j < frame.atmospheres.size(); ++j) {
    if (j < frame.transmittances.size())
      frame.transmittances[j](d, scratch);
    else
      star_transmittance(frame.atmospheres[j], frame.camera_m, d, scratch);
    for (std::size_t k = 0; k < n; ++k) out[k] *= scratch[k];
  }
}

std::array<double, 3> star_colour(const StarField& field, std::size_t i, const double* transmittance,
                                  const StarFrame& frame) {
  std::array<double, 3> rgb{0, 0, 0};
  for (std::size_t k = 0; k < field.wavelengths_nm().size(); ++k) {
    const double e = field.irradiance(i, k) * transmittance[k];
    for (std::size_t c = 0; c < 3; ++c) rgb[c] += frame.rgb_weights[k][c] * e;
  }
  return rgb;
}

void StarFrame::set_twinkling(const astro::ScintillationOptions& options, std::int64_t interval,
                              double observer_altitude, double refractivity) {
  scintillation = &options;
  scintillation_interval = interval;
  observer_altitude_m = observer_altitude;
  ground_refractivity = refractivity;
  scintillation_per_cubed_air_mass =
      astro::scintillation_variance_per_cubed_air_mass(options, observer_altitude, refractivity);
  twinkle_sigma.emplace(scintillation_per_cubed_air_mass);
}

double star_twinkle(std::size_t i, const glm::dvec3& d, const StarFrame& frame) {
  if (!frame.scintillation) return 1.0;
  const double g = frame.scintillation_normals ? (*frame.scintillation_normals)[i]
                                               : astro::scintillation_normal(i, frame.scintillation_interval);
  const double mu = glm::dot(d, frame.up);
  return astro::scintillation_factor_of_log_sigma(
      frame.twinkle_sigma ? (*frame.twinkle_sigma)(mu) : twinkle_log_sigma(frame.scintillation_per_cubed_air_mass, mu),
      g);
}

std::optional<PlacedStar> place_star(const StarField& field, std::size_t i, const glm::dvec3& enu,
                                     const StarFrame& frame, std::vector<double>& transmittance,
                                     std::vector<double>& one) {
  if (star_rejected(enu, frame)) return std::nullopt;
  const glm::dvec3 d = star_apparent_direction(enu, frame);
  if (star_hidden(d, frame)) return std::nullopt;
  const std::optional<glm::dvec2> pixel = star_pixel(d, frame);
  if (!pixel) return std::nullopt;
  PlacedStar s;
  s.pixel = *pixel;
  s.direction = d;
  const std::size_t n = field.wavelengths_nm().size();
  transmittance.resize(n);
  one.resize(n);
  star_line_of_sight_transmittance(d, frame, transmittance.data(), one.data());
  s.omega_sr = frame.closed_form_solid_angle ? frame.projection->pixel_solid_angle_sr(s.pixel.x, s.pixel.y)
                                             : frame.projection->pixel_solid_angle_by_rays_sr(s.pixel.x, s.pixel.y);
  if (!(s.omega_sr > 0.0)) return std::nullopt;
  std::array<double, 3> rgb = star_colour(field, i, transmittance.data(), frame);
  if (rgb[0] == 0.0 && rgb[1] == 0.0 && rgb[2] == 0.0) return std::nullopt;
  const double factor = star_twinkle(i, d, frame);  // the star's intensity over this integration interval
  for (std::size_t c = 0; c < 3; ++c) s.rgb[c] = rgb[c] * factor * frame.exposure / s.omega_sr;
  return s;
}

std::vector<StarSplat> star_splats(const StarField& field, const std::vector<glm::dvec3>& directions_enu,
                                   const StarFrame& frame) {
  const std::size_t n = field.wavelengths_nm().size();
  const std::size_t count = std::min(field.size(), directions_enu.size());
  // Each chunk's splats in catalogue order, joined in chunk order: the same
  // list on every node and run, without a slot per catalogue star (2 MB a
  // frame for 101 922 stars, of which a view keeps a few per cent).
  constexpr std::size_t kChunk = 4096;
  std::vector<std::vector<StarSplat>> chunks((count + kChunk - 1) / kChunk);
  core::parallel_for(chunks.size(), 0, [&](std::size_t chunk) {
    std::vector<double> transmittance(n), one(n);
    for (std::size_t i = chunk * kChunk; i < std::min(count, (chunk + 1) * kChunk); ++i) {
      const std::optional<PlacedStar> p = place_star(field, i, directions_enu[i], frame, transmittance, one);
      if (!p) continue;
      StarSplat s;
      s.x_px = static_cast<float>(p->pixel.x);
      s.y_px = static_cast<float>(p->pixel.y);
      for (std::size_t c = 0; c < 3; ++c) s.rgb[c] = static_cast<float>(p->rgb[c]);
      chunks[chunk].push_back(s);
    }
  });
  std::vector<StarSplat> out;
  for (const std::vector<StarSplat>& c : chunks) out.insert(out.end(), c.begin(), c.end());
  std::stable_sort(out.begin(), out.end(), [](const StarSplat& a, const StarSplat& b) { return a.y_px < b.y_px; });
  return out;
}

}  // namespace zenith::render
