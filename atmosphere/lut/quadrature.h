#pragma once
// The rule that integrates scattering along a ray: where its samples lie, and
// one interval between two of them.
#include <algorithm>
#include <cmath>

#include "atmosphere/lut/precompute_options.h"

namespace zenith::atmosphere::lut {

/// |ln(f1/f0)| below which integrate_interval uses the series of (e^x − 1)/x
/// (SERIES_LIMIT in the shaders).
inline constexpr double kLogLinearSeriesLimit = 1e-4;

/// ∫ f over an interval of length h from its end values f0, f1 ≥ 0.
///  * Trapezoid: h (f0 + f1)/2.
///  * LogLinear: f interpolated as an exponential, ∫ = h (f1 − f0)/ln(f1/f0),
///    exact when f decays exponentially across the interval (density profiles
///    and transmittance along steep rays); trapezoid where an end value is 0,
///    and a series where f0 ≈ f1.
inline double integrate_interval(double f0, double f1, double h, PrecomputeOptions::Quadrature rule) {
  if (rule == PrecomputeOptions::Quadrature::Trapezoid || f0 <= 0.0 || f1 <= 0.0) return 0.5 * h * (f0 + f1);
  const double x = std::log(f1 / f0);
  if (std::abs(x) < kLogLinearSeriesLimit) return h * f0 * (1.0 + x / 2.0 + x * x / 6.0);  // (e^x − 1)/x
  return h * (f1 - f0) / x;
}

/// Equal log-linear steps per interval between two samples of a view ray when
/// the precompute accumulates the optical depth along it (cpu_precompute.cpp,
/// view_ray_samples; OPTICAL_DEPTH_SUBSTEPS in the shaders). β_ext is a sum of
/// profiles with different scale heights, which one log-linear step per
/// interval overestimates; four keep τ within 0.1 % along the sky's rays.
constexpr int kOpticalDepthSubsteps = 4;

/// Distance from the start of a ray (r, μ) of length d to its lowest point:
/// 0 for a ray going up (μ ≥ 0), d for one that ends on the ground, else the
/// tangent point −rμ (at most d).
inline double lowest_point_distance_m(double r_m, double mu, double d_m, bool hits_ground) {
  if (mu >= 0.0) return 0.0;
  if (hits_ground) return d_m;
  return std::min(-r_m * mu, d_m);
}

/// t_i, the distance of sample i of n along a ray of length d whose lowest
/// point is at t_low (lowest_point_distance_m): samples crowd quadratically
/// toward the lowest point,
///   s = i/n, s_low = t_low/d,
///   t = t_low + (d − t_low) ((s − s_low)/(1 − s_low))²   for s ≥ s_low,
///   t = t_low − t_low ((s_low − s)/s_low)²                otherwise,
/// so the steps are shortest where the air is densest and its makeup changes
/// fastest, and at most twice the uniform step at the far ends.
///
/// Why: the multiple-scattering density J mixes a Rayleigh part (scale height
/// ~8 km on Earth) and an aerosol part (~1.2 km). A sum of two exponentials is
/// log-convex, so the log-linear rule over uniform steps (2.7 km on a ray going
/// up at 43° from the ground with 50 samples) overestimates ∫ J by 4 %, and the
/// second order by 3–8 % away from the sun against the path tracer
/// (docs/lookup-tables.md, "Samples along the rays"). Single scattering keeps
/// Rayleigh and Mie apart and was exact either way.
inline double ray_sample_distance_m(int i, int n, double d_m, double lowest_m) {
  const double s = double(i) / double(n);
  const double s_low = d_m > 0.0 ? std::clamp(lowest_m / d_m, 0.0, 1.0) : 0.0;
  if (s >= s_low) {
    const double span = 1.0 - s_low;
    if (span <= 0.0) return d_m;
    const double u = (s - s_low) / span;
    return lowest_m + (d_m - lowest_m) * u * u;
  }
  const double u = (s_low - s) / s_low;
  return lowest_m - lowest_m * u * u;
}

/// The sample after i when a ray of n intervals is read every `stride`-th
/// sample and at its end: 0, stride, 2·stride, …, n, then n + 1 (past the end).
/// The higher scattering orders read their rays this way
/// (PrecomputeOptions::coarse_ray_stride); a stride of 1 visits every sample.
inline int next_ray_sample(int i, int stride, int n) { return i >= n ? n + 1 : std::min(i + stride, n); }

/// The stride of a coarse ray (μ, hitting the ground or not): a ray that dips to
/// a tangent point inside the atmosphere and climbs again (a limb ray from
/// altitude) keeps every sample. Its integrand peaks at the tangent point, and
/// read every 2nd sample its order-3 and order-4 radiance moved by 2–6 % (small
/// tables, earth-advanced); every other ray moved by less than 0.3 %.
inline int coarse_ray_stride_for(double mu, bool ray_hits_ground, int stride) {
  return mu < 0.0 && !ray_hits_ground ? 1 : stride;
}

}  // namespace zenith::atmosphere::lut
