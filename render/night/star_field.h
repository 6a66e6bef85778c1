#pragma once
// The catalogue's stars at a scene's wavelengths (docs/night-sky.md,
// "Rendering the night sky"): their fluxes above the atmosphere
// (astro/star_photometry.h), their geometric directions by date and place
// (ERFA's places at an epoch, turned by the Earth's rotation since), the most
// light neighbouring stars can put into one pixel, and their twinkle's draws
// per interval. No GL: render/night/star_placement.h places them in a frame.
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "astro/civil_time.h"
#include "astro/sky_positions.h"
#include "astro/star_catalogue.h"
#include "core/units.h"

namespace zenith::render {

/// How far the sky clock may move from the epoch of the stars' ERFA places
/// before they are recomputed [s]: over 6 hours precession, nutation and
/// aberration move a star by < 0.2″ about the rotation's pole.
inline constexpr double kStarEpochSpan_s = 6.0 * 3600.0;
/// The Earth rotation angle's rate [rad per UT1 second].
inline constexpr double kEarthRotationRate_rad_s = 2.0 * core::kPi * 1.00273781191135448 / 86400.0;

/// The first stars of the faint rests whose neighbourhoods
/// (StarField::neighbourhood_irradiance) are filled together: the whole
/// catalogue and the rests after the brightest 16, 64, …, 4096 (the star
/// test's ladder, render/night/star_visibility.h).
inline constexpr std::array<std::size_t, 6> kNeighbourhoodFirsts = {0, 16, 64, 256, 1024, 4096};

/// The stars of a catalogue, their fluxes at a scene's wavelengths and their
/// places at an epoch.
class StarField {
 public:
  /// Throws std::invalid_argument for no wavelengths.
  StarField(astro::StarCatalogue catalogue, const std::vector<double>& wavelengths_nm);

  const astro::StarCatalogue& catalogue() const { return catalogue_; }
  const std::vector<double>& wavelengths_nm() const { return wavelengths_nm_; }
  std::size_t size() const { return catalogue_.stars.size(); }
  /// Star i's irradiance above the atmosphere at wavelength k [W m⁻² nm⁻¹].
  double irradiance(std::size_t i, std::size_t k) const { return irradiance_[i * wavelengths_nm_.size() + k]; }
  /// The largest irradiance of any star at any wavelength.
  double brightest_irradiance() const { return brightest_; }
  /// The most light one pixel can gather from several stars, per wavelength:
  /// the largest sum, over the stars within `radius_rad` of any point of the
  /// sky, of their irradiance at that wavelength [W m⁻² nm⁻¹], with the stars
  /// at their J2000 places and the radius widened by twice the largest proper
  /// motion over `years_from_j2000` (precession, nutation, aberration and the
  /// sky's turning move neighbours alike). ≥ each wavelength's brightest star.
  /// The stars within the radius of one point lie within twice it of each
  /// other: the largest sum over the stars within twice the radius of a star
  /// (candidates from a grid of cubes of that chord). Only the
  /// stars from index `first` on (the catalogue is sorted brightest first: the
  /// faint rest after the first `first`). Cached per radius step of 2^(1/4) and `first`.
  const std::vector<double>& brightest_cluster_irradiance(double radius_rad, double years_from_j2000,
                                                          std::size_t first = 0);
  /// Per star i (every one), the sum of the irradiances of the stars from
  /// index `first` on within twice the widened radius of it, per wavelength,
  /// at [i · wavelengths + k]: a pixel gathering star i gathers no more of
  /// them (brightest_cluster_irradiance is the largest over i ≥ `first`).
  /// Cached per radius step and `first`; for a `first` of kNeighbourhoodFirsts
  /// all of those are filled in one pass (on the worker threads).
  const std::vector<double>& neighbourhood_irradiance(double radius_rad, double years_from_j2000,
                                                      std::size_t first = 0);
  /// The largest standard normal astro::scintillation_normal draws for any
  /// star of the catalogue (by its index, as star_splats does) in integration
  /// interval `interval`: the brightest twinkle of that interval is
  /// scintillation_factor(σ², this). Cached for the last interval.
  double largest_scintillation_normal(std::int64_t interval);
  /// Every star's astro::scintillation_normal for `interval` (by index), where
  /// largest_scintillation_normal computed them for it last; else null.
  const std::vector<double>* scintillation_normals(std::int64_t interval) const;

  /// Every star's geometric direction at `time` from `site` as (east, north,
  /// up) unit vectors into `out`: ERFA at the epoch, turned by the Earth's
  /// rotation since (recomputing the epoch when `time` is more than
  /// kStarEpochSpan_s from it or the site changed). Only the first `count`
  /// stars are turned (the brightest: the star test's second stage).
  void directions_enu(const astro::AstroTime& time, const astro::Site& site, std::vector<glm::dvec3>& out,
                      std::size_t count = static_cast<std::size_t>(-1));

 private:
  astro::StarCatalogue catalogue_;
  std::vector<double> wavelengths_nm_;
  std::vector<double> irradiance_;  // n per star
  double brightest_ = 0.0;
  double largest_proper_motion_rad_yr_ = 0.0;
  /// The caches' key: the radius widened by twice the largest proper motion
  /// over the years, rounded up to a step of 2^(1/4) (as log2 × 4).
  int radius_step(double radius_rad, double years_from_j2000) const;
  // By radius step and first star: the largest sums, the sums per star.
  std::map<std::pair<int, std::size_t>, std::vector<double>> clusters_, neighbourhoods_;
  bool have_normal_ = false;
  std::int64_t normal_interval_ = 0;
  double largest_normal_ = 0.0;
  std::vector<double> normals_;
  bool have_epoch_ = false;
  double epoch_ut1_jd_ = 0.0;
  astro::Site epoch_site_;
  std::vector<glm::dvec3> epoch_enu_;
};

}  // namespace zenith::render
