#pragma once
// Piecewise-constant bounds of the extinction coefficient for delta and ratio tracking.
//
// The atmosphere shell [R_ground, R_top] is cut into concentric sub-shells of
// equal thickness; each holds, per wavelength, an upper bound β̄ (majorant) and a
// lower bound β̲ (minorant) of β_ext(h) over its altitude range, without the
// air-mass stretch (the trackers multiply by the ray's stretch s, constant along
// a ray). A majorant that follows the density makes delta tracking efficient high
// in the atmosphere, where a single global majorant (the ground value) would waste
// almost every step; the minorant is the analytic control of residual ratio
// tracking (delta_tracking.h).
//
// The bounds are safe by construction: every density profile is either
// exponential (monotone: its extremes over [h0, h1] are at h0 and h1) or the
// model's monotone piecewise cubic (PCHIP: monotone between knots, so its
// extremes over [h0, h1] are at h0, h1 or a knot inside). The grid takes the
// extremes of those values and of 33 evenly spaced samples over the range widened
// by 1 m, sums the constituents' maxima (Σ max ≥ max Σ) and minima (Σ min ≤ min Σ),
// and widens by 1% (β̄ × 1.01, β̲ × 0.99). The trackers count any tentative
// collision where β_ext > β̄ (a "majorant violation", which would bias delta
// tracking) and report it.
#include <cstddef>
#include <vector>

#include "atmosphere/atmosphere_model.h"

namespace zenith::atmosphere::reference {

class MajorantGrid {
 public:
  /// `shell_count` ≥ 1 sub-shells of thickness (R_top − R_ground)/shell_count.
  MajorantGrid(const AtmosphereModel& model, std::size_t shell_count);

  std::size_t shell_count() const { return majorant_m1_.size() / wavelength_count_; }
  /// Radius of the lower boundary of shell k (k = shell_count gives R_top) [m].
  double boundary_radius_m(std::size_t k) const { return boundary_radius_m_[k]; }
  /// The shell containing radius r, clamped to [0, shell_count − 1].
  std::size_t shell_of_radius(double r_m) const;
  /// β̄ of shell k at wavelength index i [m^-1] (unstretched).
  double majorant_m1(std::size_t shell, std::size_t wavelength) const {
    return majorant_m1_[shell * wavelength_count_ + wavelength];
  }
  /// β̲ of shell k at wavelength index i [m^-1] (unstretched), 0 ≤ β̲ ≤ β̄.
  double minorant_m1(std::size_t shell, std::size_t wavelength) const {
    return minorant_m1_[shell * wavelength_count_ + wavelength];
  }

 private:
  std::size_t wavelength_count_;
  double ground_radius_m_, shell_thickness_m_;
  std::vector<double> boundary_radius_m_;
  std::vector<double> majorant_m1_;  // [shell][wavelength]
  std::vector<double> minorant_m1_;  // [shell][wavelength]
};

}  // namespace zenith::atmosphere::reference
