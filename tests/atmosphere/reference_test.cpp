// Tests of the independent reference solver (atmosphere/reference/): geometry,
// quadrature, optical depth, single scattering and the Monte Carlo path tracer.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "atmosphere/constants.h"
#include "atmosphere/parameters.h"
#include "atmosphere/phase_functions.h"
#include "atmosphere/reference/adaptive_quadrature.h"
#include "atmosphere/reference/direction_sampling.h"
#include "atmosphere/reference/geometry.h"
#include "atmosphere/reference/majorant_grid.h"
#include "atmosphere/reference/medium.h"
#include "atmosphere/reference/optical_depth.h"
#include "atmosphere/reference/parallel_estimator.h"
#include "atmosphere/reference/path_integrator.h"
#include "atmosphere/reference/path_tracer.h"
#include "atmosphere/reference/phase_sampling.h"
#include "atmosphere/reference/single_scattering.h"
#include "atmosphere/reference/sun_disc.h"
#include "atmosphere/solar_limb_darkening.h"
#include "tests/atmosphere/test_util.h"

namespace zenith::atmosphere::reference {
namespace {

constexpr double kEarthRadius = 6371e3;
constexpr double kAstronomicalUnit_m = 1.495978707e11;

/// One wavelength (550 nm), molecules only: β·exp(−h/H), classic Rayleigh phase.
AtmosphereModel exponential_model(double beta_m1, double scale_height_m, double atmosphere_height_m,
                                  double albedo = 0.0) {
  AtmosphereModel m;
  m.name = "test exponential";
  m.wavelengths_nm = {550.0};
  m.ground_radius_m = kEarthRadius;
  m.top_radius_m = kEarthRadius + atmosphere_height_m;
  m.ground_albedo = Spectrum{albedo};
  m.rayleigh_scattering_m1 = Spectrum{beta_m1};
  m.rayleigh_density = DensityProfile::exponential(scale_height_m);
  m.rayleigh_phase = RayleighPhaseModel::Classic;
  m.mie_scattering_m1 = Spectrum{0.0};
  m.mie_extinction_m1 = Spectrum{0.0};
  m.mie_phase.g1 = m.mie_phase.g2 = m.mie_phase.alpha = Spectrum{0.0};
  m.check();
  return m;
}

AtmosphereModel preset(const char* name) { return load_preset(name).model; }

/// `m` with its Mie phase replaced by a table of Cornette–Shanks (g 0.8 at
/// 440 nm, 0.6 at 680 nm) every 2°: a phase no proposal of the solver matches.
AtmosphereModel with_tabulated_mie_phase(AtmosphereModel m) {
  std::vector<double> angles;
  for (int a = 0; a <= 180; a += 2) angles.push_back(a);
  std::vector<TabulatedPhase::Column> columns = {{440.0, {}}, {680.0, {}}};
  for (double a : angles) {
    columns[0].values.push_back(cornette_shanks(std::cos(a * kPi / 180.0), 0.8));
    columns[1].values.push_back(cornette_shanks(std::cos(a * kPi / 180.0), 0.6));
  }
  m.mie_phase.model = MiePhase::Model::Tabulated;
  m.mie_phase.table = std::make_shared<const TabulatedPhase>(angles, columns, m.wavelengths_nm);
  return m;
}

Vec3 above_ground(const AtmosphereModel& m, double altitude_m) { return {0.0, 0.0, m.ground_radius_m + altitude_m}; }

double degrees(double deg) { return deg * kPi / 180.0; }

// ---------------------------------------------------------------------------------------------
// Quadrature

TEST(ReferenceQuadrature, GaussKronrodIsExactForPolynomialsAndG7UpToDegree13) {
  for (int k = 0; k <= 22; ++k) {
    QuadratureOptions loose;
    loose.relative_tolerance = 1.0;  // one panel, no bisection
    const std::vector<double> ends = {0.0, 1.0};
    const QuadratureResult r =
        integrate_adaptive([k](double x, std::span<double> v) { v[0] = std::pow(x, k); }, ends, 1, loose);
    EXPECT_EQ(r.evaluations, 15u);
    EXPECT_NEAR(r.integral[0], 1.0 / (k + 1), 1e-15) << "degree " << k;
    if (k <= 13) {
      EXPECT_LT(r.error_estimate[0], 1e-15) << "degree " << k;  // G7 is exact too
    }
  }
}

TEST(ReferenceQuadrature, AdaptiveBisectionResolvesANarrowPeakPerComponent) {
  // Component 0: exp(−x) on [0, 100]; component 1: a Lorentzian of half-width 0.01 at x = 3.
  const std::vector<double> ends = {0.0, 100.0};
  QuadratureOptions o;
  o.relative_tolerance = 1e-11;
  const QuadratureResult r = integrate_adaptive(
      [](double x, std::span<double> v) {
        v[0] = std::exp(-x);
        v[1] = 1.0 / (1.0 + 1e4 * (x - 3.0) * (x - 3.0));
      },
      ends, 2, o);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.integral[0], 1.0 - std::exp(-100.0), 1e-11);
  const double lorentzian = (std::atan(100.0 * 97.0) + std::atan(100.0 * 3.0)) / 100.0;
  EXPECT_NEAR(r.integral[1], lorentzian, 1e-11 * lorentzian);
  EXPECT_LT(r.error_estimate[1], 1e-11 * lorentzian);
}

// ---------------------------------------------------------------------------------------------
// Geometry

TEST(ReferenceGeometry, RadiusCosineFormsAgreeWithTheRay) {
  const double R = kEarthRadius, top = R + 100e3;
  for (double altitude : {1.0, 1e3, 3e4, 99e3}) {
    const double r = R + altitude;
    for (double mu : {-1.0, -0.5, -0.05, -1e-3, 0.0, 1e-3, 0.3, 1.0}) {
      const Ray ray({0.0, 0.0, r}, {std::sqrt(1.0 - mu * mu), 0.0, mu});
      const AtmosphereInterval interval = atmosphere_interval(ray, R, top);
      ASSERT_TRUE(interval.intersects);
      EXPECT_EQ(interval.begin_t_m, 0.0);
      EXPECT_EQ(interval.ends_on_ground, ray_hits_ground(r, mu, R)) << altitude << " " << mu;
      const double expected =
          interval.ends_on_ground ? distance_to_ground_m(r, mu, R) : distance_to_top_of_atmosphere_m(r, mu, top);
      EXPECT_NEAR(interval.end_t_m, expected, 1e-9 * expected + 1e-9) << altitude << " " << mu;
    }
  }
  // Straight down from 1 km: 1 km to the ground; straight up from the ground: 100 km to the top.
  EXPECT_NEAR(distance_to_ground_m(R + 1e3, -1.0, R), 1e3, 1e-9);
  EXPECT_NEAR(distance_to_top_of_atmosphere_m(R, 1.0, top), 100e3, 1e-8);
  // From outside, straight down: enters after (r − top) and leaves the far side after (r + top).
  EXPECT_NEAR(distance_to_atmosphere_entry_m(R + 200e3, -1.0, top), 100e3, 1e-8);
  EXPECT_NEAR(distance_to_top_of_atmosphere_m(R + 200e3, -1.0, top), 2.0 * R + 300e3, 1e-6);
  EXPECT_TRUE(std::isinf(distance_to_atmosphere_entry_m(R + 200e3, 0.5, top)));
}

TEST(ReferenceGeometry, ObserverAt40AstronomicalUnits) {
  const double R = kEarthRadius, top = R + 100e3, distance = 40.0 * kAstronomicalUnit_m;
  const Vec3 observer{distance, 0.0, 0.0};
  // Aimed at the centre: enters at the top, ends on the ground, with millimetre accuracy.
  const Ray to_centre(observer, -observer);
  const AtmosphereInterval hit = atmosphere_interval(to_centre, R, top);
  ASSERT_TRUE(hit.intersects);
  EXPECT_TRUE(hit.ends_on_ground);
  EXPECT_NEAR(to_centre.radius_at(hit.begin_t_m), top, 1e-2);
  EXPECT_NEAR(to_centre.radius_at(hit.end_t_m), R, 1e-2);
  EXPECT_NEAR(length(to_centre.point_at(hit.end_t_m) - Vec3{R, 0.0, 0.0}), 0.0, 1e-2);
  // Aimed 50 km above the limb: impact parameter R + 50 km (to 1 cm); passes through, misses the ground.
  const Vec3 limb_point{0.0, R + 50e3, 0.0};
  const Ray grazing(observer, limb_point - observer);
  EXPECT_NEAR(grazing.impact_parameter_m(), R + 50e3, 1e-2);
  const AtmosphereInterval pass = atmosphere_interval(grazing, R, top);
  ASSERT_TRUE(pass.intersects);
  EXPECT_FALSE(pass.ends_on_ground);
  const double half_chord = std::sqrt(top * top - (R + 50e3) * (R + 50e3));
  EXPECT_NEAR(pass.end_t_m - pass.begin_t_m, 2.0 * half_chord, 1e-2);
  // Aimed 1 m outside the top: misses the atmosphere entirely.
  const Ray miss(observer, Vec3{0.0, top + 1.0, 0.0} - observer);
  EXPECT_FALSE(atmosphere_interval(miss, R, top).intersects);
}

TEST(ReferenceGeometry, RaysWithin1e6RadOfTheHorizon) {
  const double R = kEarthRadius, top = R + 100e3, h = 1.0, r = R + h;
  // Geometric horizon of an observer 1 m up: zenith angle π/2 + dip, cos(dip) = R/r.
  const double horizon_zenith = 0.5 * kPi + std::acos(R / r);
  const Vec3 observer{0.0, 0.0, r};
  const Ray below(observer, direction_from_angles(horizon_zenith + 1e-6, 0.0));
  const Ray above(observer, direction_from_angles(horizon_zenith - 1e-6, 0.0));
  const AtmosphereInterval b = atmosphere_interval(below, R, top), a = atmosphere_interval(above, R, top);
  ASSERT_TRUE(b.intersects && a.intersects);
  EXPECT_TRUE(b.ends_on_ground);
  EXPECT_FALSE(a.ends_on_ground);
  // Below: the impact parameter is p = r cos(dip + δ) = R − √(2Rh)·δ − Rδ²/2 with δ = 1e-6
  // (3.6 mm below the ground sphere), the perigee moves out to t_c = r sin(dip + δ), and the ray meets the
  // ground a half-chord √(R² − p²) ≈ 213 m before its perigee, ≈ 3363 m away.
  const double tangent = std::sqrt((r - R) * (r + R));
  const double depth = R - below.impact_parameter_m();
  EXPECT_NEAR(depth, tangent * 1e-6 + 0.5 * R * 1e-12, 1e-8);
  const double perigee = r * std::sin(std::acos(R / r) + 1e-6);
  EXPECT_NEAR(b.end_t_m, perigee - std::sqrt(2.0 * R * depth), 1e-3);
  // The (r, μ) form agrees to the precision double allows here (p is known to ~1e-9 m
  // and the chord amplifies that by R/chord).
  EXPECT_NEAR(b.end_t_m, distance_to_ground_m(r, below.direction().z, R), 1e-4);
  EXPECT_NEAR(below.radius_at(b.end_t_m), R, 1e-6);
  // Above: passes 3.6 mm over the ground and crosses the rest of the shell to the top.
  EXPECT_NEAR(above.radius_at(a.end_t_m), top, 1e-6);
  EXPECT_NEAR(a.end_t_m, std::sqrt(top * top - R * R) + tangent, 10.0);
  // Within 1e-6 rad of the horizontal: both above the horizon (the dip is 5.6e-4 rad).
  for (double dz : {-1e-6, 1e-6}) {
    const AtmosphereInterval i = atmosphere_interval(Ray(observer, direction_from_angles(0.5 * kPi + dz, 0.0)), R, top);
    EXPECT_FALSE(i.ends_on_ground);
    EXPECT_NEAR(i.end_t_m, std::sqrt(top * top - r * r), 10.0);
  }
}

TEST(ReferenceGeometry, PlanetShadowBoundaryIsTheNightSideCylinder) {
  const double R = kEarthRadius;
  const Vec3 sun{1.0, 0.0, 0.0};
  // A ray at x = −2R travelling along +y crosses the shadow cylinder at y = ±R.
  const Ray night({-2.0 * R, -2.0 * R, 0.0}, {0.0, 1.0, 0.0});
  const std::vector<double> t = planet_shadow_crossings_t_m(night, sun, R);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_NEAR(t[0], R, 1e-6);
  EXPECT_NEAR(t[1], 3.0 * R, 1e-6);
  // The same ray on the day side (x = +2R) never enters the shadow.
  EXPECT_TRUE(planet_shadow_crossings_t_m(Ray({2.0 * R, -2.0 * R, 0.0}, {0.0, 1.0, 0.0}), sun, R).empty());
}

// ---------------------------------------------------------------------------------------------
// Medium and majorants

TEST(ReferenceMedium, EqualsTheModelsExtinction) {
  const AtmosphereModel m = preset("earth-advanced");  // Rayleigh, Mie, tabulated ozone
  ASSERT_FALSE(m.absorbers.empty());
  const AtmosphereMedium medium(m);
  std::vector<double> beta(m.wavelength_count());
  std::vector<LocalCoefficients> local(m.wavelength_count());
  for (double h = 0.0; h <= m.atmosphere_height_m(); h += 1234.5) {
    const Spectrum expected = m.extinction_m1(h);
    medium.extinction_m1(h, beta);
    medium.coefficients(h, local);
    for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
      EXPECT_DOUBLE_EQ(beta[i], expected[i]) << h;
      EXPECT_DOUBLE_EQ(medium.extinction_m1(h, i), expected[i]) << h;
      EXPECT_DOUBLE_EQ(local[i].extinction_m1, expected[i]) << h;
      EXPECT_DOUBLE_EQ(medium.coefficients(h, i).extinction_m1, expected[i]) << h;
      EXPECT_DOUBLE_EQ(local[i].scattering_m1(),
                       m.rayleigh_scattering_m1[i] * m.rayleigh_density(h) + m.mie_scattering_m1[i] * m.mie_density(h));
    }
  }
}

TEST(ReferenceMajorantGrid, BoundsTheExtinctionOfEveryPreset) {
  for (const std::string& name : preset_names()) {
    const AtmosphereModel m = preset(name.c_str());
    const MajorantGrid grid(m, 128);
    const AtmosphereMedium medium(m);
    double tightest = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= 100000; ++k) {
      const double h = m.atmosphere_height_m() * k / 100000.0;
      const std::size_t shell = grid.shell_of_radius(m.ground_radius_m + h);
      for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
        const double beta = medium.extinction_m1(h, i);
        ASSERT_LE(beta, grid.majorant_m1(shell, i)) << name << " h " << h;
        if (beta > 0.0) tightest = std::min(tightest, grid.majorant_m1(shell, i) / beta);
      }
    }
    EXPECT_LT(tightest, 1.02) << name;  // the bound is attained up to the 1% margin somewhere
  }
}

// ---------------------------------------------------------------------------------------------
// Optical depth

TEST(ReferenceOpticalDepth, VerticalExponentialMatchesClosedForm) {
  const double beta = 1e-5, H = 8000.0;
  const AtmosphereModel m = exponential_model(beta, H, 100e3);
  for (double dh : {1e3, 20e3, 100e3}) {
    const double tau = optical_depth(m, above_ground(m, 0.0), above_ground(m, dh))[0];
    const double expected = beta * H * (1.0 - std::exp(-dh / H));  // β H (1 − e^{−Δh/H})
    EXPECT_NEAR(tau, expected, 1e-10 * expected) << dh;
  }
  const double tau = optical_depth(m, above_ground(m, 5e3), above_ground(m, 30e3))[0];
  const double expected = beta * H * (std::exp(-5e3 / H) - std::exp(-30e3 / H));
  EXPECT_NEAR(tau, expected, 1e-10 * expected);
  // Above the top there is no atmosphere.
  EXPECT_NEAR(optical_depth(m, above_ground(m, 0.0), above_ground(m, 1e6))[0], beta * H * (1.0 - std::exp(-100e3 / H)),
              1e-10 * beta * H);
}

TEST(ReferenceOpticalDepth, VerticalColumnOfEveryPresetMatchesTheExactColumns) {
  // zenith_optical_depth integrates each profile exactly (PCHIP ozone included).
  for (const std::string& name : preset_names()) {
    const AtmosphereModel m = preset(name.c_str());
    const Spectrum tau = optical_depth(m, above_ground(m, 0.0), above_ground(m, m.atmosphere_height_m()));
    const Spectrum exact = m.zenith_optical_depth().total;
    const double stretch = m.air_mass(m.ground_radius_m, 1.0);
    for (std::size_t i = 0; i < m.wavelength_count(); ++i)
      EXPECT_NEAR(tau[i], stretch * exact[i], 1e-9 * exact[i]) << name << " " << m.wavelengths_nm[i];
  }
}

TEST(ReferenceOpticalDepth, HorizontalRayMatchesChapmanGrazingIncidence) {
  // From the perigee of a horizontal ray at altitude h0 to infinity, for x = r0/H:
  //   τ = β e^{−h0/H} H √(πx/2) (1 + 3/(8x) − 15/(128x²) + …)   (Chapman function at 90°).
  const double beta = 1e-5, H = 8000.0;
  const AtmosphereModel m = exponential_model(beta, H, 250e3);  // e^{−250/8}: the top is at infinity
  for (double h0 : {0.0, 5e3, 40e3}) {
    const double r0 = kEarthRadius + h0, x = r0 / H;
    const double chapman = std::sqrt(kPi * x / 2.0) * (1.0 + 3.0 / (8.0 * x) - 15.0 / (128.0 * x * x));
    const double expected = beta * std::exp(-h0 / H) * H * chapman;
    const Vec3 start{0.0, 0.0, r0};
    const Vec3 far_end{3e6, 0.0, r0};  // beyond the top
    EXPECT_NEAR(optical_depth(m, start, far_end)[0], expected, 2e-7 * expected) << h0;
    // Through the whole shell: twice that.
    EXPECT_NEAR(optical_depth(m, Vec3{-3e6, 0.0, r0}, far_end)[0], 2.0 * expected, 4e-7 * expected) << h0;
  }
}

TEST(ReferenceOpticalDepth, TransmittanceIsReciprocalWithTheAirMassStretch) {
  const AtmosphereModel m = preset("earth-standard");
  ASSERT_TRUE(m.air_mass.enabled());
  const Vec3 a = above_ground(m, 1.0);
  for (double zenith_deg : {10.0, 60.0, 85.0, 89.5}) {
    const Vec3 b = a + 150e3 * direction_from_angles(degrees(zenith_deg), 0.7);
    const Spectrum ab = transmittance(m, a, b), ba = transmittance(m, b, a);
    for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
      EXPECT_GT(ab[i], 0.0);
      EXPECT_NEAR(ab[i], ba[i], 1e-12 * ab[i]) << zenith_deg;
    }
  }
}

TEST(ReferenceOpticalDepth, StretchMultipliesTheOpticalDepthOfTheWholeRay) {
  const AtmosphereModel pickering = preset("earth-standard");
  AtmosphereModel geometric = pickering;
  geometric.air_mass = AirMassStretch();
  const Vec3 a = above_ground(pickering, 1.0);
  const Vec3 view = direction_from_angles(degrees(89.0), 0.0);
  const Vec3 b = a + 400e3 * view;
  const double s = pickering.air_mass(length(a), dot(normalize(a), view));
  EXPECT_GT(s, 1.02);  // near the horizon Pickering's air mass is well above the straight-ray one
  const Spectrum stretched = optical_depth(pickering, a, b), straight = optical_depth(geometric, a, b);
  for (std::size_t i = 0; i < stretched.size(); ++i) EXPECT_NEAR(stretched[i], s * straight[i], 1e-9 * stretched[i]);
}

TEST(ReferenceOpticalDepth, PlanetBlocksSegmentsAndTheSun) {
  const AtmosphereModel m = preset("earth-standard");
  const Spectrum through = transmittance(m, above_ground(m, 1e3), Vec3{0.0, 0.0, -(m.ground_radius_m + 1e3)});
  EXPECT_EQ(through[0], 0.0);
  // Sun straight up from 1 km: exp(−τ(1 km → top)); straight down: the planet is in the way.
  const Spectrum up = transmittance_to_sun(m, above_ground(m, 1e3), {0.0, 0.0, 1.0});
  const Spectrum column = transmittance(m, above_ground(m, 1e3), above_ground(m, m.atmosphere_height_m()));
  EXPECT_NEAR(up[2], column[2], 1e-14);
  EXPECT_EQ(transmittance_to_sun(m, above_ground(m, 1e3), {0.0, 0.0, -1.0})[2], 0.0);
  // From outside the atmosphere, away from it: nothing in the way.
  EXPECT_EQ(transmittance_to_sun(m, above_ground(m, 200e3), {0.0, 0.0, 1.0})[2], 1.0);
}

// ---------------------------------------------------------------------------------------------
// Sampling

TEST(ReferenceSampling, PhaseSamplersInvertTheirCumulativeDistributions) {
  for (double u = 0.0; u < 1.0; u += 1.0 / 64.0) {
    const double nu = sample_rayleigh_classic_cosine(u);  // CDF (ν³ + 3ν + 4)/8
    EXPECT_NEAR((nu * nu * nu + 3.0 * nu + 4.0) / 8.0, u, 1e-13);
    for (double g : {-0.3, 0.2, 0.85, 0.99}) {
      const double c = sample_henyey_greenstein_cosine(g, u);
      // HG CDF: (1 − g²)/(2g) [1/√(1 + g² − 2gν) − 1/(1 + g)]
      const double cdf = (1.0 - g * g) / (2.0 * g) * (1.0 / std::sqrt(1.0 + g * g - 2.0 * g * c) - 1.0 / (1.0 + g));
      EXPECT_NEAR(cdf, u, 1e-12) << g;
    }
  }
  const AtmosphereModel mars = preset("mars");  // double Henyey–Greenstein
  for (std::size_t i = 0; i < mars.wavelength_count(); ++i)
    EXPECT_NEAR(test::integrate_over_sphere([&](double c) { return mie_proposal_pdf(mars.mie_phase, i, c); }), 1.0,
                1e-9);
  const AtmosphereModel tabulated = with_tabulated_mie_phase(preset("earth-standard"));
  for (std::size_t i = 0; i < tabulated.wavelength_count(); ++i)
    EXPECT_NEAR(test::integrate_over_sphere_in_sin_half_angle(
                    [&](double c) { return mie_proposal_pdf(tabulated.mie_phase, i, c); }),
                1.0, 1e-12);
}

TEST(ReferenceSampling, ScatteringWeightsReproduceThePhaseFunctionsAngularMoments) {
  // E_q[w f(ν)] = ∫_{4π} P(ν) f(ν) dω for the mixture phase at 1 km, for f = 1 (normalization,
  // 0.99991 for Penndorf's fit), ν, ν² and the forward cone ν > 0.95.
  AtmosphereModel cornette_shanks = preset("earth-standard");
  cornette_shanks.mie_phase.model = MiePhase::Model::CornetteShanks;
  const AtmosphereModel models[] = {preset("earth-standard"), preset("mars"), preset("titan"), cornette_shanks,
                                    with_tabulated_mie_phase(preset("earth-standard"))};
  for (const AtmosphereModel& m : models) {
    const AtmosphereMedium medium(m);
    for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
      const LocalCoefficients c = medium.coefficients(1000.0, i);
      const auto phase = [&](double nu) { return medium.mixture_phase(c, i, nu); };
      const std::function<double(double)> moments[] = {[](double) { return 1.0; }, [](double nu) { return nu; },
                                                       [](double nu) { return nu * nu; },
                                                       [](double nu) { return nu > 0.95 ? 1.0 : 0.0; }};
      Pcg32 rng(2024, i);
      const int n = 100000;
      double sum[4] = {}, sum_sq[4] = {};
      for (int k = 0; k < n; ++k) {
        const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
        const PhaseSample s = sample_scattering_cosine(medium, c, i, u1, u2, u3);
        for (int f = 0; f < 4; ++f) {
          const double x = s.weight * moments[f](s.cos_scattering);
          sum[f] += x;
          sum_sq[f] += x * x;
        }
      }
      for (int f = 0; f < 4; ++f) {
        const double mean = sum[f] / n, error = std::sqrt((sum_sq[f] / n - mean * mean) / (n - 1));
        const double exact = test::integrate_over_sphere([&](double nu) { return phase(nu) * moments[f](nu); }, 20000);
        EXPECT_NEAR(mean, exact, 4.0 * error + 1e-12) << m.name << " " << m.wavelengths_nm[i] << " moment " << f;
        EXPECT_LT(error, 0.005);  // |f| ≤ 1 and ∫P ≈ 1: absolute precision
      }
    }
  }
}

TEST(ReferenceSampling, SunDiscDirectionsFillTheConeUniformly) {
  const SunDisc sun{normalize(Vec3{1.0, 2.0, 3.0}), 4.65e-3};
  const double cos_alpha = std::cos(sun.angular_radius_rad);
  EXPECT_NEAR(sun_solid_angle_sr(sun), 2.0 * kPi * (1.0 - cos_alpha), 1e-15);
  // L_sun Ω with L_sun = 1/(π sin²α).
  EXPECT_NEAR(sun_sample_weight(sun), sun_solid_angle_sr(sun) / (kPi * std::pow(std::sin(sun.angular_radius_rad), 2)),
              1e-12);
  Pcg32 rng(7, 11);
  double mean_one_minus_cos = 0.0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const Vec3 w = sample_sun_direction(sun, rng.uniform(), rng.uniform());
    EXPECT_NEAR(length(w), 1.0, 1e-15);
    EXPECT_GE(dot(w, sun.direction), cos_alpha - 1e-15);
    mean_one_minus_cos += (1.0 - dot(w, sun.direction)) / n;
  }
  EXPECT_NEAR(mean_one_minus_cos, 0.5 * (1.0 - cos_alpha), 0.02 * (1.0 - cos_alpha));  // uniform in cos θ
}

// ---------------------------------------------------------------------------------------------
// Single scattering

TEST(ReferenceSingleScattering, OpticallyThinHomogeneousLayerIsBetaTimesPhaseTimesLength) {
  // ρ ≈ 1 throughout a 10 km layer and τ ≤ 3e-6 on every path: L1 = β P(ν) ℓ to O(τ).
  const double beta = 1e-11;
  const AtmosphereModel m = exponential_model(beta, 1e12, 10e3);
  const Vec3 sun = direction_from_angles(degrees(40.0), 0.0);
  struct Case {
    Vec3 observer{}, view{};
  };
  const Case cases[] = {{above_ground(m, 1.0), {0.0, 0.0, 1.0}},
                        {above_ground(m, 5e3), direction_from_angles(degrees(90.0), 1.0)},
                        {above_ground(m, 2e3), direction_from_angles(degrees(120.0), 2.5)}};
  for (const Case& c : cases) {
    const Ray ray(c.observer, c.view);
    const AtmosphereInterval interval = atmosphere_interval(ray, m.ground_radius_m, m.top_radius_m);
    const double path_length = interval.end_t_m - interval.begin_t_m;
    const SingleScatteringResult r = single_scattering_radiance(m, c.observer, c.view, sun);
    EXPECT_TRUE(r.converged);
    const double expected = beta * rayleigh_phase_classic(dot(normalize(c.view), sun)) * path_length;
    EXPECT_NEAR(r.atmosphere_radiance[0], expected, 1e-5 * expected);
    EXPECT_EQ(r.ray_hits_ground, interval.ends_on_ground);
  }
}

TEST(ReferenceSingleScattering, DistantObserverSeesWhatAnObserverAboveTheAtmosphereSees) {
  const AtmosphereModel m = preset("earth-standard");
  const Vec3 sun = normalize(Vec3{1.0, 0.3, 0.2});
  const Vec3 far_observer = 40.0 * kAstronomicalUnit_m * normalize(Vec3{0.6, -0.8, 0.1});
  for (const Vec3& target : {Vec3{m.ground_radius_m, 0.0, 0.0}, Vec3{0.0, 0.0, m.ground_radius_m + 20e3}}) {
    const Vec3 view = normalize(target - far_observer);
    const Ray line(far_observer, view);
    const double t_top = line.sphere_crossings(m.top_radius_m)->entry_t_m;
    const Vec3 near_observer = line.point_at(t_top - 1e3);  // 1 km above the top, on the same line
    const SingleScatteringResult far = single_scattering_radiance(m, far_observer, view, sun);
    const SingleScatteringResult near = single_scattering_radiance(m, near_observer, view, sun);
    EXPECT_EQ(far.ray_hits_ground, near.ray_hits_ground);
    for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
      EXPECT_GT(far.atmosphere_radiance[i], 0.0);
      EXPECT_NEAR(far.atmosphere_radiance[i], near.atmosphere_radiance[i], 1e-6 * near.atmosphere_radiance[i]);
      EXPECT_NEAR(far.ground_radiance[i], near.ground_radiance[i], 1e-6 * near.ground_radiance[i]);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Path tracer

PathTracerOptions options(std::size_t samples, int max_order = 1000, std::uint64_t seed = 1) {
  PathTracerOptions o;
  o.samples_per_wavelength = samples;
  o.max_scattering_order = max_order;
  o.seed = seed;
  o.thread_count = 2;
  return o;
}

struct OrderOneCase {
  const char* preset;
  double observer_altitude_m, sun_zenith_deg, view_zenith_deg, view_azimuth_rad, sun_angular_radius_rad;
  std::size_t samples;
  const char* label;
};

class ReferenceOrderOne : public ::testing::TestWithParam<OrderOneCase> {};

TEST_P(ReferenceOrderOne, PathTracedOrderOneMatchesSingleScatteringQuadrature) {
  const OrderOneCase& c = GetParam();
  const AtmosphereModel m = preset(c.preset);
  const Vec3 observer = above_ground(m, c.observer_altitude_m);
  const Vec3 view = direction_from_angles(degrees(c.view_zenith_deg), c.view_azimuth_rad);
  const SunDisc sun{direction_from_angles(degrees(c.sun_zenith_deg), 0.0), c.sun_angular_radius_rad};
  const SingleScatteringResult quadrature = single_scattering_radiance(m, observer, view, sun.direction);
  ASSERT_TRUE(quadrature.converged);
  const RadianceEstimate mc = path_traced_radiance(m, observer, view, sun, options(c.samples, 1));
  EXPECT_EQ(mc.majorant_violations, 0u);
  for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
    const double expected = quadrature.atmosphere_radiance[i] + quadrature.ground_radiance[i];
    EXPECT_GT(expected, 0.0);
    EXPECT_LT(mc.standard_error[i], 0.04 * expected);  // the comparison has teeth
    EXPECT_NEAR(mc.mean[i], expected, 3.0 * mc.standard_error[i])
        << c.label << " " << m.wavelengths_nm[i] << " nm, z = " << (mc.mean[i] - expected) / mc.standard_error[i];
  }
}

INSTANTIATE_TEST_SUITE_P(
    Geometries, ReferenceOrderOne,
    ::testing::Values(OrderOneCase{"earth-standard", 1.0, 30.0, 60.0, 2.0, 4.65e-3, 60000, "EarthSun30"},
                      OrderOneCase{"earth-standard", 1.0, 80.0, 45.0, 0.5, 4.65e-3, 60000, "EarthSun80"},
                      // Near the horizon, where the air-mass stretch is large on both rays.
                      OrderOneCase{"earth-standard", 1.0, 86.0, 88.0, 1.2, 0.0, 60000, "EarthStretchNearHorizon"},
                      // Looking down from 10 km: atmosphere plus the sunlit ground.
                      OrderOneCase{"earth-standard", 10e3, 30.0, 120.0, 2.0, 4.65e-3, 60000, "EarthGround"},
                      // Twilight (ozone, Pickering): the lower part of the view ray is in the planet's
                      // shadow. Most collisions fall in the dark part, hence more samples.
                      OrderOneCase{"earth-advanced", 1.0, 92.0, 70.0, 0.0, 0.0, 150000, "EarthTwilight"},
                      OrderOneCase{"mars", 1.0, 30.0, 60.0, 2.0, 0.0, 60000, "Mars"},
                      OrderOneCase{"mars", 1.0, 60.0, 70.0, 0.2, 0.0, 60000, "MarsNearSun"}),
    [](const ::testing::TestParamInfo<OrderOneCase>& test_case) { return std::string(test_case.param.label); });

TEST(ReferencePathTracer, SameSeedGivesIdenticalResultsForAnyThreadCount) {
  const AtmosphereModel m = preset("earth-standard");
  const SunDisc sun{direction_from_angles(degrees(60.0), 0.0)};
  const Vec3 view = direction_from_angles(degrees(70.0), 1.0);
  PathTracerOptions o = options(3000);
  o.thread_count = 1;
  const RadianceEstimate one = path_traced_radiance(m, above_ground(m, 1.0), view, sun, o);
  for (unsigned threads : {2u, 3u}) {
    o.thread_count = threads;
    const RadianceEstimate many = path_traced_radiance(m, above_ground(m, 1.0), view, sun, o);
    for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(one.mean[i]), std::bit_cast<std::uint64_t>(many.mean[i])) << threads;
      EXPECT_EQ(std::bit_cast<std::uint64_t>(one.standard_error[i]),
                std::bit_cast<std::uint64_t>(many.standard_error[i]))
          << threads;
    }
  }
  o.seed = 2;  // another seed: another, statistically compatible, estimate
  const RadianceEstimate other = path_traced_radiance(m, above_ground(m, 1.0), view, sun, o);
  for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
    EXPECT_NE(one.mean[i], other.mean[i]);
    EXPECT_NEAR(one.mean[i], other.mean[i], 4.0 * std::hypot(one.standard_error[i], other.standard_error[i]));
  }
}

TEST(ReferencePathTracer, RaysWithin1e6RadOfTheHorizonGiveFiniteNonNegativeRadiance) {
  const AtmosphereModel m = preset("earth-standard");
  const double r = m.ground_radius_m + 1.0;
  const double horizon_zenith = 0.5 * kPi + std::acos(m.ground_radius_m / r);
  const SunDisc sun{direction_from_angles(degrees(70.0), 0.0)};
  for (double zenith : {horizon_zenith - 1e-6, horizon_zenith + 1e-6, 0.5 * kPi - 1e-6, 0.5 * kPi + 1e-6}) {
    const Vec3 view = direction_from_angles(zenith, 0.3);
    const SingleScatteringResult l1 = single_scattering_radiance(m, above_ground(m, 1.0), view, sun.direction);
    EXPECT_EQ(l1.ray_hits_ground, zenith > horizon_zenith);
    const RadianceEstimate mc = path_traced_radiance(m, above_ground(m, 1.0), view, sun, options(1500));
    EXPECT_EQ(mc.majorant_violations, 0u);
    for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
      for (double v : {l1.atmosphere_radiance[i], l1.ground_radiance[i], mc.mean[i], mc.standard_error[i]}) {
        EXPECT_TRUE(std::isfinite(v)) << zenith;
        EXPECT_GE(v, 0.0) << zenith;
      }
      EXPECT_GT(l1.atmosphere_radiance[i], 0.0);
      EXPECT_GT(mc.mean[i], 0.0);
    }
  }
  // Just above the horizon the ray grazes the ground for ~2000 km and L1 varies smoothly;
  // just below it ends on the ground after ~3.4 km (that distance varies as the square root
  // of the depression, so L1 is continuous only on the upper side).
  const auto l1_at = [&](double zenith) {
    return single_scattering_radiance(m, above_ground(m, 1.0), direction_from_angles(zenith, 0.3), sun.direction)
        .atmosphere_radiance[1];
  };
  EXPECT_NEAR(l1_at(horizon_zenith - 1e-6), l1_at(horizon_zenith - 2e-6), 1e-4 * l1_at(horizon_zenith - 1e-6));
  EXPECT_LT(l1_at(horizon_zenith + 1e-6), 0.2 * l1_at(horizon_zenith - 1e-6));
}

TEST(ReferencePathTracer, DistantObserverMatchesAnObserverAboveTheAtmosphere) {
  const AtmosphereModel m = preset("earth-standard");
  const SunDisc sun{normalize(Vec3{1.0, 0.3, 0.2})};
  const Vec3 far_observer = 40.0 * kAstronomicalUnit_m * normalize(Vec3{0.6, -0.8, 0.1});
  const Vec3 view = normalize(Vec3{m.ground_radius_m, 0.0, 0.0} - far_observer);
  const Vec3 near_observer =
      Ray(far_observer, view).point_at(Ray(far_observer, view).perigee_t_m() - m.top_radius_m - 1e3);
  const RadianceEstimate far = path_traced_radiance(m, far_observer, view, sun, options(4000));
  const RadianceEstimate near = path_traced_radiance(m, near_observer, view, sun, options(4000));
  for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
    EXPECT_GT(far.mean[i], 0.0);
    EXPECT_NEAR(far.mean[i], near.mean[i], 2.0 * far.standard_error[i]);
  }
}

TEST(ReferencePathTracer, ScatteringOrdersAddUpMonotonicallyAndConverge) {
  const AtmosphereModel m = preset("earth-standard");
  const SunDisc sun{direction_from_angles(degrees(45.0), 0.0)};
  const Vec3 view = direction_from_angles(degrees(75.0), 2.0);
  std::vector<Spectrum> partial;  // L(order ≤ k), same sample streams, so sample-wise increasing
  const std::vector<int> orders = {1, 2, 3, 4, 8, 1000};
  for (int k : orders)
    partial.push_back(path_traced_radiance(m, above_ground(m, 1.0), view, sun, options(6000, k)).mean);
  for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
    for (std::size_t k = 1; k < orders.size(); ++k) EXPECT_LE(partial[k - 1][i], partial[k][i] * (1.0 + 1e-12));
    const double second = partial[1][i] - partial[0][i], third = partial[2][i] - partial[1][i],
                 fourth = partial[3][i] - partial[2][i];
    EXPECT_GT(second, third);
    EXPECT_GT(third, fourth);
    EXPECT_LT(partial.back()[i] - partial[4][i], 0.02 * partial.back()[i]);  // orders > 8: under 2%
  }
}

TEST(ReferencePathTracer, BrighterGroundBrightensTheSky) {
  AtmosphereModel dark = preset("earth-standard"), bright = dark;
  dark.ground_albedo = Spectrum(dark.wavelength_count(), 0.0);
  bright.ground_albedo = Spectrum(dark.wavelength_count(), 1.0);
  const SunDisc sun{direction_from_angles(degrees(40.0), 0.0)};
  const Vec3 view = direction_from_angles(degrees(50.0), 2.5);
  const RadianceEstimate d = path_traced_radiance(dark, above_ground(dark, 1.0), view, sun, options(6000));
  const RadianceEstimate b = path_traced_radiance(bright, above_ground(bright, 1.0), view, sun, options(6000));
  for (std::size_t i = 0; i < dark.wavelength_count(); ++i)
    EXPECT_GT(b.mean[i] - d.mean[i], 3.0 * std::hypot(b.standard_error[i], d.standard_error[i]));
}

TEST(ReferencePathTracer, EnergyIsConservedWithoutAbsorption) {
  // No absorption anywhere (Mie extinction = scattering, no absorbers, geometric air
  // mass, white ground): all the power the planet intercepts, π R_top² for a point
  // sun of unit irradiance, leaves through the top sphere, either scattered or
  // unscattered. Scattered: ∫_top ∫_out L cos dω dA, estimated with uniform points on
  // the top sphere and cosine-weighted outward directions as 4π R_top² · π · E[L]. Unscattered:
  // ∫_{R_ground}^{R_top} 2π b T(b) db over the chords that miss the ground.
  // Phases that are exactly normalized but differ from the sampling proposals, so the
  // direction weights P/q are exercised.
  AtmosphereModel m = exponential_model(2.5e-5, 8000.0, 100e3, 1.0);
  m.rayleigh_phase = RayleighPhaseModel::Depolarized;
  m.rayleigh_depolarization = 0.09;
  m.mie_scattering_m1 = m.mie_extinction_m1 = Spectrum{2e-5};
  m.mie_density = DensityProfile::exponential(1200.0);
  m.mie_phase.model = MiePhase::Model::CornetteShanks;
  m.mie_phase.g1 = Spectrum{0.8};
  m.check();
  const SunDisc sun{{0.0, 0.0, 1.0}, 0.0};
  const double top = m.top_radius_m;

  PathSettings settings;
  const PathIntegrator integrator(m, sun, settings);
  ParallelEstimatorSettings s;
  s.samples_per_wavelength = 120000;
  s.seed = 5;
  s.thread_count = 2;
  std::atomic<std::size_t> violations{0};
  const SampleMoments scattered =
      run_parallel_estimator(s, [&](std::size_t i, std::size_t, Pcg32& rng, std::span<double> value) {
        // Uniform point on the top sphere (normal n), cosine-weighted outgoing direction ω;
        // the radiance leaving along ω is what an observer there sees looking along −ω.
        const double z = 2.0 * rng.uniform() - 1.0, phi = 2.0 * kPi * rng.uniform();
        const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
        const Vec3 normal{rho * std::cos(phi), rho * std::sin(phi), z};
        const double u1 = rng.uniform(), u2 = rng.uniform();
        const double radius = std::sqrt(u1), azimuth = 2.0 * kPi * u2;
        const Vec3 t1 =
            normalize(std::abs(normal.x) < 0.9 ? cross(normal, {1.0, 0.0, 0.0}) : cross(normal, {0.0, 1.0, 0.0}));
        const Vec3 t2 = cross(normal, t1);
        const Vec3 out =
            radius * std::cos(azimuth) * t1 + radius * std::sin(azimuth) * t2 + std::sqrt(1.0 - u1) * normal;
        std::size_t local = 0;
        value[0] = 4.0 * kPi * integrator.radiance(Ray(top * normal, -out), i, rng, local);  // P_out / (π R_top²)
        if (local) violations += local;
      });
  EXPECT_EQ(violations.load(), 0u);

  // Unscattered fraction: (1/π R_top²) ∫ 2π b T(b) db, T along the full chord at impact parameter b.
  const std::vector<double> breakpoints = {m.ground_radius_m, m.ground_radius_m + 2e3, m.ground_radius_m + 10e3,
                                           m.ground_radius_m + 40e3, top};
  const QuadratureResult direct = integrate_adaptive(
      [&](double b, std::span<double> v) {
        const Vec3 a{-2.0 * top, b, 0.0}, c{2.0 * top, b, 0.0};
        v[0] = 2.0 * kPi * b * transmittance(m, a, c)[0] / (kPi * top * top);
      },
      breakpoints, 1, QuadratureOptions{1e-8, 0.0, 400});
  const double total = scattered.mean[0] + direct.integral[0];
  EXPECT_GT(scattered.mean[0], 0.3);  // a good part is scattered (the ground alone returns ≈ half)
  EXPECT_NEAR(total, 1.0, 3.0 * scattered.standard_error[0])
      << "scattered " << scattered.mean[0] << " ± " << scattered.standard_error[0] << ", direct " << direct.integral[0];
  EXPECT_LT(scattered.standard_error[0], 0.006);
}

TEST(ReferencePathTracer, GroundIrradianceDirectPartMatchesTheTransmittance) {
  const AtmosphereModel m = preset("earth-standard");
  const SunDisc sun{direction_from_angles(degrees(50.0), 0.0), 0.0};
  const GroundIrradianceEstimate e = ground_irradiance(m, above_ground(m, 0.0), sun, options(20000));
  const Spectrum t = transmittance_to_sun(m, above_ground(m, 0.0), sun.direction);
  EXPECT_EQ(e.majorant_violations, 0u);
  for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
    const double direct = sun.direction.z * t[i];  // μ_s T(ground, sun)
    EXPECT_NEAR(e.direct_mean[i], direct, 3.0 * e.direct_standard_error[i] + 1e-12);
    EXPECT_LT(e.direct_standard_error[i], 0.01 * direct);
    EXPECT_GT(e.diffuse_mean[i], 10.0 * e.diffuse_standard_error[i]);
    EXPECT_LT(e.diffuse_mean[i] + e.direct_mean[i], sun.direction.z);  // less than at the top of the atmosphere
    EXPECT_NEAR(e.total_mean[i], e.direct_mean[i] + e.diffuse_mean[i], 1e-12);
  }
  // Blue sky: more diffuse light at 440 nm than at 680 nm.
  EXPECT_GT(e.diffuse_mean[2], e.diffuse_mean[0]);
}

// ---------------------------------------------------------------------------------------------
// Eclipses: a sphere between the air and the (limb-darkened) disc

/// The sun at the zenith of the observer at `point`, and a sphere of angular
/// radius `radius_rad` centred `separation_rad` from the sun's centre, 380 000 km away.
SunDisc eclipsed_sun(const Vec3& point, double separation_rad, double radius_rad, const LimbDarkening& limb = {}) {
  constexpr double kMoonDistance_m = 3.8e8;
  SunDisc sun;
  sun.direction = normalize(point);
  sun.angular_radius_rad = 4.65e-3;
  if (limb != LimbDarkening{}) sun.limb_darkening = {limb};
  const Vec3 towards = Frame::around(sun.direction).to_world(std::sin(separation_rad), 0.0, std::cos(separation_rad));
  sun.occulter.centre_m = point + kMoonDistance_m * towards;
  sun.occulter.radius_m = kMoonDistance_m * std::sin(radius_rad);
  return sun;
}

/// The direct irradiance on a surface facing the sun at `point` in airless space around the planet:
/// the visible fraction of the disc (per unit solar irradiance), by `n` Monte Carlo samples.
double direct_fraction(const SunDisc& sun, const Vec3& point, std::size_t n) {
  const AtmosphereModel airless = exponential_model(0.0, 8e3, 100e3);
  const PathIntegrator integrator(airless, sun, PathSettings{});
  Pcg32 rng(7, 11);
  std::size_t violations = 0;
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) sum += integrator.direct_irradiance(point, sun.direction, 0, rng, violations);
  return sum / static_cast<double>(n);
}

TEST(ReferenceEclipse, TheDirectSunIsTheUncoveredPartOfTheLimbDarkenedDisc) {
  const AtmosphereModel m = exponential_model(0.0, 8e3, 100e3);
  const Vec3 point = above_ground(m, 0.0);
  const double r_s = 4.65e-3;
  constexpr std::size_t kSamples = 400000;
  // Nothing in the way: the whole disc, limb-darkened or not.
  const LimbDarkening sun_550 = solar_limb_darkening(550.0);
  EXPECT_NEAR(direct_fraction(eclipsed_sun(point, 0.1, 0.0), point, kSamples), 1.0, 2e-3);
  EXPECT_NEAR(direct_fraction(eclipsed_sun(point, 0.1, 0.0, sun_550), point, kSamples), 1.0, 4e-3);
  // Total: a larger sphere on the line to the centre covers every direction of the disc.
  EXPECT_EQ(direct_fraction(eclipsed_sun(point, 0.0, 1.04 * r_s, sun_550), point, 10000), 0.0);
  // Annular, centred (sin ρ / sin r_s = 0.9): with I(μ) = Σ a_k μ^k the uncovered ring is
  // μ < μ_0 = sqrt(1 − 0.81), whose share of the light is Σ a_k μ_0^{k+2}/(k+2) / Σ a_k/(k+2)
  // (sun_disc.h's normalisation integrated up to the sphere's edge) — 0.19 of the disc's area but
  // less of its light, the limb being darkest.
  const double rho = std::asin(0.9 * std::sin(r_s));
  for (const LimbDarkening& law : {LimbDarkening{}, sun_550}) {
    const double mu_0 = std::sqrt(1.0 - 0.81);
    double uncovered = 0.0, whole = 0.0;
    for (std::size_t k = 0; k < law.coefficients.size(); ++k) {
      uncovered += law.coefficients[k] * std::pow(mu_0, double(k + 2)) / double(k + 2);
      whole += law.coefficients[k] / double(k + 2);
    }
    EXPECT_NEAR(direct_fraction(eclipsed_sun(point, 0.0, rho, law), point, kSamples), uncovered / whole, 3e-3)
        << "a_0 = " << law.coefficients[0];
  }
  // Partial, uniform disc: the uncovered area of two overlapping discs of equal radius r at
  // centre distance d is 1 − (2 acos(d/2r) − (d/r) sqrt(1 − d²/4r²)) / π of the disc.
  const double d_over_r = 1.2;
  const double lens = (2.0 * std::acos(0.5 * d_over_r) - d_over_r * std::sqrt(1.0 - 0.25 * d_over_r * d_over_r)) / kPi;
  EXPECT_NEAR(direct_fraction(eclipsed_sun(point, d_over_r * r_s, r_s), point, kSamples), 1.0 - lens, 3e-3);
}

TEST(ReferenceEclipse, AtTotalityTheZenithIsAboutATenThousandthOfItsDaylightAndBluer) {
  // The Earth's advanced preset, the sun 45° up, the Moon 360 000 km away on the
  // line to it (0.277° against the sun's 0.267°: an umbra ~120 km wide on the
  // air). Measured at mid-totality with the sun 40–50° up: ~1e-4 of the
  // uneclipsed zenith (Dandekar & Turtle 1971), and bluer; the light comes from
  // the sunlit air around the umbra, scattered at least twice.
  const AtmosphereModel m = preset("earth-advanced");
  const Vec3 observer = above_ground(m, 2.0);
  const Vec3 to_sun = normalize(Vec3{std::sin(degrees(45.0)), 0.0, std::cos(degrees(45.0))});
  SunDisc day;
  day.direction = to_sun;
  day.angular_radius_rad = 4.65e-3;
  SunDisc total = day;
  total.occulter.centre_m = observer + 3.6e8 * to_sun;
  total.occulter.radius_m = 1737.4e3;
  const RadianceEstimate lit = path_traced_radiance(m, observer, Vec3{0.0, 0.0, 1.0}, day, options(4000));
  const RadianceEstimate dark = path_traced_radiance(m, observer, Vec3{0.0, 0.0, 1.0}, total, options(2000000));
  for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
    const double ratio = dark.mean[i] / lit.mean[i];
    std::printf("%.0f nm: totality/day %.3g (±%.2g)\n", m.wavelengths_nm[i], ratio,
                dark.standard_error[i] / lit.mean[i]);
    EXPECT_GT(ratio, 2e-5) << m.wavelengths_nm[i];
    EXPECT_LT(ratio, 1e-3) << m.wavelengths_nm[i];
  }
  // Bluer than the daylit zenith (measured: ~11 000 K against ~9 000 K): the blue keeps more of its daylight
  // than the red. 2 000 000 paths: each ratio to ~8 %; blue over red 1.9 here.
  EXPECT_GT(dark.mean[2] / lit.mean[2], 1.3 * dark.mean[0] / lit.mean[0]) << "440 nm against 680 nm";
}

}  // namespace
}  // namespace zenith::atmosphere::reference
