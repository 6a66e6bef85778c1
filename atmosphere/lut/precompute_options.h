#pragma once
// Options and report of a lookup-table precomputation, shared by the CPU
// (atmosphere/lut/cpu_precompute.h) and GPU (render/) implementations, which
// must produce the same tables for the same options.
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "atmosphere/lut/table_sizes.h"

namespace zenith::atmosphere::lut {

struct PrecomputeProgress {
  std::string stage;  ///< "transmittance", "single scattering", "order 2: density", ...
  double fraction;    ///< of the whole precompute, [0, 1]
};

/// Scattering orders of the tables unless the user says otherwise (every
/// command, the cluster config, the benchmarks), the orders after them added
/// as their series tail (PrecomputeOptions::series_tail, series_tail.h). Once
/// the view rays were integrated without their log-convex bias
/// (quadrature.h), 4 orders left Earth's noon sky 4.8 % RMS from the path
/// tracer and Mars' twilight 15.5 %, and the default became 8 orders. With the
/// tail, 6 orders are closer to the converged series than 8 without it in
/// every statistic (paper sizes, every texel: Earth 0.08 % RMS against 0.20 %,
/// Mars 0.56 % against 1.39 %; largest error 2.7 % and 5.9 % against 3.3 % and
/// 15 %), for three quarters of the cost (docs/lookup-tables.md, "Closing the
/// series").
constexpr int kDefaultScatteringOrders = 6;

struct PrecomputeOptions {
  TableSizes sizes{};
  /// Highest scattering order n (paper: "n is a user input"). ≥ 1.
  int max_orders = kDefaultScatteringOrders;
  /// If > 0, stop early once an order adds less than this fraction of the total
  /// in-scattered radiance (summed over the table); max_orders still caps it.
  double tolerance = 0.0;
  /// Close the series after the last order computed (at least the third) with
  /// its geometric tail per texel and wavelength (series_tail.h), instead of
  /// dropping the orders after it.
  bool series_tail = true;
  unsigned threads = 0;  ///< CPU worker threads; 0 = hardware concurrency

  // Quadrature: the same on CPU and GPU.
  int transmittance_samples = 500;  ///< Simpson intervals along each transmittance ray (rounded up to even)
  int scattering_samples = 50;      ///< samples along each single/multiple scattering ray
  /// From order `coarse_ray_first_order` on, the multiple-scattering rays read
  /// every `coarse_ray_stride`-th of their scattering_samples samples (and the
  /// last). The higher orders are smooth along a ray and small (order 3 is 7 % of
  /// Earth's in-scattered radiance, order 5 1 %), and the samples stay crowded
  /// toward the ray's lowest point (quadrature.h), so a stride of 2 moves the
  /// tables by much less than their own error while the ray integrals of those
  /// orders cost half (docs/lookup-tables.md, "Samples along the rays").
  int coarse_ray_stride = 2;       ///< ≥ 1; 1 keeps every sample at every order
  int coarse_ray_first_order = 3;  ///< ≥ 2

  /// The stride through the ray's samples of the multiple scattering of `order` (≥ 2).
  int ray_sample_stride(int order) const { return order >= coarse_ray_first_order ? coarse_ray_stride : 1; }

  /// How the integrand is interpolated between samples along scattering rays:
  /// trapezoid (linear, as Bruneton & Neyret), or log-linear (exact for an
  /// exponential integrand: on a vertical ray through a 1.2 km Mie layer with
  /// 2 km steps the trapezoid overestimates by ~20%, log-linear by < 1%).
  enum class Quadrature { Trapezoid, LogLinear };
  Quadrature scattering_quadrature = Quadrature::LogLinear;
  /// How the scattering density J_n (the sphere integral of the last order's
  /// radiance times the phase functions) is computed:
  ///  * Harmonics: the incoming radiance at each (r, μs) is projected once onto
  ///    spherical harmonics up to `harmonic_degree`, and J_n follows for every
  ///    (μ, ν) from the phase functions' Legendre moments (Funk–Hecke;
  ///    spherical_harmonics.h). The phase is integrated exactly to that degree.
  ///  * Direct: the sphere integral summed per 4D texel, as Bruneton & Neyret
  ///    (the method before; kept for comparison: 50–100× the cost, and its
  ///    error is that of the phase's forward peak between the directions).
  enum class DensityMethod { Harmonics, Direct };
  DensityMethod density_method = DensityMethod::Harmonics;
  /// Highest spherical-harmonic degree L of DensityMethod::Harmonics (the
  /// aerosol phase is cut after g^L of its forward peak). Capped at
  /// 2·sphere_zenith_samples − 1, what the direction rule resolves.
  int harmonic_degree = 32;
  /// Gauss–Legendre nodes in cos θ of the scattering-density sphere integral.
  /// Harmonics: this many on each side of the horizon (the radiance jumps
  /// there), 4× as many azimuths over the circle (cos(mφ) resolved without
  /// aliasing up to the degree). Direct: this many over [−1, 1], 2× as many
  /// azimuths. The sky-irradiance hemisphere uses half as many nodes.
  /// 24, not 16: in the deep twilight the light of the higher orders comes from a
  /// band a few degrees wide just above the horizon toward the sun (the sunlit air
  /// beyond the terminator), which 16 nodes undersample: Earth's zenith at sun
  /// −12° came out 4 % dark in the red, at −18° 12 % (`twilight` sizes); 24, 32
  /// and 48 nodes agree within 0.6 % (docs/night-sky.md, "Twilight in the tables").
  /// By day, at low sun and from orbit the tables do not move measurably.
  int sphere_zenith_samples = 24;
  /// The degree DensityMethod::Harmonics uses: harmonic_degree, capped by the rule.
  int harmonic_degree_used() const { return std::min(harmonic_degree, 2 * sphere_zenith_samples - 1); }

  std::function<void(const PrecomputeProgress&)> progress;  ///< optional
};

/// Throws std::invalid_argument naming the option and its allowed range when
/// `o` cannot be computed (the CPU and GPU precomputes check the same).
void check_precompute_options(const PrecomputeOptions& o);

struct StageTiming {
  std::string stage;
  double seconds;
};

struct PrecomputeReport {
  std::vector<StageTiming> stages;
  int orders_used = 0;
  /// Fraction of the final total in-scattered radiance each order added
  /// (index 0 = single scattering).
  std::vector<double> order_fraction;
  /// Fraction of the final total the series tail added (0 without one).
  double tail_fraction = 0.0;
  std::string device;  ///< "CPU (2 threads)" or the GL renderer string
  double total_seconds() const;
  /// Fills orders_used, order_fraction and tail_fraction from Σ radiance of
  /// each order (index 0 = single) and of the series tail.
  void set_order_sums(const std::vector<double>& order_sums, double tail_sum = 0.0);
};

}  // namespace zenith::atmosphere::lut
