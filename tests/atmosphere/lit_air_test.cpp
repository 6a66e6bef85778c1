// The reference's deep-twilight estimator (atmosphere/reference/lit_air_estimator.h):
// against the path tracer where both converge, per order and in total; its order 2
// in deep twilight against an independent nested quadrature; determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <thread>
#include <vector>

#include "atmosphere/constants.h"
#include "atmosphere/parameters.h"
#include "atmosphere/reference/geometry.h"
#include "atmosphere/reference/lit_air_estimator.h"
#include "atmosphere/reference/medium.h"
#include "atmosphere/reference/optical_depth.h"
#include "atmosphere/reference/path_tracer.h"
#include "atmosphere/reference/single_scattering.h"

namespace zenith::atmosphere::reference {
namespace {

const Vec3 kZenith{0.0, 0.0, 1.0};

/// ZENITH_VALIDATION_SCALE multiplies the sample counts (default 1) for the
/// longer validation runs quoted in atmosphere/reference/README.md.
std::size_t scaled(std::size_t samples) {
  const char* scale = std::getenv("ZENITH_VALIDATION_SCALE");
  return scale ? std::size_t(double(samples) * std::stod(scale)) : samples;
}

Vec3 sun_at_elevation(double elevation_deg) {
  const double e = elevation_deg * kPi / 180.0;
  return Vec3{std::cos(e), 0.0, std::sin(e)};
}

Vec3 camera(const AtmosphereModel& m) { return {0.0, 0.0, m.ground_radius_m + 1.0}; }

/// Either estimator's options: `samples` (per wavelength), scattering orders min_order…max_order.
template <typename Options>
Options estimator(std::size_t samples, int min_order, int max_order) {
  Options o;
  if constexpr (requires { o.samples; })
    o.samples = samples;
  else
    o.samples_per_wavelength = samples;
  o.min_scattering_order = min_order;
  o.max_scattering_order = max_order;
  return o;
}
LitAirOptions lit_air(std::size_t samples, int min_order = 1, int max_order = 1000) {
  return estimator<LitAirOptions>(samples, min_order, max_order);
}
PathTracerOptions path_tracer(std::size_t samples, int min_order = 1, int max_order = 1000) {
  return estimator<PathTracerOptions>(samples, min_order, max_order);
}

struct OrderRange {
  int min, max;
  double teeth;  ///< the largest combined relative standard error accepted
  const char* label;
};

// Sun 20° up (the zenith ray lit, every order reached by both estimators):
// order 2, orders ≥ 3 and the total agree within 3.5 combined standard errors.
// The aerosols are taken out: with them the path tracer's order 2 has a heavy
// tail (the sun's aureole is found only when a phase-sampled direction points
// near the sun), which 40 000 paths do not resolve; the lit-air estimator samples
// the aureole itself. With the aerosols, ZENITH_VALIDATION_SCALE=4 agrees within
// 2.1 σ (atmosphere/reference/README.md); its order 2 in deep twilight, with
// aerosols, is checked by the nested quadrature below.
TEST(ReferenceLitAir, AgreesWithThePathTracerPerOrderAndInTotalWhereBothConverge) {
  const bool aerosols = std::getenv("ZENITH_VALIDATION_SCALE") != nullptr;
  AtmosphereModel m = load_preset("earth-advanced").model;
  if (!aerosols) {
    m.mie_scattering_m1 = m.mie_extinction_m1 = Spectrum(m.wavelength_count());
    m.check();
  }
  const SunDisc sun{sun_at_elevation(20.0), 4.65e-3};
  for (const OrderRange& r : {OrderRange{2, 2, 0.10, "order 2"}, OrderRange{3, 1000, 0.25, "orders >= 3"},
                              OrderRange{1, 1000, 0.06, "all orders"}}) {
    const LitAirEstimate ours = lit_air_radiance(m, camera(m), kZenith, sun, lit_air(scaled(2000), r.min, r.max));
    const RadianceEstimate theirs =
        path_traced_radiance(m, camera(m), kZenith, sun, path_tracer(scaled(40000), r.min, r.max));
    EXPECT_EQ(ours.majorant_violations, 0u);
    for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
      const double combined = std::hypot(ours.standard_error[i], theirs.standard_error[i]);
      std::cout << r.label << " " << m.wavelengths_nm[i] << " nm: lit air " << ours.mean[i] << " +- "
                << ours.standard_error[i] << ", path tracer " << theirs.mean[i] << " +- " << theirs.standard_error[i]
                << ", z = " << (ours.mean[i] - theirs.mean[i]) / combined << "\n";
      EXPECT_LT(combined, r.teeth * theirs.mean[i]) << r.label;  // the comparison has teeth
      EXPECT_NEAR(ours.mean[i], theirs.mean[i], 3.5 * combined) << r.label << " " << m.wavelengths_nm[i] << " nm";
    }
  }
}

/// Order 2 of the zenith radiance by nested Gauss–Legendre quadrature, sharing
/// no sampling code with the estimator:
///   L2 = ∫_column T(x, y) ∫_{4π} [β_R P_R(ν) + β_M P_M(ν)](y) [L1 + L_g](y, ω) dω dt,
/// ν = ω·z (the column is vertical). The sun lies in the x–z plane, so the
/// integrand is even in the azimuth φ of ω: ∫_0^π, doubled. Panels in μ = ω·up
/// break at the horizon's dip at the vertex (where rays begin to hit the
/// ground, and L_g appears) and cluster near the horizon, where the lit air is.
Spectrum nested_order_two(const AtmosphereModel& m, const Vec3& sun) {
  static constexpr std::array<double, 4> kNodes = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                                   0.8611363115940526};
  static constexpr std::array<double, 4> kWeights = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                                     0.3478548451374538};
  auto panels = [](std::vector<double> cuts, const auto& f) {
    std::sort(cuts.begin(), cuts.end());
    for (std::size_t p = 0; p + 1 < cuts.size(); ++p) {
      const double half = 0.5 * (cuts[p + 1] - cuts[p]), mid = 0.5 * (cuts[p + 1] + cuts[p]);
      if (half <= 0.0) continue;
      for (std::size_t k = 0; k < kNodes.size(); ++k) f(mid + half * kNodes[k], half * kWeights[k]);
    }
  };
  const std::size_t n = m.wavelength_count();
  const AtmosphereMedium medium(m);
  SingleScatteringOptions quadrature;
  quadrature.relative_tolerance = 1e-3;
  quadrature.optical_depth.relative_tolerance = 1e-6;
  // Vertices along the column, in altitude panels (the density falls fastest low down).
  std::vector<std::pair<double, double>> column;  // altitude, weight
  panels({1.0, 3e3, 8e3, 15e3, 25e3, 40e3, 60e3, m.top_radius_m - m.ground_radius_m},
         [&](double h, double w) { column.emplace_back(h, w); });
  std::vector<Spectrum> per_vertex(column.size(), Spectrum(n));
  auto work = [&](std::size_t first, std::size_t stride) {
    std::vector<LocalCoefficients> local(n);
    for (std::size_t v = first; v < column.size(); v += stride) {
      const double h = column[v].first;
      const Vec3 y{0.0, 0.0, m.ground_radius_m + h};
      medium.coefficients(h, local);
      const double r = m.ground_radius_m + h;
      const double dip = -std::sqrt(std::max(0.0, 1.0 - (m.ground_radius_m / r) * (m.ground_radius_m / r)));
      Spectrum inner(n);
      panels({-1.0, dip - 0.05, dip, dip + 0.03, dip + 0.07, 0.15, 0.3, 1.0}, [&](double mu, double wmu) {
        panels({0.0, 0.3, 0.7, 1.2, 2.0, kPi}, [&](double phi, double wphi) {
          const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
          const Vec3 w{s * std::cos(phi), s * std::sin(phi), mu};
          const SingleScatteringResult l1 = single_scattering_radiance(m, y, w, sun, quadrature);
          for (std::size_t i = 0; i < n; ++i)
            inner[i] += 2.0 * wmu * wphi * medium.mixture_phase(local[i], i, mu) * local[i].scattering_m1() *
                        (l1.atmosphere_radiance[i] + l1.ground_radiance[i]);
        });
      });
      const Spectrum depth = optical_depth(m, Vec3{0.0, 0.0, m.ground_radius_m + 1.0}, y);
      for (std::size_t i = 0; i < n; ++i) per_vertex[v][i] = column[v].second * std::exp(-depth[i]) * inner[i];
    }
  };
  std::thread helper(work, 1, 2);
  work(0, 2);
  helper.join();
  Spectrum total(n);
  for (const Spectrum& s : per_vertex) total += s;
  return total;
}

// Sun −12°: the whole zenith ray is in the Earth's shadow (order 1 is 0), the
// light is scattered at least twice. Order 2 of the estimator (4 000 paths)
// against the nested quadrature, which agrees with a finer one (9 × 9 × 6
// panels, L1 to 1e-4) to 0.5 % (680 nm), 0.02 % and 0.004 %.
TEST(ReferenceLitAir, DeepTwilightOrderTwoMatchesANestedQuadrature) {
  const AtmosphereModel m = load_preset("earth-advanced").model;
  const Vec3 sun = sun_at_elevation(-12.0);
  const Spectrum expected = nested_order_two(m, sun);
  const LitAirEstimate ours =
      lit_air_radiance(m, camera(m), kZenith, SunDisc{sun, 4.65e-3}, lit_air(scaled(4000), 2, 2));
  const LitAirEstimate first = lit_air_radiance(m, camera(m), kZenith, SunDisc{sun, 4.65e-3}, lit_air(1, 1, 1));
  for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
    std::cout << m.wavelengths_nm[i] << " nm: order 2 lit air " << ours.mean[i] << " +- " << ours.standard_error[i]
              << ", nested quadrature " << expected[i]
              << ", z = " << (ours.mean[i] - expected[i]) / ours.standard_error[i] << "\n";
    EXPECT_EQ(first.mean[i], 0.0);  // no direct sunlight anywhere on the zenith ray
    EXPECT_GT(expected[i], 0.0);
    EXPECT_LT(ours.standard_error[i], 0.08 * expected[i]);  // 5.5-6.3 % measured
    // 3σ plus the nested quadrature's own error (≤ 0.5 %, doubled).
    EXPECT_NEAR(ours.mean[i], expected[i], 3.0 * ours.standard_error[i] + 0.01 * expected[i]);
  }
}

TEST(ReferenceLitAir, SameSeedGivesIdenticalResultsForAnyThreadCountAndBatching) {
  const AtmosphereModel m = load_preset("earth-advanced").model;
  const SunDisc sun{sun_at_elevation(-15.0), 4.65e-3};
  LitAirOptions o = lit_air(768);  // three chunks of the parallel estimator
  o.thread_count = 1;
  const LitAirEstimate one = lit_air_radiance(m, camera(m), kZenith, sun, o);
  o.thread_count = 3;
  const LitAirEstimate three = lit_air_radiance(m, camera(m), kZenith, sun, o);
  std::size_t reported = 0;
  o.batches = 3;
  o.progress = [&](std::size_t done, std::size_t total) {
    EXPECT_EQ(total, 768u);
    EXPECT_EQ(done, reported + 256u);
    reported = done;
  };
  const LitAirEstimate batched = lit_air_radiance(m, camera(m), kZenith, sun, o);
  EXPECT_EQ(reported, 768u);
  for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(one.mean[i]), std::bit_cast<std::uint64_t>(three.mean[i]));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(one.standard_error[i]),
              std::bit_cast<std::uint64_t>(three.standard_error[i]));
    EXPECT_GT(one.mean[i], 0.0);
    EXPECT_EQ(one.order_one[i], 0.0);  // the zenith ray is in the Earth's shadow
    // Three batches are other paths, statistically compatible.
    EXPECT_NEAR(batched.mean[i], one.mean[i], 4.0 * std::hypot(one.standard_error[i], batched.standard_error[i]));
  }
  LitAirOptions bad = lit_air(100);
  bad.batches = 3;
  EXPECT_THROW(lit_air_radiance(m, camera(m), kZenith, sun, bad), std::invalid_argument);
  EXPECT_THROW(lit_air_radiance(m, camera(m), kZenith, sun, lit_air(100, 3, 2)), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::atmosphere::reference
