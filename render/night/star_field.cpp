#include "render/night/star_field.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "astro/scintillation.h"
#include "astro/star_photometry.h"
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
    for (std::size_t i = 0; i < places.size(); ++i) epoch_enu_[i] = places[i].east_north_up();
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

}  // namespace zenith::render
