// The sun's disc drawn where the eye sees it (render/frame/sun_refraction.h,
// sun_disc.glsl): lifted by the refraction of the model's own air and
// flattened, measured on rendered frames against astro::Refraction (itself
// checked against Bennett and Sæmundsson in tests/astro/refraction_test.cpp).
//
// The frames: a camera 2 m above the Earth's north pole (up = +z) looking at
// the sun's azimuth, a 1.5° planar view of 128² pixels (0.0117° a pixel, the
// disc 45 pixels across), atmospheres off (nothing but the disc and the
// ground), a uniform disc (no limb darkening): the disc's pixels are those
// brighter than anything the ground can send.
#include <gtest/gtest.h>

#include <cmath>

#include "astro/refraction.h"
#include "core/units.h"
#include "render/renderer.h"
#include "render_test_support.h"
#include "warp/planar_projection.h"

namespace zenith::render {
namespace {

using core::kDeg;

constexpr double kCameraAltitudeM = 2.0;
constexpr int kSize = 128;
constexpr double kFovDeg = 1.5;

struct DiscMoments {
  double weight = 0.0;          ///< Σ v (pixels of the disc)
  double altitude_rad = 0.0;    ///< weighted mean apparent altitude of the disc's pixels
  double vertical_rad = 0.0;    ///< standard deviation in altitude
  double horizontal_rad = 0.0;  ///< standard deviation across (azimuth × cos altitude)
  double top_rad = -1.0;        ///< highest altitude of a disc pixel's centre
};

class SunRefractionFrames : public ::testing::Test {
 protected:
  SunRefractionFrames() : renderer_((testing::context(), options()), tables()) {}

  static RenderOptions options() {
    RenderOptions o;
    o.colour = image::ColourMapping::direct;
    o.atmospheres = false;
    o.limb_darkening = false;
    return o;
  }
  static TableSource tables() {
    return
        [](const atmosphere::AtmosphereModel&) { return atmosphere::lut::SmallTables::get("earth-advanced").tables; };
  }

  /// The scene: the sun at true altitude `sun_altitude_deg`, azimuth 0; the
  /// camera `altitude_m` above the north pole looking at azimuth 0, altitude `view_deg`.
  static scene::Scene scene(double sun_altitude_deg, double view_deg, double altitude_m = kCameraAltitudeM) {
    scene::Scene s = testing::one_planet_scene("sun refraction", "earth", "earth-advanced", "earth-advanced");
    const double h = sun_altitude_deg * kDeg, v = view_deg * kDeg;
    s.sun.direction = {std::cos(h), 0.0, std::sin(h)};
    s.camera.position_m = {0.0, 0.0, s.bodies[0].radius_m + altitude_m};
    s.camera.orientation = testing::look_rotation({std::cos(v), 0.0, std::sin(v)}, {0.0, 0.0, 1.0});
    s.camera.exposure = 1.0;
    return s;
  }

  DiscMoments moments(const scene::Scene& s) {
    const warp::PlanarProjection p = warp::PlanarProjection::symmetric(kSize, kSize, kFovDeg);
    const std::vector<float> image = renderer_.render_image(s, p);
    // The ground sends at most E·albedo/π ≈ 0.06 of green here; the disc ~1e7.
    const double threshold = 1e3;
    DiscMoments m;
    double h1 = 0.0, h2 = 0.0, a1 = 0.0, a2 = 0.0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const double v = image[(static_cast<std::size_t>(y) * kSize + x) * 3 + 1];
        if (!(v > threshold)) continue;
        const glm::dvec3 d = glm::normalize(s.camera.orientation * *p.ray(x + 0.5, y + 0.5));
        const double h = std::asin(d.z), across = std::atan2(d.y, d.x) * std::cos(h);
        m.weight += v;
        h1 += v * h, h2 += v * h * h, a1 += v * across, a2 += v * across * across;
        m.top_rad = std::max(m.top_rad, h);
      }
    if (m.weight == 0.0) return m;
    m.altitude_rad = h1 / m.weight;
    m.vertical_rad = std::sqrt(std::max(0.0, h2 / m.weight - m.altitude_rad * m.altitude_rad));
    m.horizontal_rad = std::sqrt(std::max(0.0, a2 / m.weight - (a1 / m.weight) * (a1 / m.weight)));
    return m;
  }

  /// The air of the frames, at the camera's altitude.
  static astro::Refraction air(double altitude_m = kCameraAltitudeM) {
    return astro::Refraction::for_atmosphere(atmosphere::load_preset("earth-advanced"), 550.0, altitude_m);
  }

  Renderer renderer_;
};

constexpr double kPixelRad = kFovDeg * kDeg / kSize;
constexpr double kSunRadiusRad = 4.65e-3;

/// What the frame should hold, computed apart from the renderer: the true
/// disc (uniform, radius r, centre at true altitude h₀) mapped point by point
/// to apparent altitude f(h) = Refraction::apparent_from_true_rad(h), the
/// horizontal unchanged. Radiance is kept along a ray, so the image is uniform
/// over the mapped region, whose area element is f′(h) dA: the moments are
/// those of the true disc weighted by f′. (The centroid is not f(h₀): f is
/// curved, and the squeezed lower half weighs less — 0.14 pixel at 0.6°.)
DiscMoments expected_moments(const astro::Refraction& r, double true_altitude_rad) {
  const int n = 400;
  double w = 0.0, h1 = 0.0, h2 = 0.0, a2 = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = kSunRadiusRad * (2.0 * (i + 0.5) / n - 1.0), v = kSunRadiusRad * (2.0 * (j + 0.5) / n - 1.0);
      if (u * u + v * v > kSunRadiusRad * kSunRadiusRad) continue;
      const double h = true_altitude_rad + v, dh = 1e-5;
      const double f = r.apparent_from_true_rad(h);
      const double slope = (r.apparent_from_true_rad(h + dh) - r.apparent_from_true_rad(h - dh)) / (2.0 * dh);
      w += slope, h1 += slope * f, h2 += slope * f * f, a2 += slope * u * u;
    }
  DiscMoments m;
  m.weight = w;
  m.altitude_rad = h1 / w;
  m.vertical_rad = std::sqrt(h2 / w - m.altitude_rad * m.altitude_rad);
  m.horizontal_rad = std::sqrt(a2 / w);
  return m;
}

TEST_F(SunRefractionFrames, TheDiscIsLiftedAndFlattenedAsTheAirBendsItsLight) {
  const astro::Refraction r = air();
  for (double true_deg : {2.0, 0.6}) {
    const DiscMoments m = moments(scene(true_deg, true_deg + 0.3));
    ASSERT_GT(m.weight, 0.0) << true_deg;
    const DiscMoments expected = expected_moments(r, true_deg * kDeg);
    // Lifted by R (18′ at 2°, 27′ at 0.6°); the centroid within a tenth of a pixel (0.07′).
    EXPECT_NEAR(m.altitude_rad, expected.altitude_rad, 0.1 * kPixelRad) << "true altitude " << true_deg << "°";
    EXPECT_GT(m.altitude_rad - true_deg * kDeg, 0.25 * kDeg);
    // Flattened by the lift's difference across the disc.
    const double flattening = expected.vertical_rad / expected.horizontal_rad;
    EXPECT_LT(flattening, true_deg < 1.0 ? 0.9 : 0.95) << "the flattening is visible at " << true_deg << "°";
    // The pixels' antialiased edge adds nearly the same small spread both ways (5e-4 measured).
    EXPECT_NEAR(m.vertical_rad / m.horizontal_rad, flattening, 0.003) << "true altitude " << true_deg << "°";
  }
}

TEST_F(SunRefractionFrames, ASunGeometricallyBelowTheHorizonIsStillSeen) {
  const astro::Refraction r = air();
  const double true_deg = -0.45;  // its upper limb 0.18° below the horizon, which dips 0.045° at 2 m
  const DiscMoments m = moments(scene(true_deg, 0.2));
  ASSERT_GT(m.weight, 0.0) << "the refracted sun shows above the horizon";
  const double top = r.apparent_from_true_rad(true_deg * kDeg + kSunRadiusRad);
  EXPECT_NEAR(m.top_rad, top, 1.0 * kPixelRad);
  EXPECT_GT(top, 0.1 * kDeg);
}

TEST_F(SunRefractionFrames, FromAboveTheAirTheDiscIsWhereItIs) {
  // 150 km up, above earth-advanced's 100-km top: straight rays.
  const scene::Scene s = scene(2.0, 2.3, 150e3);
  const DiscMoments m = moments(s);
  ASSERT_GT(m.weight, 0.0);
  EXPECT_NEAR(m.altitude_rad, 2.0 * kDeg, 0.1 * kPixelRad);
  EXPECT_NEAR(m.vertical_rad / m.horizontal_rad, 1.0, 0.01);
}

TEST_F(SunRefractionFrames, AirThatTrapsHorizontalRaysKeepsTheDiscWhereItIs) {
  // earth-advanced's refractivity (2.9e-4) over a 1 km scale height: ε R / H = 1.8 > 1, so n r falls with height
  // from the ground up (astro::ducting_altitude_m) and R(0) diverges. Such air's refraction is not drawn (one
  // warning): the frame renders and the disc stays at its geometric place.
  scene::Scene s = scene(2.0, 2.3);
  atmosphere::AtmosphereModel& model = s.bodies[0].atmosphere->loaded.model;
  model.rayleigh_density = atmosphere::DensityProfile::exponential(1000.0);
  ASSERT_TRUE(astro::ducting_altitude_m(model.ground_radius_m, model.top_radius_m, model.rayleigh_density,
                                        astro::ground_refractivity(s.bodies[0].atmosphere->loaded), kCameraAltitudeM));
  const DiscMoments m = moments(s);
  ASSERT_GT(m.weight, 0.0);
  EXPECT_NEAR(m.altitude_rad, 2.0 * kDeg, 0.1 * kPixelRad);
  EXPECT_NEAR(m.vertical_rad / m.horizontal_rad, 1.0, 0.01);
}

}  // namespace
}  // namespace zenith::render
