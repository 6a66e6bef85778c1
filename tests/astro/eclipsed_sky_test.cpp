// The Moon's shadow on the air (astro/moon_shadow.h) and the eclipsed sky read
// from the tables (astro/eclipsed_sky.h): V against the limb-darkened share of
// astro/solar_eclipse.h, the tables' sky exactly where the Moon is out of the
// way, what totality leaves, the shadow's tables reused as it moves, and bad
// input. Its agreement with the path tracer is `zenith validate eclipse`'s
// (tests/cli/validate_eclipse.cmake).
#include "astro/eclipsed_sky.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <stop_token>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "astro/moon_shadow.h"
#include "astro/sky_positions.h"
#include "astro/solar_eclipse.h"
#include "atmosphere/lut/cpu_precompute.h"
#include "atmosphere/parameters.h"
#include "atmosphere/rayleigh_polarization.h"
#include "atmosphere/reference/path_tracer.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

using atmosphere::AtmosphereModel;
using atmosphere::lut::LookupTables;
using atmosphere::lut::TableQueries;

/// NASA's point of greatest eclipse, 2017-08-21, and a moment in its totality.
const Site kSite{36.9667, -87.6667, 150.0};
AstroTime totality(double seconds_after = 0.0) {
  return AstroTime::from_utc(UtcTime{2017, 8, 21, 18, 25, 27.0}).plus_seconds(seconds_after);
}

struct EclipseSetup {
  EclipseGeometry geometry;
  glm::dvec3 observer_m;
};

EclipseSetup setup_at(const AtmosphereModel& model, const AstroTime& t) {
  const SkyPositions sky(t, kSite);
  const SunAndMoon s = sun_and_moon(sky, model.ground_radius_m + 2.0);
  const double z = s.sun_zenith_deg * core::kDeg, a = s.sun_azimuth_deg * core::kDeg;
  EclipseSetup e;
  e.geometry.moon_centre_m = s.moon_centre_m;
  e.geometry.moon_radius_m = s.moon_radius_m;
  e.geometry.sun_direction = {std::sin(z) * std::cos(a), std::sin(z) * std::sin(a), std::cos(z)};
  e.geometry.sun_angular_radius_rad = s.sun_angular_radius_rad;
  e.geometry.limb_darkening = atmosphere::solar_limb_darkening(model.wavelengths_nm);
  e.observer_m = {0.0, 0.0, model.ground_radius_m + 2.0};
  return e;
}

/// Coarse nodes and few rays: these tests check the shadow's logic, not its accuracy.
MoonShadowOptions quick() {
  MoonShadowOptions o;
  o.field_across = 9;
  o.field_side = 5;
  o.field_altitudes_m = {0.0, 5e3, 20e3, 60e3};
  o.directions = 12;
  o.segments = 6;
  return o;
}

/// The full nodes and half the rays: for tests that compare two shadows of one instant.
MoonShadowOptions fewer_rays() {
  MoonShadowOptions o;
  o.directions = 32;
  o.higher_order_directions = 16;
  return o;
}

/// The same shadow twice: weighting the light's polarization, and not (the scalar transfer's).
struct PolarizedAndScalar {
  MoonShadow polarized, scalar;
};
PolarizedAndScalar polarized_and_scalar(const TableQueries& q, const AtmosphereModel& model, const EclipseSetup& e,
                                        MoonShadowOptions o) {
  MoonShadow polarized(e.geometry, q, model, e.observer_m, o);
  o.polarized = false;
  return {std::move(polarized), MoonShadow(e.geometry, q, model, e.observer_m, o)};
}

class EclipsedSky : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_ = new AtmosphereModel(atmosphere::load_preset("earth-advanced").model);
    atmosphere::lut::PrecomputeOptions o;
    o.sizes = atmosphere::lut::TableSizes::small();
    o.max_orders = 3;
    tables_ = new LookupTables(atmosphere::lut::precompute_tables_cpu(*model_, o));
  }
  static void TearDownTestSuite() {
    delete tables_;
    delete model_;
  }
  static AtmosphereModel* model_;
  static LookupTables* tables_;
};
AtmosphereModel* EclipsedSky::model_ = nullptr;
LookupTables* EclipsedSky::tables_ = nullptr;

TEST_F(EclipsedSky, DirectLightIsTheUncoveredLimbDarkenedShare) {
  const TableQueries q(*model_, *tables_);
  // 40 minutes before totality: a partial phase, the Moon over part of the disc.
  const AstroTime t = totality(-2400.0);
  const EclipseSetup e = setup_at(*model_, t);
  const MoonShadow shadow(e.geometry, q, *model_, e.observer_m, quick());
  const SolarEclipseView view = solar_eclipse_view(SkyPositions(t, kSite));
  ASSERT_EQ(view.kind, EclipseKind::partial);
  for (std::size_t i = 0; i < model_->wavelengths_nm.size(); ++i) {
    const double expected = 1.0 - limb_darkened_obscuration(view.separation_rad, view.sun_radius_rad,
                                                            view.moon_radius_rad, e.geometry.limb_darkening[i]);
    // The profile's 1024 samples, linear between: 1e-4 (ERFA's topocentric place vs sun_and_moon's: 1e-4).
    EXPECT_NEAR(shadow.direct_light(e.observer_m, i), expected, 3e-4) << model_->wavelengths_nm[i] << " nm";
  }
  // 30 km up, 20 km east: V from that point's own separation and Moon radius (the profile's shift of the
  // Moon's radius into x keeps the limbs' distance, good to 1e-3 of the light here).
  const glm::dvec3 p = e.observer_m + glm::dvec3{0.0, 20e3, 30e3};
  const glm::dvec3 to_moon = e.geometry.moon_centre_m - p;
  const double separation = std::atan2(glm::length(glm::cross(to_moon, e.geometry.sun_direction)),
                                       glm::dot(to_moon, e.geometry.sun_direction));
  const double moon_radius = std::asin(e.geometry.moon_radius_m / glm::length(to_moon));
  const double expected = 1.0 - limb_darkened_obscuration(separation, e.geometry.sun_angular_radius_rad, moon_radius,
                                                          e.geometry.limb_darkening[1]);
  EXPECT_NEAR(shadow.direct_light(p, 1), expected, 1e-3);
  EXPECT_NE(shadow.direct_light(p, 1), shadow.direct_light(e.observer_m, 1)) << "the shadow has parallax";
}

TEST_F(EclipsedSky, WithTheMoonOutOfTheWayItIsTheTablesSky) {
  const TableQueries q(*model_, *tables_);
  EclipseSetup e = setup_at(*model_, totality());
  e.geometry.moon_centre_m = -e.geometry.moon_centre_m;  // behind the Earth: no eclipse anywhere
  const MoonShadow shadow(e.geometry, q, *model_, e.observer_m, quick());
  const glm::dvec3 views[] = {{0, 0, 1},
                              glm::normalize(glm::dvec3{1, 0.3, 0.17}),
                              glm::normalize(glm::dvec3{0, 1, 0.02}),
                              glm::normalize(glm::dvec3{-0.5, 0.5, -0.3})};
  for (const glm::dvec3& v : views) {
    const atmosphere::Spectrum eclipsed = eclipsed_sky_radiance(q, *model_, shadow, e.observer_m, v);
    const atmosphere::Spectrum day = q.sky_radiance(e.observer_m, v, e.geometry.sun_direction);
    for (std::size_t i = 0; i < day.size(); ++i)
      EXPECT_NEAR(eclipsed[i], day[i], 1e-9 * day[i]) << "the segments' sum telescopes to the tables' sky";
  }
}

TEST_F(EclipsedSky, TotalityLeavesOnlyLightFromAfar) {
  const TableQueries q(*model_, *tables_);
  const EclipseSetup e = setup_at(*model_, totality());
  ASSERT_EQ(solar_eclipse_view(SkyPositions(totality(), kSite)).kind, EclipseKind::total);
  // The full nodes: the umbra is 100 km across, the quick nodes' first step from the axis 225 km.
  const MoonShadow shadow(e.geometry, q, *model_, e.observer_m);
  const glm::dvec3 up{0, 0, 1};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(shadow.direct_light(e.observer_m, i), 0.0) << "no sunlight in the umbra";
    const double ground = shadow.scattered_light(e.observer_m, up, i);
    const double high = shadow.scattered_light(e.observer_m + 40e3 * up, up, i);
    EXPECT_GT(ground, 0.0);
    EXPECT_LT(ground, 1e-3) << "a thousandth of the scattered light at most reaches the umbra's floor";
    EXPECT_GT(high, 10.0 * ground) << "light from the sunlit air far away reaches the thin upper air";
    // 3 000 km across the axis lies the penumbra's outer edge: the Moon leaves almost all the light.
    const glm::dvec3 far = e.observer_m + 3.6e6 * glm::normalize(glm::cross(up, e.geometry.sun_direction));
    EXPECT_GT(shadow.scattered_light(far, up, i), 0.99);
  }
  // The zenith: dark, but lit; the horizon brighter.
  const atmosphere::Spectrum zenith = eclipsed_sky_radiance(q, *model_, shadow, e.observer_m, up);
  const atmosphere::Spectrum day = q.sky_radiance(e.observer_m, up, e.geometry.sun_direction);
  const atmosphere::Spectrum horizon =
      eclipsed_sky_radiance(q, *model_, shadow, e.observer_m, glm::normalize(glm::dvec3{1, 0, 0.18}));
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_GT(zenith[i], 1e-6 * day[i]);
    EXPECT_LT(zenith[i], 1e-3 * day[i]);
    EXPECT_GT(horizon[i], 3.0 * zenith[i]);
  }
}

TEST_F(EclipsedSky, TheLightOfAllOrdersIsTheOnceAndTheMultiplyScatteredLight) {
  // The second pass of V̄ keeps the first's once-scattered sums and adds the multiply scattered light
  // alone: the two parts must make up the light of all orders, eclipsed and in daylight.
  const TableQueries q(*model_, *tables_);
  const EclipseSetup e = setup_at(*model_, totality(-600.0));  // a partial phase: both parts lit
  const MoonShadow shadow(e.geometry, q, *model_, e.observer_m, quick());
  const glm::dvec3 up{0, 0, 1};
  const glm::dvec3 points[] = {e.observer_m, e.observer_m + glm::dvec3{80e3, -30e3, 6e3}};
  const glm::dvec3 directions[] = {up, glm::normalize(glm::dvec3{1, 0.4, 0.05}),
                                   glm::normalize(glm::dvec3{-1, 0.2, -0.3})};
  for (const glm::dvec3& p : points)
    for (const glm::dvec3& d : directions) {
      const ArrivingLight all = arriving_light(q, *model_, shadow, p, d, 12, ArrivingOrders::all);
      const ArrivingLight once = arriving_light(q, *model_, shadow, p, d, 12, ArrivingOrders::once_scattered);
      const ArrivingLight more = arriving_light(q, *model_, shadow, p, d, 12, ArrivingOrders::multiply_scattered);
      for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_GT(once.eclipsed[i], 0.0);
        EXPECT_GT(more.eclipsed[i], 0.0);
        EXPECT_NEAR(all.eclipsed[i], once.eclipsed[i] + more.eclipsed[i], 1e-12 * all.eclipsed[i]);
        EXPECT_NEAR(all.daylight[i], once.daylight[i] + more.daylight[i], 1e-12 * all.daylight[i]);
        EXPECT_LT(all.eclipsed[i], all.daylight[i]);
      }
    }
}

TEST_F(EclipsedSky, TheSecondPassGivesTheHigherOrdersTheLightFromFarther) {
  // In totality the higher orders come from farther than the second, where more of the Sun is left, and
  // more so in the blue (the path tracer: two thirds to three quarters of the zenith's light at 440 nm,
  // half at 550): V̄ from the once-scattered light alone leaves the zenith too dark, most in the blue
  // (docs/validation.md, "Eclipses"). Fewer rays than the defaults, the same nodes. The blue's larger gain
  // is V̄'s at the zenith's air (2 km up, these tables: 1.9, 2.4 and 4.1 times at 680, 550 and 440 nm);
  // the zenith itself gains alike at the three (1.28, 1.26, 1.27), its aerosols' forward share, largest
  // in the red, scattering on the light the second pass adds along the view ray itself
  // (astro/eclipsed_sky.h).
  const TableQueries q(*model_, *tables_);
  const EclipseSetup e = setup_at(*model_, totality());
  MoonShadowOptions o = fewer_rays();
  o.iterations = 1;
  const MoonShadow one(e.geometry, q, *model_, e.observer_m, o);
  o.iterations = 2;
  const MoonShadow two(e.geometry, q, *model_, e.observer_m, o);
  const glm::dvec3 up{0, 0, 1};
  const atmosphere::Spectrum first = eclipsed_sky_radiance(q, *model_, one, e.observer_m, up);
  const atmosphere::Spectrum both = eclipsed_sky_radiance(q, *model_, two, e.observer_m, up);
  std::printf("zenith, two passes over one: %.3f %.3f %.3f (680, 550, 440 nm)\n", both[0] / first[0],
              both[1] / first[1], both[2] / first[2]);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_GT(both[i], 1.2 * first[i]) << model_->wavelengths_nm[i] << " nm";
  const glm::dvec3 air = e.observer_m + 2e3 * up;
  double gain[3];
  for (std::size_t i = 0; i < 3; ++i) gain[i] = two.scattered_light(air, up, i) / one.scattered_light(air, up, i);
  std::printf("V̄ 2 km over the zenith, two passes over one: %.3f %.3f %.3f\n", gain[0], gain[1], gain[2]);
  EXPECT_GT(gain[0], 1.5);
  EXPECT_GT(gain[2], gain[1]);
  EXPECT_GT(gain[1], gain[0]) << "the blue gains most";
}

TEST_F(EclipsedSky, ThePolarizationOfTheLightFromAfarBrightensTheTotalityZenithAsVectorTransferDoes) {
  // In totality the zenith's air is lit sideways by once-scattered, polarized light and turns it up by
  // about 90°, where a dipole scatters the two polarizations most differently: the vector path tracer's
  // zenith at mid-totality is 15–30 % brighter than the scalar one's (docs/validation.md, "Eclipses").
  // V̄ weighting the light's polarization must move the tables' zenith the same way — brighter, the red
  // (scattered fewer times) more than the blue — by most of what the path tracer gains and never more
  // (these small tables and fewer rays: +21, +20, +16 % at 680, 550, 440 nm against +28, +32, +22 %:
  // the aerosols, unpolarized, scatter their delta-M share of the sideways light, which dilutes the
  // gas's gain; with their cut phase function clipped at 0 there, +25, +23, +17 %. Over the daylight
  // weighted with its polarization, V̄'s denominator before it became the scalar tables' own, +20, +17,
  // +12 %, and with the once-scattered light's polarization alone +16, +12, +6 %, both without delta-M,
  // which lowers every gain). The path tracer's two estimates share their paths, so their ratio is far
  // steadier than either; its own gain must be over 10 % at each of these three wavelengths.
  const TableQueries q(*model_, *tables_);
  const EclipseSetup e = setup_at(*model_, totality());
  const PolarizedAndScalar shadows = polarized_and_scalar(q, *model_, e, fewer_rays());
  const glm::dvec3 up{0, 0, 1};
  const atmosphere::Spectrum tables_vector = eclipsed_sky_radiance(q, *model_, shadows.polarized, e.observer_m, up);
  const atmosphere::Spectrum tables_scalar = eclipsed_sky_radiance(q, *model_, shadows.scalar, e.observer_m, up);

  atmosphere::reference::SunDisc sun;
  sun.direction = e.geometry.sun_direction;
  sun.angular_radius_rad = e.geometry.sun_angular_radius_rad;
  sun.limb_darkening = e.geometry.limb_darkening;
  sun.occulter = {e.geometry.moon_centre_m, e.geometry.moon_radius_m};
  atmosphere::reference::PathTracerOptions paths;
  paths.samples_per_wavelength = 400000;
  const auto reference_scalar = atmosphere::reference::path_traced_radiance(*model_, e.observer_m, up, sun, paths);
  paths.polarized = true;
  const auto reference_vector = atmosphere::reference::path_traced_radiance(*model_, e.observer_m, up, sun, paths);
  double tables_gain[3], reference_gain[3];
  for (std::size_t i = 0; i < 3; ++i) {
    tables_gain[i] = tables_vector[i] / tables_scalar[i];
    reference_gain[i] = reference_vector.mean[i] / reference_scalar.mean[i];
    std::printf("%.0f nm: vector / scalar zenith, tables %.3f, path tracer %.3f\n", model_->wavelengths_nm[i],
                tables_gain[i], reference_gain[i]);
    EXPECT_GT(reference_gain[i], 1.1) << model_->wavelengths_nm[i] << " nm";
    EXPECT_GT(tables_gain[i], 1.0 + 0.6 * (reference_gain[i] - 1.0)) << model_->wavelengths_nm[i] << " nm";
    EXPECT_LT(tables_gain[i], reference_gain[i] + 0.03) << model_->wavelengths_nm[i] << " nm";
  }
  EXPECT_GT(tables_gain[0], tables_gain[2]) << "680 nm gains more than 440 nm";
}

TEST_F(EclipsedSky, TheLightTheAirScattersOnIsPolarizedAcrossItsWay) {
  // What the air at a point scatters along v is polarized by eq. (1) of the coherency arriving there: its
  // excess Π(v) − 2N, the gas's share of it, lies across v and is traceless, its eigenvalues within ±1
  // (N has trace 1 and no negative part); V̄ is scattered_light's; far beyond the penumbra the light is
  // the daylight's, polarized still; a scalar shadow has none.
  const TableQueries q(*model_, *tables_);
  const EclipseSetup e = setup_at(*model_, totality());
  const PolarizedAndScalar shadows = polarized_and_scalar(q, *model_, e, quick());
  const MoonShadow &shadow = shadows.polarized, &scalar = shadows.scalar;
  const glm::dvec3 basis[3] = {shadow.axis_1(), shadow.axis_2(), e.geometry.sun_direction};
  const auto world = [&](const ShadowTensor& t) {
    const double c[3][3] = {{t[0], t[3], t[4]}, {t[3], t[1], t[5]}, {t[4], t[5], t[2]}};
    glm::dmat3 m(0.0);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) m += c[a][b] * glm::outerProduct(basis[a], basis[b]);
    return m;
  };
  const glm::dvec3 up{0, 0, 1};
  const glm::dvec3 points[] = {e.observer_m + 10e3 * up, e.observer_m + glm::dvec3{-60e3, 45e3, 3e3},
                               e.observer_m + glm::dvec3{40e3, -70e3, 1e3}};
  const glm::dvec3 directions[] = {up, glm::normalize(glm::dvec3{1, 0.4, 0.05}),
                                   glm::normalize(glm::dvec3{-0.3, -1, 0.6})};
  double largest = 0.0;
  for (const glm::dvec3& p : points)
    for (const glm::dvec3& v : directions)
      for (std::size_t i = 0; i < 3; ++i) {
        const MoonShadow::Place place = shadow.place(p);
        const MoonShadow::ScatteredLight light = shadow.polarized_scattered_light(place, v, i);
        EXPECT_NEAR(light.share_left, shadow.scattered_light(place, v, i), 1e-12);
        const glm::dmat3 m = world(light.excess);
        EXPECT_NEAR(m[0][0] + m[1][1] + m[2][2], 0.0, 1e-9);
        EXPECT_NEAR(glm::length(m * v), 0.0, 1e-9);
        // Across v the excess is diag(λ, −λ): λ² = −det of the 2×2 block = tr(m²)/2.
        const double lambda = std::sqrt(0.5 * atmosphere::contract(m, m));
        EXPECT_LE(lambda, 1.0);
        largest = std::max(largest, lambda);
        const MoonShadow::ScatteredLight none = scalar.polarized_scattered_light(place, v, i);
        EXPECT_NEAR(none.share_left, scalar.scattered_light(place, v, i), 1e-12);
        for (std::size_t c = 0; c < 6; ++c) EXPECT_EQ(none.excess[c], 0.0);
      }
  EXPECT_GT(largest, 0.1) << "the light scattered on is partly polarized";
  // Past twice the field's reach off the axis V̄ = 1, and the daylight the air scatters up there, lit from
  // the side by the sun, is polarized across its way.
  const glm::dvec3 far = e.observer_m + 2.2 * shadow.field_end_m() * shadow.axis_2();
  const MoonShadow::ScatteredLight beyond = shadow.polarized_scattered_light(shadow.place(far), up, 1);
  EXPECT_EQ(beyond.share_left, 1.0);
  const glm::dmat3 daylight = world(beyond.excess);
  EXPECT_NEAR(glm::length(daylight * up), 0.0, 1e-9);
  EXPECT_GT(std::sqrt(0.5 * atmosphere::contract(daylight, daylight)), 0.05);
}

TEST_F(EclipsedSky, TheAerosolsForwardShareScattersOnTheViewRaysOwnLight) {
  // Low in the umbra, along a ray 10° up, most of what the air scatters toward the camera is the
  // aerosols' (61–92 % at 440–680 nm, 0.35–1.7 km up), and their forward peak scatters on the light
  // arriving from straight behind: the sunlit air far beyond the umbra, low on the air's horizon, which
  // the node's terms l ≤ 2 smear into the dark sky around it. V̄ there against the phase functions themselves
  // weighting the light arriving from 2 000 directions (scalar: the shadow without polarization; the
  // default nodes and rays): with the view ray's own light from behind (eclipsed_sky_radiance's) 0.75–0.92
  // of it here, without 0.63–0.74. What is left is the peak's width, which delta-M makes a line: it also
  // gathers the brighter light from just below v.
  const TableQueries q(*model_, *tables_);
  const EclipseSetup e = setup_at(*model_, totality());
  MoonShadowOptions o;
  o.polarized = false;
  const MoonShadow shadow(e.geometry, q, *model_, e.observer_m, o);
  const glm::dvec3 up{0, 0, 1};
  const glm::dvec3 v = std::cos(10.0 * core::kDeg) * glm::dvec3{0, 1, 0} + std::sin(10.0 * core::kDeg) * up;
  constexpr int kDirections = 2000;
  for (const double distance_m : {2e3, 5e3, 10e3}) {
    const glm::dvec3 p = e.observer_m + distance_m * v;
    const double altitude_m = glm::length(p) - model_->ground_radius_m;
    double weighted_eclipsed[3] = {}, weighted_daylight[3] = {};
    for (int n = 0; n < kDirections; ++n) {
      // A Fibonacci sphere: equal areas.
      const double z = 1.0 - (2.0 * n + 1.0) / kDirections, r = std::sqrt(1.0 - z * z), phi = 2.399963229728653 * n;
      const glm::dvec3 d{r * std::cos(phi), r * std::sin(phi), z};
      const ArrivingLight l = arriving_light(q, *model_, shadow, p, d, 24, ArrivingOrders::all);
      const double c = glm::dot(d, v);
      for (std::size_t i = 0; i < 3; ++i) {
        const double w = model_->rayleigh_scattering_m1[i] * model_->rayleigh_density(altitude_m) *
                             model_->rayleigh_phase_function(c) +
                         model_->mie_scattering_m1[i] * model_->mie_density(altitude_m) * model_->mie_phase(i, c);
        weighted_eclipsed[i] += w * l.eclipsed[i];
        weighted_daylight[i] += w * l.daylight[i];
      }
    }
    const ArrivingLight behind = arriving_light(q, *model_, shadow, p, v, 24, ArrivingOrders::all);
    const MoonShadow::Place place = shadow.place(p);
    for (std::size_t i = 0; i < 3; ++i) {
      const double exact = weighted_eclipsed[i] / weighted_daylight[i];
      const double own = shadow.scattered_light(place, v, i, behind.eclipsed[i] / behind.daylight[i]);
      const double nodes = shadow.scattered_light(place, v, i);
      std::printf("%.0f m up, %.0f nm: V̄ over the phase-weighted light %.3f with the ray's own, %.3f without\n",
                  altitude_m, model_->wavelengths_nm[i], own / exact, nodes / exact);
      EXPECT_GT(own / exact, 0.7) << altitude_m << " m, " << model_->wavelengths_nm[i] << " nm";
      EXPECT_LT(own / exact, 1.05) << altitude_m << " m, " << model_->wavelengths_nm[i] << " nm";
      EXPECT_GT(own - nodes, 0.05 * exact) << altitude_m << " m, " << model_->wavelengths_nm[i] << " nm";
    }
  }
}

TEST_F(EclipsedSky, TheAerosolsForwardPeakIsSplitOffByDeltaM) {
  // earth-advanced's aerosol is one Henyey–Greenstein lobe of g = 0.85, whose Legendre terms are g^l: delta-M
  // sends f = g⁵ straight on and keeps the terms l ≤ 4 of the whole, (1 − f) k_l' + f = g^l; the gas's
  // phase function is l ≤ 2, so it has no forward share (astro/moon_shadow.h).
  const TableQueries q(*model_, *tables_);
  const EclipseSetup e = setup_at(*model_, totality());
  const MoonShadow shadow(e.geometry, q, *model_, e.observer_m, quick());
  const double g = 0.85;
  for (std::size_t i = 0; i < 3; ++i) {
    const MoonShadow::Scatterer& aerosol = shadow.mie_scatterers()[i];
    const double f = aerosol.forward;
    EXPECT_NEAR(f, std::pow(g, 5), 1e-6);
    EXPECT_NEAR((1.0 - f) * aerosol.k1 + f, g, 1e-6);
    EXPECT_NEAR((1.0 - f) * aerosol.k2 + f, std::pow(g, 2), 1e-6);
    EXPECT_NEAR((1.0 - f) * aerosol.k3 + f, std::pow(g, 3), 1e-6);
    EXPECT_NEAR((1.0 - f) * aerosol.k4 + f, std::pow(g, 4), 1e-6);
    const MoonShadow::Scatterer& gas = shadow.rayleigh_scatterers()[i];
    EXPECT_EQ(gas.forward, 0.0);
    EXPECT_NEAR(gas.k1, 0.0, 1e-9);
    EXPECT_NEAR(gas.k3, 0.0, 1e-9);
    EXPECT_NEAR(gas.k4, 0.0, 1e-9);
  }
}

TEST_F(EclipsedSky, TheShadowsTablesFollowItAsItMoves) {
  const TableQueries q(*model_, *tables_);
  const EclipseSetup now = setup_at(*model_, totality(-20.0));
  MoonShadow shadow(now.geometry, q, *model_, now.observer_m, quick());
  const EclipseSetup soon = setup_at(*model_, totality(20.0));
  const EclipseSetup later = setup_at(*model_, totality(1800.0));
  EXPECT_TRUE(shadow.still_fits(soon.geometry, soon.observer_m)) << "40 s about greatest eclipse: b hardly moves";
  EXPECT_FALSE(shadow.still_fits(later.geometry, later.observer_m))
      << "half an hour: the axis' zenith angle moves ~10°";
  shadow.move_to(soon.geometry, soon.observer_m);
  const MoonShadow fresh(soon.geometry, q, *model_, soon.observer_m, quick());
  const glm::dvec3 up{0, 0, 1};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(shadow.direct_light(soon.observer_m + 10e3 * up, i), fresh.direct_light(soon.observer_m + 10e3 * up, i),
                1e-6);
    const double moved = shadow.scattered_light(soon.observer_m + 10e3 * up, up, i);
    const double built = fresh.scattered_light(soon.observer_m + 10e3 * up, up, i);
    EXPECT_NEAR(moved, built, 0.05 * built);
  }
}

TEST_F(EclipsedSky, ItIsRebuiltWhenTheAxisMovesNotWhenTheCameraDoes) {
  // The tables hold for the same distance b of the axis from the planet's centre: a camera 500 km away
  // reads them still. 35 minutes before greatest eclipse the axis' zenith angle moves ~0.4° a minute:
  // 30 s later the tables still fit and a moved shadow is a fresh one to 0.5 %; 60 s later they do not.
  const TableQueries q(*model_, *tables_);
  const EclipseSetup now = setup_at(*model_, totality(-2100.0));
  MoonShadow shadow(now.geometry, q, *model_, now.observer_m, quick());
  const glm::dvec3 away = glm::normalize(now.observer_m + glm::dvec3(500e3, 0.0, 0.0)) * glm::length(now.observer_m);
  EXPECT_TRUE(shadow.still_fits(now.geometry, away));
  const EclipseSetup soon = setup_at(*model_, totality(-2070.0)), later = setup_at(*model_, totality(-2040.0));
  EXPECT_TRUE(shadow.still_fits(soon.geometry, soon.observer_m));
  EXPECT_FALSE(shadow.still_fits(later.geometry, later.observer_m));
  shadow.move_to(soon.geometry, soon.observer_m);
  const MoonShadow fresh(soon.geometry, q, *model_, soon.observer_m, quick());
  double worst = 0.0;
  for (const glm::dvec3& view : {glm::dvec3{0, 0, 1}, glm::normalize(glm::dvec3{1, 0, 1}),
                                 glm::normalize(glm::dvec3{0, -1, 0.2}), glm::normalize(glm::dvec3{-1, 0.3, 0.05})}) {
    const atmosphere::Spectrum a = eclipsed_sky_radiance(q, *model_, shadow, soon.observer_m, view);
    const atmosphere::Spectrum b = eclipsed_sky_radiance(q, *model_, fresh, soon.observer_m, view);
    for (std::size_t i = 0; i < 3; ++i) worst = std::max(worst, std::abs(a[i] / b[i] - 1.0));
  }
  std::printf("a shadow moved for 30 s against one built for the instant: %.2e\n", worst);
  EXPECT_LT(worst, 0.005);
}

TEST_F(EclipsedSky, AShadowWhoseBuildIsStoppedThrowsInsteadOfFinishing) {
  // A renderer going away stops the shadow its worker thread is building (render/frame/eclipse_sky_table.h):
  // every node of V̄'s table checks the stop, so the build ends at the first one.
  const TableQueries q(*model_, *tables_);
  const EclipseSetup e = setup_at(*model_, totality());
  std::stop_source stop;
  stop.request_stop();
  EXPECT_THROW(MoonShadow(e.geometry, q, *model_, e.observer_m, quick(), stop.get_token()), ShadowBuildStopped);
  // Not stopped: built as before.
  EXPECT_NO_THROW(MoonShadow(e.geometry, q, *model_, e.observer_m, quick(), std::stop_source().get_token()));
}

TEST_F(EclipsedSky, RefusesWhatIsNoEclipse) {
  const TableQueries q(*model_, *tables_);
  const EclipseSetup good = setup_at(*model_, totality());
  const auto refuses = [&](EclipseSetup e, const char* what) {
    EXPECT_THROW(MoonShadow(e.geometry, q, *model_, e.observer_m, quick()), std::invalid_argument) << what;
  };
  EclipseSetup e = good;
  e.geometry.moon_radius_m = 0.0;
  refuses(e, "no Moon");
  e = good;
  e.geometry.limb_darkening.pop_back();
  refuses(e, "a limb darkening law missing");
  e = good;
  e.geometry.limb_darkening[0].coefficients[0] = 11.0;
  refuses(e, "limb darkening coefficients that do not sum to 1");
  e = good;
  e.geometry.sun_direction *= 2.0;
  refuses(e, "a sun direction not of unit length");
  e = good;
  e.observer_m = e.geometry.moon_centre_m;
  refuses(e, "a camera inside the Moon");
  e = good;
  e.geometry.moon_centre_m.x = std::nan("");
  refuses(e, "a non-finite Moon");
  MoonShadowOptions o = quick();
  o.field_altitudes_m = {1e3, 5e3};
  EXPECT_THROW(MoonShadow(good.geometry, q, *model_, good.observer_m, o), std::invalid_argument)
      << "the field's altitudes must start at the ground";
  o = quick();
  o.iterations = 0;
  EXPECT_THROW(MoonShadow(good.geometry, q, *model_, good.observer_m, o), std::invalid_argument) << "no pass";
  o = quick();
  o.higher_order_directions = 0;
  EXPECT_THROW(MoonShadow(good.geometry, q, *model_, good.observer_m, o), std::invalid_argument)
      << "no ray for the higher orders";
}

}  // namespace
}  // namespace zenith::astro
