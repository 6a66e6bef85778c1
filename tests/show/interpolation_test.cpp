// The interpolants of show tracks: monotone cubic, centripetal Catmull–Rom,
// squad, quantization, key lookup.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/units.h"
#include "show/catmull_rom.h"
#include "show/key_span.h"
#include "show/monotone_cubic.h"
#include "show/parameter_track.h"
#include "show/squad.h"
#include "show/sun_track.h"

namespace zenith::show {
namespace {

using core::kPi;

TEST(KeySpan, LocatesTimesAmongKeys) {
  const std::vector<double> t{0.0, 2.0, 6.0};
  EXPECT_EQ(locate(t, -1.0).segment, 0u);
  EXPECT_EQ(locate(t, -1.0).fraction, 0.0);
  EXPECT_EQ(locate(t, 1.0).segment, 0u);
  EXPECT_DOUBLE_EQ(locate(t, 1.0).fraction, 0.5);
  EXPECT_EQ(locate(t, 2.0).segment, 1u);
  EXPECT_EQ(locate(t, 2.0).fraction, 0.0);
  EXPECT_DOUBLE_EQ(locate(t, 5.0).fraction, 0.75);
  EXPECT_EQ(locate(t, 6.0).segment, 1u);
  EXPECT_EQ(locate(t, 6.0).fraction, 1.0);
  EXPECT_EQ(locate(t, 60.0).fraction, 1.0);
  EXPECT_EQ(locate({3.0}, 10.0).segment, 0u);
}

TEST(MonotoneCubic, PassesThroughKeysExactly) {
  const std::vector<double> t{0.0, 1.0, 2.5, 4.0, 7.0}, y{0.0, 0.1, 3.0, 3.0, -1.0 / 3.0};
  const MonotoneCubic f(t, y);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_EQ(f(t[i]), y[i]) << i;
  EXPECT_EQ(f(-5.0), 0.0);
  EXPECT_EQ(f(50.0), -1.0 / 3.0);
}

TEST(MonotoneCubic, NeverOvershootsMonotoneData) {
  // A step-like data set on which a natural cubic spline rings badly.
  const std::vector<double> t{0, 1, 2, 3, 4, 5, 6}, y{0, 0, 0, 1, 1, 1, 1};
  const MonotoneCubic f(t, y);
  double previous = f(0.0);
  for (int i = 1; i <= 6000; ++i) {
    const double x = i * 1e-3, v = f(x);
    ASSERT_GE(v, 0.0) << x;
    ASSERT_LE(v, 1.0) << x;
    ASSERT_GE(v, previous - 1e-15) << x;  // non-decreasing
    previous = v;
  }
  EXPECT_EQ(f(1.5), 0.0);  // flat where the neighbouring keys are equal
  EXPECT_EQ(f(4.5), 1.0);
  EXPECT_DOUBLE_EQ(f(2.5), 0.5);  // symmetric step: the midpoint
}

TEST(MonotoneCubic, SteepDataIsLimitedByFritschCarlson) {
  // Secants 1 and 100: the mean tangent 50.5 would overshoot on [0, 1].
  const MonotoneCubic f({0.0, 1.0, 2.0}, {0.0, 1.0, 101.0});
  for (int i = 0; i <= 1000; ++i) {
    const double v = f(i * 1e-3);
    ASSERT_GE(v, 0.0);
    ASSERT_LE(v, 1.0);
  }
  // α² + β² ≤ 9 after limiting: tangents at key 1 at most 3 × the secant 1.
  EXPECT_LE(f.derivative(1.0 - 1e-12), 3.0 + 1e-6);
}

TEST(MonotoneCubic, TwoKeysAreLinear) {
  const MonotoneCubic f({2.0, 6.0}, {10.0, 30.0});
  EXPECT_DOUBLE_EQ(f(3.0), 15.0);
  EXPECT_DOUBLE_EQ(f(5.0), 25.0);
  EXPECT_DOUBLE_EQ(f.derivative(4.0), 5.0);
}

TEST(MonotoneCubic, DerivativeIsContinuousAtKeys) {
  const MonotoneCubic f({0.0, 1.0, 3.0, 4.0}, {0.0, 2.0, 3.0, 7.0});
  for (double key : {1.0, 3.0}) EXPECT_NEAR(f.derivative(key - 1e-9), f.derivative(key + 1e-9), 1e-6) << key;
}

TEST(MonotoneCubic, RejectsBadKeys) {
  EXPECT_THROW(MonotoneCubic({}, {}), std::invalid_argument);
  EXPECT_THROW(MonotoneCubic({0.0, 0.0}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(MonotoneCubic({0.0, 1.0}, {1.0}), std::invalid_argument);
}

TEST(CatmullRom, ReproducesEvenlySpacedStraightLine) {
  // Evenly spaced collinear keys: equal centripetal knots, the line at constant speed.
  std::vector<glm::dvec3> keys;
  for (int i = 0; i < 5; ++i) keys.emplace_back(1.0 + 3.0 * i, -2.0 * i, 0.5 * i);
  const CentripetalCatmullRom spline(keys);
  ASSERT_EQ(spline.segments(), 4u);
  for (std::size_t s = 0; s < 4; ++s)
    for (double f : {0.0, 0.1, 0.25, 0.5, 0.9, 1.0}) {
      const glm::dvec3 expected = keys[s] + f * (keys[s + 1] - keys[s]);
      const glm::dvec3 got = spline.at(s, f);
      EXPECT_NEAR(glm::length(got - expected), 0.0, 1e-12) << s << " " << f;
    }
}

TEST(CatmullRom, EqualChordsOnACircleMatchTheUniformClosedForm) {
  // Keys evenly spaced on a circle have equal chords, so the centripetal knots
  // are uniform and the segment is the classic closed form
  //   P(u) = ½ [2P1 + (−P0 + P2) u + (2P0 − 5P1 + 4P2 − P3) u² + (−P0 + 3P1 − 3P2 + P3) u³].
  std::vector<glm::dvec3> keys;
  const double radius = 7.0e6, step = kPi / 8.0;
  for (int i = 0; i < 6; ++i) keys.emplace_back(radius * std::cos(i * step), radius * std::sin(i * step), 0.0);
  const CentripetalCatmullRom spline(keys);
  for (std::size_t s = 1; s < 4; ++s)
    for (double u : {0.2, 0.5, 0.7}) {
      const glm::dvec3 &p0 = keys[s - 1], &p1 = keys[s], &p2 = keys[s + 1], &p3 = keys[s + 2];
      const glm::dvec3 closed = 0.5 * (2.0 * p1 + (-p0 + p2) * u + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u * u +
                                       (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * u * u * u);
      EXPECT_NEAR(glm::length(spline.at(s, u) - closed), 0.0, 1e-8 * radius) << s << " " << u;
      // And close to the circle itself: 22.5° chords deviate by < 0.1 % of the radius.
      EXPECT_NEAR(glm::length(spline.at(s, u)), radius, 1e-3 * radius);
    }
  // Exactly the keys at the ends of segments.
  EXPECT_EQ(spline.at(2, 0.0), keys[2]);
  EXPECT_EQ(spline.at(2, 1.0), keys[3]);
}

TEST(CatmullRom, UnevenKeysMakeNoLoop) {
  // A tight corner after a long leg: uniform Catmull–Rom overshoots into a
  // loop; the centripetal spline stays within the keys' bounding box.
  const std::vector<glm::dvec3> keys{{0, 0, 0}, {100, 0, 0}, {101, 1, 0}, {101, 101, 0}};
  const CentripetalCatmullRom spline(keys);
  for (int i = 0; i <= 100; ++i) {
    const glm::dvec3 p = spline.at(1, i / 100.0);
    EXPECT_LE(p.x, 101.0 + 0.5) << i;
    EXPECT_GE(p.y, -0.5) << i;
  }
}

TEST(CatmullRom, SingleKeyAndRepeatedKeysAreConstant) {
  const CentripetalCatmullRom one({{1, 2, 3}});
  EXPECT_EQ(one.at(0, 0.5), glm::dvec3(1, 2, 3));
  const CentripetalCatmullRom hold({{0, 0, 0}, {5, 0, 0}, {5, 0, 0}, {9, 0, 0}});
  EXPECT_EQ(hold.at(1, 0.5), glm::dvec3(5, 0, 0));
  const glm::dvec3 p = hold.at(0, 0.5);
  EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
}

glm::dquat axis_angle(double angle_rad, glm::dvec3 axis) { return glm::angleAxis(angle_rad, glm::normalize(axis)); }

TEST(Squad, HitsKeysAndStaysUnit) {
  const std::vector<glm::dquat> keys{axis_angle(0.0, {0, 0, 1}), axis_angle(0.7, {0, 0, 1}), axis_angle(1.2, {1, 1, 0}),
                                     axis_angle(2.5, {0, 1, 0.2})};
  const SquadCurve curve(keys);
  for (std::size_t s = 0; s < 3; ++s) {
    EXPECT_EQ(curve.at(s, 0.0), curve.keys()[s]);
    EXPECT_EQ(curve.at(s, 1.0), curve.keys()[s + 1]);
    for (int i = 0; i <= 50; ++i) EXPECT_NEAR(glm::length(curve.at(s, i / 50.0)), 1.0, 1e-14);
  }
  // The keys are the same rotations as given (up to sign).
  for (std::size_t i = 0; i < keys.size(); ++i) EXPECT_NEAR(std::abs(glm::dot(curve.keys()[i], keys[i])), 1.0, 1e-15);
}

TEST(Squad, FlipsSignsForTheShortestArc) {
  // −q is q: a key given with the opposite sign must not make a 360° detour.
  const glm::dquat a = axis_angle(0.2, {0, 0, 1}), b = -axis_angle(0.4, {0, 0, 1});
  const SquadCurve curve({a, b});
  const glm::dquat mid = curve.at(0, 0.5);
  const glm::dquat expected = axis_angle(0.3, {0, 0, 1});
  EXPECT_NEAR(std::abs(glm::dot(mid, expected)), 1.0, 1e-12);
  EXPECT_GT(glm::dot(curve.keys()[0], curve.keys()[1]), 0.0);
}

TEST(Squad, OnOneAxisWithEvenKeysIsUniformRotation) {
  // Evenly spaced keys about one axis: the control points coincide with the
  // keys' geodesic, so squad is the uniform rotation.
  std::vector<glm::dquat> keys;
  for (int i = 0; i < 4; ++i) keys.push_back(axis_angle(0.5 * i, {0, 1, 0}));
  const SquadCurve curve(keys);
  for (double h : {0.25, 0.5, 0.8}) {
    const glm::dquat expected = axis_angle(0.5 * (1 + h), {0, 1, 0});
    EXPECT_NEAR(std::abs(glm::dot(curve.at(1, h), expected)), 1.0, 1e-12) << h;
  }
}

TEST(Squad, AngularVelocityIsContinuousAtAKey) {
  const SquadCurve curve({axis_angle(0.0, {0, 0, 1}), axis_angle(0.6, {0, 0, 1}), axis_angle(1.0, {1, 0, 1})});
  const double e = 1e-6;
  // Angular velocity ω = 2 q̇ q⁻¹ by finite differences on both sides of key 1 (equal segment durations).
  const glm::dquat k = curve.at(1, 0.0);
  const glm::dquat before = (k - curve.at(0, 1.0 - e)) * (1.0 / e) * glm::conjugate(k) * 2.0;
  const glm::dquat after = (curve.at(1, e) - k) * (1.0 / e) * glm::conjugate(k) * 2.0;
  EXPECT_NEAR(before.x, after.x, 1e-4);
  EXPECT_NEAR(before.y, after.y, 1e-4);
  EXPECT_NEAR(before.z, after.z, 1e-4);
}

TEST(QuaternionLogExp, AreInverse) {
  const glm::dquat q = axis_angle(2.9, {1, -2, 0.5});
  const glm::dquat back = quaternion_exp(quaternion_log(q));
  EXPECT_NEAR(std::abs(glm::dot(q, back)), 1.0, 1e-15);
  EXPECT_NEAR(glm::length(quaternion_log(q)), 1.45, 1e-12);  // half the angle
}

TEST(Quantization, RoundsToTheNearestStep) {
  EXPECT_EQ(quantize(2.0, 0.25), 8);
  EXPECT_EQ(quantize(2.124, 0.25), 8);
  EXPECT_EQ(quantize(2.126, 0.25), 9);
  EXPECT_EQ(quantize(-0.3, 0.25), -1);
  EXPECT_EQ(quantized_value(3, 0.1), 0.3);  // not 0.30000000000000004
  EXPECT_EQ(quantized_value(9, 0.25), 2.25);
}

TEST(ParameterTrack, NumericValuesAreQuantizedMonotoneCubics) {
  const ParameterTrack track(nlohmann::json::json_pointer("/aerosol/scattering/turbidity"), 0.5,
                             {{0.0, 3.0}, {10.0, 2.0}});
  EXPECT_EQ(track.value_at(0.0), 3.0);
  EXPECT_EQ(track.value_at(2.4), 3.0);  // raw 2.76 → 3.0
  EXPECT_EQ(track.value_at(2.6), 2.5);  // raw 2.74 → 2.5
  EXPECT_EQ(track.value_at(7.4), 2.5);  // raw 2.26 → 2.5
  EXPECT_EQ(track.value_at(7.6), 2.0);  // raw 2.24 → 2.0
  EXPECT_EQ(track.value_at(99.0), 2.0);
  nlohmann::json parameters = {{"aerosol", {{"scattering", {{"turbidity", 9.0}, {"K", 1}}}}}};
  track.apply(parameters, 5.0);
  EXPECT_EQ(parameters["aerosol"]["scattering"]["turbidity"], 2.5);
  EXPECT_EQ(parameters["aerosol"]["scattering"]["K"], 1);
}

TEST(ParameterTrack, HeldValuesStepAndNullRemoves) {
  const ParameterTrack track(nlohmann::json::json_pointer("/ozone"), std::nullopt,
                             {{0.0, {{"profile", "x"}}}, {5.0, nullptr}, {8.0, {{"profile", "y"}}}});
  nlohmann::json parameters = {{"ozone", {{"profile", "scene"}}}, {"gas", 1}};
  nlohmann::json at2 = parameters, at6 = parameters, at9 = parameters;
  track.apply(at2, 2.0);
  track.apply(at6, 6.0);
  track.apply(at9, 9.0);
  EXPECT_EQ(at2["ozone"]["profile"], "x");
  EXPECT_FALSE(at6.contains("ozone"));
  EXPECT_EQ(at6["gas"], 1);
  EXPECT_EQ(at9["ozone"]["profile"], "y");
}

TEST(ParameterTrack, RejectsMixedKinds) {
  const nlohmann::json::json_pointer p("/a");
  EXPECT_THROW(ParameterTrack(p, 0.5, {{0.0, true}}), std::invalid_argument);
  EXPECT_THROW(ParameterTrack(p, std::nullopt, {{0.0, 1.0}}), std::invalid_argument);
  EXPECT_THROW(ParameterTrack(p, -1.0, {{0.0, 1.0}}), std::invalid_argument);
}

TEST(WriteParameter, WritesCreatesRemovesAndRefusesWhatIsNotAContainer) {
  using Pointer = nlohmann::json::json_pointer;
  nlohmann::json p = {{"aerosol", {{"scattering", {{"turbidity", 2.0}}}}}, {"list", {1, 2}}, {"name", "x"}};
  write_parameter(p, Pointer("/aerosol/scattering/turbidity"), 3.0);
  EXPECT_EQ(p["aerosol"]["scattering"]["turbidity"], 3.0);
  write_parameter(p, Pointer("/ozone/profile"), "us_standard_1976");  // objects created on the way
  EXPECT_EQ(p["ozone"]["profile"], "us_standard_1976");
  write_parameter(p, Pointer("/ozone"), nullptr);  // null removes
  EXPECT_FALSE(p.contains("ozone"));
  write_parameter(p, Pointer("/oxygen/x"), nullptr);  // removing what is absent changes nothing
  EXPECT_FALSE(p.contains("oxygen"));
  write_parameter(p, Pointer("/list/1"), 5);
  write_parameter(p, Pointer("/list/-"), 6);
  write_parameter(p, Pointer("/list/0"), nullptr);
  EXPECT_EQ(p["list"], nlohmann::json({5, 6}));
  EXPECT_THROW(write_parameter(p, Pointer("/name/x"), 1), std::invalid_argument);
  EXPECT_THROW(write_parameter(p, Pointer("/list/7"), 1), std::invalid_argument);
  EXPECT_THROW(write_parameter(p, Pointer("/list/01"), 1), std::invalid_argument);
  EXPECT_THROW(write_parameter(p, Pointer("/list/x/y"), 1), std::invalid_argument);
  EXPECT_THROW(write_parameter(p, Pointer(""), 1), std::invalid_argument);
}

scene::Sun sun_towards(double azimuth_rad, double radius_rad, double irradiance) {
  scene::Sun s;
  s.direction = {std::cos(azimuth_rad), std::sin(azimuth_rad), 0.0};
  s.angular_radius_rad = radius_rad;
  s.irradiance_W_m2_nm = {irradiance, 2.0 * irradiance};
  return s;
}

TEST(SunTrack, FollowsTheGreatCircleMonotonically) {
  const SunTrack track({{0.0, sun_towards(0.0, 0.004, 1.0)},
                        {10.0, sun_towards(0.5, 0.004, 1.0)},
                        {20.0, sun_towards(1.5, 0.006, 0.5)}});
  EXPECT_EQ(track.at(0.0).direction, glm::dvec3(1, 0, 0));
  EXPECT_EQ(track.at(10.0).direction, sun_towards(0.5, 0, 0).direction);
  double previous = -1.0;
  for (int i = 0; i <= 200; ++i) {
    const scene::Sun s = track.at(i * 0.1);
    EXPECT_NEAR(glm::length(s.direction), 1.0, 1e-15);
    EXPECT_NEAR(s.direction.z, 0.0, 1e-15);  // on the great circle z = 0
    const double azimuth = std::atan2(s.direction.y, s.direction.x);
    EXPECT_GE(azimuth, previous - 1e-15) << i;  // never backtracks
    previous = azimuth;
    EXPECT_GE(s.angular_radius_rad, 0.004 - 1e-17);
    EXPECT_LE(s.angular_radius_rad, 0.006 + 1e-17);
    EXPECT_GE(s.irradiance_W_m2_nm[0], 0.5);
    EXPECT_LE(s.irradiance_W_m2_nm[0], 1.0);
  }
  // Two keys: constant angular speed, the midpoint halfway.
  const SunTrack two({{0.0, sun_towards(0.0, 0.004, 1.0)}, {4.0, sun_towards(0.8, 0.004, 1.0)}});
  EXPECT_NEAR(std::atan2(two.at(1.0).direction.y, two.at(1.0).direction.x), 0.2, 1e-14);
}

}  // namespace
}  // namespace zenith::show
