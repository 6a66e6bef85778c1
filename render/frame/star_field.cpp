#include "render/frame/star_field.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "astro/scintillation.h"
#include "astro/star_photometry.h"
#include "atmosphere/air_mass.h"
#include "atmosphere/lut/parameterization.h"
#include "core/parallel_for.h"

namespace zenith::render {

StarField::StarField(astro::StarCatalogue catalogue, const std::vector<double>& wavelengths_nm)
    : catalogue_(std::move(catalogue)), wavelengths_nm_(wavelengths_nm) {
  if (wavelengths_nm_.empty()) throw std::invalid_argument("StarField: no wavelengths");
  const std::size_t n = wavelengths_nm_.size();
  irradiance_.resize(catalogue_.stars.size() * n);
  for (std::size_t i = 0; i < catalogue_.stars.size(); ++i) {
    const astro::CatalogueStar& s = catalogue_.stars[i];
    astro::star_irradiance_W_m2_nm(s.v_mag, s.b_minus_v, wavelengths_nm_, std::span<double>(&irradiance_[i * n], n));
  }
  if (!irradiance_.empty()) brightest_ = *std::max_element(irradiance_.begin(), irradiance_.end());
  constexpr double kMasToRad = 3.14159265358979323846 / (180.0 * 3600.0 * 1000.0);
  for (const astro::CatalogueStar& s : catalogue_.stars)
    largest_proper_motion_rad_yr_ =
        std::max(largest_proper_motion_rad_yr_, std::hypot(s.pm_ra_cosdec_mas_yr, s.pm_dec_mas_yr) * kMasToRad);
}

double StarField::largest_scintillation_normal(std::int64_t interval) {
  if (have_normal_ && normal_interval_ == interval) return largest_normal_;
  double largest = -astro::kLargestScintillationNormal;
  for (std::size_t i = 0; i < catalogue_.stars.size(); ++i)
    largest = std::max(largest, astro::scintillation_normal(i, interval));
  have_normal_ = true;
  normal_interval_ = interval;
  largest_normal_ = largest;
  return largest;
}

int StarField::radius_step(double radius_rad, double years_from_j2000) const {
  const double widened = radius_rad + 2.0 * largest_proper_motion_rad_yr_ * std::abs(years_from_j2000);
  return static_cast<int>(std::ceil(4.0 * std::log2(std::max(widened, 1e-9))));
}

const std::vector<double>& StarField::neighbourhood_irradiance(double radius_rad, double years_from_j2000,
                                                               std::size_t first) {
  const int step = radius_step(radius_rad, years_from_j2000);
  const auto cached = neighbourhoods_.find({step, first});
  if (cached != neighbourhoods_.end()) return cached->second;
  const double radius = std::min(std::exp2(step / 4.0), 0.5 * 3.14159265358979323846);
  // Candidates from a grid of cubes of side the chord of 2 · radius (every
  // star within it lies in the 27 cubes around a star's cube), then the chord
  // itself. One pass fills the tables of every first star of
  // kNeighbourhoodFirsts (or of `first` alone): a pair's light goes to its
  // bucket between two of them, and each table is the sum of the buckets from its own.
  std::vector<std::size_t> firsts(kNeighbourhoodFirsts.begin(), kNeighbourhoodFirsts.end());
  if (std::find(firsts.begin(), firsts.end(), first) == firsts.end()) firsts = {first};
  const std::size_t buckets = firsts.size();
  const double reach = 2.0 * std::sin(radius);
  const std::size_t n = wavelengths_nm_.size();
  const std::size_t count = catalogue_.stars.size();
  std::vector<glm::dvec3> d(count);
  std::vector<std::size_t> bucket(count, buckets);  // buckets: before the first table's first star
  for (std::size_t i = 0; i < count; ++i) {
    const astro::CatalogueStar& s = catalogue_.stars[i];
    d[i] = {std::cos(s.dec_rad) * std::cos(s.ra_rad), std::cos(s.dec_rad) * std::sin(s.ra_rad), std::sin(s.dec_rad)};
    for (std::size_t b = buckets; b-- > 0;)
      if (i >= firsts[b]) {
        bucket[i] = b;
        break;
      }
  }
  std::map<std::array<std::int64_t, 3>, std::vector<std::size_t>> cubes;
  for (std::size_t i = 0; i < count; ++i)
    cubes[{static_cast<std::int64_t>(std::floor(d[i].x / reach)), static_cast<std::int64_t>(std::floor(d[i].y / reach)),
           static_cast<std::int64_t>(std::floor(d[i].z / reach))}]
        .push_back(i);
  std::vector<const std::pair<const std::array<std::int64_t, 3>, std::vector<std::size_t>>*> list;
  for (const auto& entry : cubes) list.push_back(&entry);
  std::vector<std::vector<double>> tables(buckets, std::vector<double>(count * n, 0.0));
  const double reach2 = reach * reach;
  core::parallel_for(list.size(), 0, [&](std::size_t c) {
    const auto& [centre, members] = *list[c];
    std::vector<std::size_t> near;  // the 27 cubes' stars
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          const auto it = cubes.find({centre[0] + dx, centre[1] + dy, centre[2] + dz});
          if (it != cubes.end()) near.insert(near.end(), it->second.begin(), it->second.end());
        }
    for (std::size_t i : members) {  // each star's rows are its own: no two workers write one
      for (std::size_t j : near) {
        if (bucket[j] == buckets) continue;
        const glm::dvec3 e = d[i] - d[j];
        if (glm::dot(e, e) > reach2) continue;
        for (std::size_t k = 0; k < n; ++k) tables[bucket[j]][i * n + k] += irradiance(j, k);
      }
      for (std::size_t b = buckets - 1; b-- > 0;)
        for (std::size_t k = 0; k < n; ++k) tables[b][i * n + k] += tables[b + 1][i * n + k];
    }
  });
  for (std::size_t b = 0; b < buckets; ++b) neighbourhoods_[{step, firsts[b]}] = std::move(tables[b]);
  return neighbourhoods_.at({step, first});
}

const std::vector<double>& StarField::brightest_cluster_irradiance(double radius_rad, double years_from_j2000,
                                                                   std::size_t first) {
  const int step = radius_step(radius_rad, years_from_j2000);
  const auto cached = clusters_.find({step, first});
  if (cached != clusters_.end()) return cached->second;
  const std::vector<double>& sums = neighbourhood_irradiance(radius_rad, years_from_j2000, first);
  const std::size_t n = wavelengths_nm_.size();
  std::vector<double> brightest(n, 0.0);
  for (std::size_t i = first * n; i < sums.size(); ++i) brightest[i % n] = std::max(brightest[i % n], sums[i]);
  return clusters_[{step, first}] = brightest;
}

glm::dvec3 rotate_about(const glm::dvec3& v, const glm::dvec3& axis, double angle_rad) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0 - c));
}

void StarField::directions_enu(const astro::AstroTime& time, const astro::Site& site, std::vector<glm::dvec3>& out,
                               std::size_t count) {
  const double ut1_jd = time.ut1().value();
  const bool same_site = have_epoch_ && site.latitude_deg == epoch_site_.latitude_deg &&
                         site.longitude_deg == epoch_site_.longitude_deg && site.altitude_m == epoch_site_.altitude_m;
  if (!same_site || std::abs(ut1_jd - epoch_ut1_jd_) * 86400.0 > kStarEpochSpan_s) {
    const astro::SkyPositions sky(time, site);
    std::vector<astro::Horizontal> places;
    sky.stars(catalogue_.stars, places);
    epoch_enu_.resize(places.size());
    for (std::size_t i = 0; i < places.size(); ++i) {
      const auto enu = places[i].east_north_up();
      epoch_enu_[i] = {enu[0], enu[1], enu[2]};
    }
    epoch_ut1_jd_ = ut1_jd;
    epoch_site_ = site;
    have_epoch_ = true;
  }
  // The sky turns westward about the celestial pole, which stands at the
  // site's latitude above the northern horizon (polar motion neglected, as
  // SkyPositions does): a rotation by −ω Δt about (0, cos φ, sin φ).
  const double phi = site.latitude_deg * 3.14159265358979323846 / 180.0;
  const glm::dvec3 pole(0.0, std::cos(phi), std::sin(phi));
  // Two-part difference: the day parts cancel in double without losing the seconds.
  const double dt_s = ((time.ut1().day1 - epoch_ut1_jd_) + time.ut1().day2) * 86400.0;
  const double angle = -kEarthRotationRate_rad_s * dt_s;
  out.resize(std::min(count, epoch_enu_.size()));
  const double c = std::cos(angle), s = std::sin(angle);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const glm::dvec3& v = epoch_enu_[i];
    out[i] = v * c + glm::cross(pole, v) * s + pole * (glm::dot(pole, v) * (1.0 - c));
  }
}

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

void star_transmittance(const StarAtmosphere& a, const glm::dvec3& camera_m, const glm::dvec3& d, double* out) {
  const atmosphere::lut::LookupTables& t = *a.transmittance;
  const std::size_t n = t.channels;
  const glm::dvec3 p = camera_m - a.centre_m;
  const double r = glm::length(p);
  const double mu = glm::dot(p, d) / r;
  const double b = r * mu;                               // p·d
  const double closest2 = std::max(0.0, r * r - b * b);  // squared distance of the line from the centre
  std::fill(out, out + n, 1.0);
  if (b < 0.0 && closest2 < a.ground_radius_m * a.ground_radius_m) {  // the ground hides it
    std::fill(out, out + n, 0.0);
    return;
  }
  double r_at = r, mu_at = mu;
  if (r > a.top_radius_m) {
    if (b >= 0.0 || closest2 >= a.top_radius_m * a.top_radius_m) return;  // misses the shell
    // Where it enters the shell: the same line from there.
    const double t_in = -b - std::sqrt(a.top_radius_m * a.top_radius_m - closest2);
    r_at = a.top_radius_m;
    mu_at = std::clamp((b + t_in) / a.top_radius_m, -1.0, 1.0);
  }
  const atmosphere::lut::TransmittanceUV uv = atmosphere::lut::transmittance_uv(
      t.geometry, t.sizes, std::clamp(r_at, a.ground_radius_m, a.top_radius_m), mu_at);
  t.transmittance.sample(uv.u_mu, uv.v_r, out);
  for (std::size_t c = 0; c < n; ++c) out[c] = std::clamp(out[c], 0.0, 1.0);
}

glm::dvec2 on_splat_grid(const glm::dvec2& pixel) {
  return {std::round(pixel.x * kSplatGridPerPixel) / kSplatGridPerPixel,
          std::round(pixel.y * kSplatGridPerPixel) / kSplatGridPerPixel};
}

bool splat_touches_image(const glm::dvec2& pixel, double width, double height) {
  return pixel.x >= -0.5 && pixel.x < width + 0.5 && pixel.y >= -0.5 && pixel.y < height + 0.5;
}

double pixel_solid_angle_sr(const warp::Projection& projection, double x_px, double y_px) {
  const auto xa = projection.ray(x_px - 0.5, y_px), xb = projection.ray(x_px + 0.5, y_px);
  const auto ya = projection.ray(x_px, y_px - 0.5), yb = projection.ray(x_px, y_px + 0.5);
  if (!xa || !xb || !ya || !yb) return 0.0;
  return glm::length(glm::cross(glm::normalize(*xb) - glm::normalize(*xa), glm::normalize(*yb) - glm::normalize(*ya)));
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
        widest = std::max(widest, 0.5 * 3.14159265358979323846);  // a fisheye's circle: at least its field
        continue;
      }
      widest = std::max(widest, std::acos(std::clamp(glm::dot(glm::normalize(*r), axis), -1.0, 1.0)));
    }
  }
  const double limit = widest + margin_rad;
  return {axis, limit >= 3.14159265358979323846 ? -1.0 : std::cos(limit)};
}

std::optional<PlacedStar> place_star(const StarField& field, std::size_t i, const glm::dvec3& enu,
                                     const StarFrame& frame, std::vector<double>& transmittance,
                                     std::vector<double>& one) {
  const warp::Projection& projection = *frame.projection;
  const std::size_t n = field.wavelengths_nm().size();
  if (enu.z < frame.lowest_sin_altitude) return std::nullopt;  // under the ground
  glm::dvec3 d = enu.x * frame.east + enu.y * frame.north + enu.z * frame.up;
  if (glm::dot(d, frame.view_axis) < frame.view_cos_limit) return std::nullopt;  // outside the view
  if (frame.refraction) {
    const double true_altitude = std::asin(std::clamp(enu.z, -1.0, 1.0));
    const double apparent = frame.refraction->apparent_from_true_rad(true_altitude);
    const glm::dvec3 level = enu.x * frame.east + enu.y * frame.north;
    const double l = glm::length(level);
    if (l > 0.0) d = level / l * std::cos(apparent) + frame.up * std::sin(apparent);
  }
  d = glm::normalize(d);
  for (const auto& [centre, radius] : frame.occluders)
    if (ray_meets_sphere(frame.camera_m - centre, d, radius)) return std::nullopt;
  const auto exact = projection.pixel(frame.world_to_camera * d);
  if (!exact) return std::nullopt;
  PlacedStar s;
  s.pixel = on_splat_grid(*exact);
  s.direction = d;
  if (!splat_touches_image(s.pixel, projection.width(), projection.height())) return std::nullopt;
  transmittance.assign(n, 1.0);
  one.resize(n);
  for (const StarAtmosphere& a : frame.atmospheres) {
    star_transmittance(a, frame.camera_m, d, one.data());
    for (std::size_t k = 0; k < n; ++k) transmittance[k] *= one[k];
  }
  s.omega_sr = pixel_solid_angle_sr(projection, s.pixel.x, s.pixel.y);
  if (!(s.omega_sr > 0.0)) return std::nullopt;
  std::array<double, 3> rgb{0, 0, 0};
  for (std::size_t k = 0; k < n; ++k) {
    const double e = field.irradiance(i, k) * transmittance[k];
    for (int c = 0; c < 3; ++c)
      rgb[static_cast<std::size_t>(c)] += frame.rgb_weights[k][static_cast<std::size_t>(c)] * e;
  }
  if (rgb[0] == 0.0 && rgb[1] == 0.0 && rgb[2] == 0.0) return std::nullopt;
  if (frame.scintillation) {  // the star's intensity over this integration interval
    const double altitude_deg =
        std::asin(std::clamp(glm::dot(d, frame.up), 0.0, 1.0)) * (180.0 / 3.14159265358979323846);
    const double variance =
        astro::scintillation_variance(*frame.scintillation, atmosphere::pickering_air_mass(altitude_deg),
                                      frame.observer_altitude_m, frame.ground_refractivity);
    const double factor =
        astro::scintillation_factor(variance, astro::scintillation_normal(i, frame.scintillation_interval));
    for (double& c : rgb) c *= factor;
  }
  for (std::size_t c = 0; c < 3; ++c) s.rgb[c] = rgb[c] * frame.exposure / s.omega_sr;
  return s;
}

std::vector<StarSplat> star_splats(const StarField& field, const std::vector<glm::dvec3>& directions_enu,
                                   const StarFrame& frame) {
  const std::size_t n = field.wavelengths_nm().size();
  const std::size_t count = std::min(field.size(), directions_enu.size());
  std::vector<StarSplat> placed(count);
  std::vector<unsigned char> kept(count, 0);
  constexpr std::size_t kChunk = 4096;
  core::parallel_for((count + kChunk - 1) / kChunk, 0, [&](std::size_t chunk) {
    std::vector<double> transmittance(n), one(n);
    for (std::size_t i = chunk * kChunk; i < std::min(count, (chunk + 1) * kChunk); ++i) {
      const std::optional<PlacedStar> p = place_star(field, i, directions_enu[i], frame, transmittance, one);
      if (!p) continue;
      StarSplat& s = placed[i];
      s.x_px = static_cast<float>(p->pixel.x);
      s.y_px = static_cast<float>(p->pixel.y);
      for (std::size_t c = 0; c < 3; ++c) s.rgb[c] = static_cast<float>(p->rgb[c]);
      kept[i] = 1;
    }
  });
  std::vector<StarSplat> out;
  for (std::size_t i = 0; i < count; ++i)
    if (kept[i]) out.push_back(placed[i]);
  std::stable_sort(out.begin(), out.end(), [](const StarSplat& a, const StarSplat& b) { return a.y_px < b.y_px; });
  return out;
}

}  // namespace zenith::render
