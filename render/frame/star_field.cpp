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
#include "core/units.h"

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
  constexpr double kMasToRad = core::kDeg / (3600.0 * 1000.0);
  for (const astro::CatalogueStar& s : catalogue_.stars)
    largest_proper_motion_rad_yr_ =
        std::max(largest_proper_motion_rad_yr_, std::hypot(s.pm_ra_cosdec_mas_yr, s.pm_dec_mas_yr) * kMasToRad);
}

double StarField::largest_scintillation_normal(std::int64_t interval) {
  if (have_normal_ && normal_interval_ == interval) return largest_normal_;
  // Every star's deviate for the interval, on the worker threads (each a fixed
  // function of its index): kept for the pass's twinkle (scintillation_normals).
  const std::size_t count = catalogue_.stars.size();
  normals_.resize(count);
  constexpr std::size_t kChunk = 8192;
  core::parallel_for((count + kChunk - 1) / kChunk, 0, [&](std::size_t chunk) {
    for (std::size_t i = chunk * kChunk; i < std::min(count, (chunk + 1) * kChunk); ++i)
      normals_[i] = astro::scintillation_normal(i, interval);
  });
  double largest = -astro::kLargestScintillationNormal;
  for (double g : normals_) largest = std::max(largest, g);
  have_normal_ = true;
  normal_interval_ = interval;
  largest_normal_ = largest;
  return largest;
}

const std::vector<double>* StarField::scintillation_normals(std::int64_t interval) const {
  return have_normal_ && normal_interval_ == interval ? &normals_ : nullptr;
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
  const double radius = std::min(std::exp2(step / 4.0), 0.5 * core::kPi);
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
  const double phi = site.latitude_deg * core::kDeg;
  const glm::dvec3 pole(0.0, std::cos(phi), std::sin(phi));
  // Two-part difference: the day parts cancel in double without losing the seconds.
  const double dt_s = ((time.ut1().day1 - epoch_ut1_jd_) + time.ut1().day2) * 86400.0;
  const double angle = -kEarthRotationRate_rad_s * dt_s;
  out.resize(std::min(count, epoch_enu_.size()));
  const double c = std::cos(angle), s = std::sin(angle);
  // On the worker threads in chunks (0.7–0.9 ms for 101 922 stars on one of
  // this project's VM's cores, every frame of a show).
  constexpr std::size_t kChunk = 16384;
  core::parallel_for((out.size() + kChunk - 1) / kChunk, 0, [&](std::size_t chunk) {
    for (std::size_t i = chunk * kChunk; i < std::min(out.size(), (chunk + 1) * kChunk); ++i) {
      const glm::dvec3& v = epoch_enu_[i];
      out[i] = v * c + glm::cross(pole, v) * s + pole * (glm::dot(pole, v) * (1.0 - c));
    }
  });
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

/// The twinkle's s = √ln(1 + σ_I²) at μ = sin e (TwinkleSigmaTable's formula).
double twinkle_log_sigma(double per_cubed_air_mass, double mu) {
  const double elevation_deg = std::asin(std::clamp(mu, 0.0, 1.0)) * core::kRadToDeg;
  return astro::scintillation_log_sigma(
      astro::scintillation_variance_at(per_cubed_air_mass, atmosphere::pickering_air_mass(elevation_deg)));
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

CameraTransmittance::CameraTransmittance(const StarAtmosphere& a, const glm::dvec3& camera_m)
    : geometry_(a.transmittance->geometry),
      p_(camera_m - a.centre_m),
      ground_(a.ground_radius_m),
      top_(a.top_radius_m),
      r_(glm::length(camera_m - a.centre_m)) {
  const atmosphere::lut::LookupTables& t = *a.transmittance;
  const atmosphere::lut::ShellGeometry& g = geometry_;
  // The radius every ray is read at (star_transmittance), its row weight and the ends of its u_μ.
  r_at_ = r_ > a.top_radius_m ? a.top_radius_m : std::clamp(r_, a.ground_radius_m, a.top_radius_m);
  const atmosphere::lut::TransmittanceUV uv = atmosphere::lut::transmittance_uv(g, t.sizes, r_at_, 1.0);
  d_min_ = g.top_radius_m - r_at_;
  d_max_ = g.horizon_distance_m(r_at_) + g.horizon_distance_at_top_m();
  width_ = t.transmittance.width;
  channels_ = t.channels;
  // GL_LINEAR with GL_CLAMP_TO_EDGE across the rows (atmosphere/lut/table.h).
  const double y = uv.v_r * double(t.transmittance.height) - 0.5, fy = std::floor(y);
  const auto last = static_cast<std::ptrdiff_t>(t.transmittance.height) - 1;
  const auto y0 = static_cast<std::size_t>(std::clamp(static_cast<std::ptrdiff_t>(fy), std::ptrdiff_t{0}, last));
  const auto y1 = static_cast<std::size_t>(std::clamp(static_cast<std::ptrdiff_t>(fy) + 1, std::ptrdiff_t{0}, last));
  const double wy = y - fy;
  row_.resize(width_ * channels_);
  for (std::size_t x = 0; x < width_; ++x)
    for (std::size_t c = 0; c < channels_; ++c)
      row_[x * channels_ + c] =
          (1.0 - wy) * double(t.transmittance.texel(x, y0)[c]) + wy * double(t.transmittance.texel(x, y1)[c]);
}

void CameraTransmittance::operator()(const glm::dvec3& d, double* out) const {
  const double mu = glm::dot(p_, d) / r_;
  const double b = r_ * mu;                                // p·d
  const double closest2 = std::max(0.0, r_ * r_ - b * b);  // squared distance of the line from the centre
  std::fill(out, out + channels_, 1.0);
  if (b < 0.0 && closest2 < ground_ * ground_) {  // the ground hides it
    std::fill(out, out + channels_, 0.0);
    return;
  }
  double mu_at = mu;
  if (r_ > top_) {
    if (b >= 0.0 || closest2 >= top_ * top_) return;  // misses the shell
    const double t_in = -b - std::sqrt(top_ * top_ - closest2);
    mu_at = std::clamp((b + t_in) / top_, -1.0, 1.0);
  }
  const double to_top = geometry_.distance_to_top_m(r_at_, mu_at);
  const double x_mu = d_max_ > d_min_ ? (to_top - d_min_) / (d_max_ - d_min_) : 0.0;
  const double u = atmosphere::lut::texture_coord_from_unit(std::clamp(x_mu, 0.0, 1.0), width_);
  const double x = u * double(width_) - 0.5, fx = std::floor(x), wx = x - fx;
  const auto last = static_cast<std::ptrdiff_t>(width_) - 1;
  const double* t0 =
      &row_[static_cast<std::size_t>(std::clamp(static_cast<std::ptrdiff_t>(fx), std::ptrdiff_t{0}, last)) * channels_];
  const double* t1 =
      &row_[static_cast<std::size_t>(std::clamp(static_cast<std::ptrdiff_t>(fx) + 1, std::ptrdiff_t{0}, last)) *
            channels_];
  for (std::size_t c = 0; c < channels_; ++c) out[c] = std::clamp((1.0 - wx) * t0[c] + wx * t1[c], 0.0, 1.0);
}

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

TwinkleSigmaTable::TwinkleSigmaTable(double per_cubed_air_mass) : per_cubed_air_mass_(per_cubed_air_mass) {
  // Where σ_I² reaches its cap of 1 (X falls as μ rises): s is √ln 2 below, smooth above.
  const auto capped = [&](double mu) {
    const double elevation_deg = std::asin(mu) * core::kRadToDeg;
    const double x = atmosphere::pickering_air_mass(elevation_deg);
    return per_cubed_air_mass_ * (x * x * x) >= 1.0;
  };
  if (capped(1.0)) {
    mu_cap_ = 1.0;
  } else if (capped(0.0)) {
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < 64; ++k) (capped(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
    mu_cap_ = hi;
  }
  s_cap_ = astro::scintillation_log_sigma(1.0);
  span_ = 1.0 - mu_cap_;
  s_.resize(kNodes + 1);
  for (std::size_t j = 0; j <= kNodes; ++j) {
    const double t = double(j) / double(kNodes);
    s_[j] = exact(mu_cap_ + span_ * t * t);
  }
  std::vector<double> second(kNodes + 1, 0.0);
  for (std::size_t j = 1; j < kNodes; ++j) second[j] = std::abs(s_[j - 1] - 2.0 * s_[j] + s_[j + 1]);
  second[0] = second[1];
  second[kNodes] = second[kNodes - 1];
  bound_.resize(kNodes);
  for (std::size_t j = 0; j < kNodes; ++j) {
    bound_[j] = 2.0 * 0.25 * (second[j] + second[j + 1]) + 1e-15;
    largest_bound_ = std::max(largest_bound_, bound_[j]);
  }
}

double TwinkleSigmaTable::exact(double mu) const { return twinkle_log_sigma(per_cubed_air_mass_, mu); }

double TwinkleSigmaTable::operator()(double mu) const {
  if (mu_cap_ > 0.0 && !(mu > mu_cap_)) return s_cap_;
  const double x = std::sqrt((std::clamp(mu, mu_cap_, 1.0) - mu_cap_) / span_) * double(kNodes);
  const std::size_t j = std::min(static_cast<std::size_t>(x), kNodes - 1);
  const double f = x - double(j);
  return s_[j] + (s_[j + 1] - s_[j]) * f;
}

double TwinkleSigmaTable::bound_at(double mu) const {
  if (mu_cap_ > 0.0 && !(mu > mu_cap_)) return 1e-15;
  const double x = std::sqrt((std::clamp(mu, mu_cap_, 1.0) - mu_cap_) / span_) * double(kNodes);
  return bound_[std::min(static_cast<std::size_t>(x), kNodes - 1)];
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
