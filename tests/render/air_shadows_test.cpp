// A body's shadow through its air on another body (render/frame/air_shadows.h).
#include "render/frame/air_shadows.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../atmosphere/lut_fixture.h"
#include "atmosphere/parameters.h"
#include "atmosphere/photometry.h"

namespace zenith::render {
namespace {

/// The Earth (earth-advanced at its small tables' wavelengths) at the origin,
/// the sun along +z, and a moon 384 400 km behind it, `off_axis_m` from the
/// shadow's axis.
scene::Scene earth_and_moon(double off_axis_m) {
  const atmosphere::lut::SmallTables& t = atmosphere::lut::SmallTables::get("earth-advanced");
  scene::Scene s;
  s.name = "air shadow test";
  s.wavelengths_nm = t.model.wavelengths_nm;
  scene::Body earth;
  earth.name = "earth";
  earth.radius_m = t.model.ground_radius_m;
  earth.atmosphere = scene::BodyAtmosphere{"preset:earth-advanced", atmosphere::load_preset("earth-advanced")};
  scene::Body moon;
  moon.name = "moon";
  moon.radius_m = 1.7374e6;
  moon.position_m = {off_axis_m, 0.0, -3.844e8};
  s.bodies = {earth, moon};
  s.sun.direction = {0.0, 0.0, 1.0};
  s.sun.angular_radius_rad = 4.65e-3;
  for (double w : s.wavelengths_nm) s.sun.irradiance_W_m2_nm.push_back(atmosphere::solar_irradiance_W_m2_nm(w));
  return s;
}

TEST(AirShadows, TheEarthsAirShadowsTheMoonFromTheAxisToWhereTheWholeSunShines) {
  AirShadows shadows;
  shadows.update(earth_and_moon(3.0e6));
  ASSERT_EQ(shadows.shadows().size(), 1u) << "the Earth's air on the moon, not the moon's (it has none)";
  const AirShadow& s = shadows.shadows()[0];
  EXPECT_EQ(s.occluder, 0u);
  EXPECT_EQ(s.receiver, 1u);
  const atmosphere::lut::SmallTables& t = atmosphere::lut::SmallTables::get("earth-advanced");
  EXPECT_NEAR(s.reach_m, t.model.top_radius_m + 3.844e8 * std::tan(4.65e-3), 1.0);
  ASSERT_EQ(s.light_left.size(), kAirShadowEntries);
  for (std::size_t i = 0; i < t.model.wavelengths_nm.size(); ++i) {
    // No seam where the table ends and the whole sun takes over.
    EXPECT_NEAR(s.light_left.back()[i], 1.0, 1e-3) << t.model.wavelengths_nm[i] << " nm";
    // The umbra keeps some light, far less than the penumbra's outer half.
    EXPECT_GT(s.light_left.front()[i], 0.0);
    EXPECT_LT(s.light_left.front()[i], 1e-2);
    for (const std::vector<double>& e : s.light_left) EXPECT_TRUE(e[i] >= 0.0 && e[i] <= 1.0 + 1e-9);
  }
  std::printf("the light left on the axis: %.3g (%.0f nm) … %.3g (%.0f nm)\n", s.light_left.front().front(),
              t.model.wavelengths_nm.front(), s.light_left.front().back(), t.model.wavelengths_nm.back());
}

TEST(AirShadows, NoneWhereTheShadowMissesOrTheBodyIsTooNearItsAirsTop) {
  AirShadows shadows;
  shadows.update(earth_and_moon(2.0e7));  // 20 000 km off the axis: beyond the penumbra's 8 200 km
  EXPECT_TRUE(shadows.shadows().empty());
  scene::Scene near = earth_and_moon(0.0);
  near.bodies[1].position_m = {0.0, 0.0, -2.0e7};  // 3 Earth radii behind: too near for EarthShadow
  shadows.update(near);
  EXPECT_TRUE(shadows.shadows().empty()) << "the solid Earth's geometric shadow stays";
  scene::Scene sunward = earth_and_moon(0.0);
  sunward.bodies[1].position_m.z = 3.844e8;  // between the Earth and the sun
  shadows.update(sunward);
  EXPECT_TRUE(shadows.shadows().empty());
}

TEST(AirShadows, TheBufferHoldsTheColourMatrixAndTheLanesOfEveryEntry) {
  const scene::Scene s = earth_and_moon(3.0e6);
  AirShadows shadows;
  shadows.update(s);
  FrameConstants frame;
  frame.n = s.wavelengths_nm.size();
  frame.groups = (frame.n + 3) / 4;
  frame.rgb_weights = image::spectral_to_rgb_weights(s.wavelengths_nm, image::ColourMapping::automatic);
  frame.albedo_weights = image::rgb_to_spectral_weights(s.wavelengths_nm, image::ColourMapping::automatic);
  const auto buffer = air_shadow_buffer(shadows.shadows(), frame, s);
  const std::size_t per_entry = air_shadow_values_per_entry(frame);
  ASSERT_EQ(buffer.size(), kAirShadowEntries * per_entry);
  const std::size_t k = kAirShadowEntries / 3;
  const std::vector<double>& left = shadows.shadows()[0].light_left[k];
  const std::array<float, 9> m = direct_light_colour_matrix(frame, s, left);
  for (std::size_t column = 0; column < 3; ++column)
    for (std::size_t row = 0; row < 3; ++row) EXPECT_EQ(buffer[k * per_entry + column][row], m[column * 3 + row]);
  for (std::size_t i = 0; i < frame.n; ++i)
    EXPECT_FLOAT_EQ(buffer[k * per_entry + 3 + i / 4][i % 4], static_cast<float>(left[i]));
  EXPECT_TRUE(air_shadow_buffer({}, frame, s).size() == 1u) << "one zero vec4 to bind where there is no shadow";
}

}  // namespace
}  // namespace zenith::render
