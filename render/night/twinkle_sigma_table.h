#pragma once
// How strongly a frame's stars twinkle at each elevation (docs/night-sky.md,
// "Scintillation"; astro/scintillation.h), by formula and by table. No GL.
#include <cstddef>
#include <vector>

namespace zenith::render {

/// The twinkle's s = √ln(1 + σ_I²) at μ = sin e by the formula, for a frame
/// whose astro::scintillation_variance_per_cubed_air_mass is `per_cubed_air_mass`.
double twinkle_log_sigma(double per_cubed_air_mass, double mu);

/// The twinkle's s = √ln(1 + σ_I²) of a frame's stars (astro/scintillation.h),
/// a function of a star's apparent elevation alone: of μ = sin e (d · up,
/// clamped to [0, 1]) through Pickering's air mass X(e) and σ_I² = min(1,
/// C X³), C the frame's astro::scintillation_variance_per_cubed_air_mass.
/// Below μ_cap, where C X³ reaches the cap, s = √ln 2 exactly; above,
/// tabulated at μ_j = μ_cap + (1 − μ_cap) t_j², t_j = j/N (N = kNodes: dense
/// at the horizon, where Pickering's h^1.1 bends X; the cap's kink at the
/// first node) and read linearly in t: a star then costs a root and a lerp
/// where the formula takes an arcsine, a power, a sine, a log and a root.
/// The error on [t_j, t_j+1] is at most (h/4) times the variation of ds/dt there
/// (linear interpolation's kernel is ≤ h/4), which the table's own second
/// differences D_j = s_j−1 − 2 s_j + s_j+1 bound where s″ keeps its sign over
/// the neighbouring intervals: bound_j = (|D_j| + |D_j+1|)/4, doubled for
/// inflections and + 1e-15 for rounding
/// (StarField.TheTwinkleTableIsTheFormulaWithinItsOwnBound checks it at 64
/// points per interval). A factor exp(s g − s²/2) read with s + ε is within
/// exp(|ε| (|g| + s + |ε|)) of the formula's: star_visibility's first stage
/// widens its twinkle by that for error_bound().
class TwinkleSigmaTable {
 public:
  static constexpr std::size_t kNodes = 2048;
  explicit TwinkleSigmaTable(double per_cubed_air_mass);
  /// s at μ by the table.
  double operator()(double mu) const;
  /// s at μ by the formula.
  double exact(double mu) const;
  /// The bound above on the interval holding μ, and the largest over all.
  double bound_at(double mu) const;
  double error_bound() const { return largest_bound_; }

 private:
  double per_cubed_air_mass_;
  double mu_cap_ = 0.0, s_cap_ = 0.0, span_ = 1.0;  // σ_I² = 1 at and below μ_cap; 1 − μ_cap
  std::vector<double> s_, bound_;                   // at the nodes; per interval
  double largest_bound_ = 0.0;
};

}  // namespace zenith::render
