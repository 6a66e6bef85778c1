#include "scene/sun_disc.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/units.h"

namespace zenith::scene {
namespace {

using core::kPi;

/// ∫_disc L(θ) cos θ dΩ = 2π ∫_0^θs L(θ) cos θ sin θ dθ by composite Gauss–Legendre
/// in w with θ = θs (1 − w²): the substitution removes the square-root
/// behaviour of μ at the limb that would slow plain quadrature in θ down.
double integrated_irradiance(double irradiance, double angular_radius, double wavelength_nm) {
  // 8-point Gauss–Legendre nodes and weights on [−1, 1].
  const double x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                       0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
  const double w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                       0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  const int panels = 400;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double a = double(p) / panels, b = double(p + 1) / panels;
    for (int k = 0; k < 8; ++k) {
      const double s = 0.5 * (a + b) + 0.5 * (b - a) * x[k];  // w in [0, 1]
      const double theta = angular_radius * (1.0 - s * s);
      const double dtheta_ds = 2.0 * angular_radius * s;
      const double L = disc_radiance(irradiance, angular_radius, wavelength_nm, theta);
      sum += 0.5 * (b - a) * w[k] * L * std::cos(theta) * std::sin(theta) * dtheta_ds;
    }
  }
  return 2.0 * kPi * sum;
}

TEST(SunDisc, RadianceIntegratesToTheIrradiance) {
  const double sun_radius = 0.5 * 0.533 * kPi / 180.0;
  for (double wavelength : {360.0, 440.0, 550.0, 680.0, 830.0})
    for (double radius : {sun_radius, 0.5 * sun_radius, 2e-3, 0.05, 15.0 * kPi / 180.0})
      for (double irradiance : {1.0, 1.86}) {
        const double E = integrated_irradiance(irradiance, radius, wavelength);
        EXPECT_NEAR(E / irradiance, 1.0, 1e-6) << wavelength << " nm, radius " << radius;
      }
}

TEST(SunDisc, CentreRadianceClosedForm) {
  // L_0 = E / (π sin²θs m), m the law's mean over its centre: the uniform disc (m = 1) is
  // E / (π sin²θs); with darkening the centre is brighter (at 550 nm m = 0.80, Neckel & Labs's 0.8002
  // at 541.76 nm and 0.8061 at 559.95 nm).
  const double radius = 4.65e-3, E = 1.5;
  const double m = atmosphere::solar_limb_darkening(550.0).mean_over_centre();
  EXPECT_GT(m, 0.8002);
  EXPECT_LT(m, 0.8061);
  EXPECT_NEAR(disc_centre_radiance(E, radius, 550.0), E / (kPi * std::sin(radius) * std::sin(radius) * m), 1e-9);
  EXPECT_GT(disc_centre_radiance(E, radius, 550.0), E / (kPi * std::sin(radius) * std::sin(radius)));
  EXPECT_DOUBLE_EQ(disc_centre_radiance(0.0, radius, 550.0), 0.0);
  EXPECT_NEAR(uniform_disc_radiance(E, radius), disc_centre_radiance(E, radius, 550.0) * m, 1e-9);
}

TEST(SunDisc, UniformDiscIntegratesToTheIrradiance) {
  // 2π ∫0^θs L cos θ sin θ dθ = π L sin²θs, by the midpoint rule.
  const double radius = 0.2, E = 1.3, L = uniform_disc_radiance(E, radius);
  const int n = 200000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double theta = (i + 0.5) * radius / n;
    sum += L * std::cos(theta) * std::sin(theta) * radius / n;
  }
  EXPECT_NEAR(2.0 * kPi * sum / E, 1.0, 1e-9);
}

TEST(SunDisc, TheDiscIsItsCentreDarkenedTowardTheLimbAndNothingBeyond) {
  const double radius = 4.65e-3, E = 1.5;
  for (double wavelength : {440.0, 550.0, 680.0}) {
    const atmosphere::LimbDarkening law = atmosphere::solar_limb_darkening(wavelength);
    const double centre = disc_centre_radiance(E, radius, wavelength);
    EXPECT_DOUBLE_EQ(disc_radiance(E, radius, wavelength, 0.0), centre);
    EXPECT_NEAR(disc_radiance(E, radius, wavelength, 0.6 * radius) / centre,
                law.intensity(disc_mu(0.6 * radius, radius)), 1e-12);
    // Just inside the limb the measured Sun keeps a_0 of its centre; outside, no disc.
    EXPECT_NEAR(disc_radiance(E, radius, wavelength, radius * (1.0 - 1e-12)) / centre, law.coefficients[0], 1e-5);
    EXPECT_DOUBLE_EQ(disc_radiance(E, radius, wavelength, radius), 0.0);
    EXPECT_DOUBLE_EQ(disc_radiance(E, radius, wavelength, 2.0 * radius), 0.0);
  }
}

TEST(SunDisc, MuMatchesTheGeometryOfASphere) {
  // The sun: radius R at distance D. Intersect the line of sight at angle θ with
  // the sphere and measure the cosine between the surface normal and the ray back.
  const double R = kSolarRadius_m, D = 0.05 * kAstronomicalUnit_m;  // a large disc (~30°)
  const double radius = std::asin(R / D);
  for (double f : {0.0, 0.3, 0.7, 0.95, 0.999}) {
    const double theta = f * radius;
    // Ray from the origin along (sin θ, 0, cos θ); sphere centre at (0, 0, D).
    const double dx = std::sin(theta), dz = std::cos(theta);
    const double b = dz * D;  // projection of the centre on the ray
    const double c = D * D - R * R;
    const double t = b - std::sqrt(b * b - c);  // first hit
    const double nx = t * dx / R, nz = (t * dz - D) / R;
    const double mu = -(nx * dx + nz * dz);
    EXPECT_NEAR(disc_mu(theta, radius), mu, 1e-9) << f;
  }
  EXPECT_DOUBLE_EQ(disc_mu(radius * 1.01, radius), 0.0);
  EXPECT_DOUBLE_EQ(disc_mu(0.0, radius), 1.0);
}

TEST(SunDisc, RejectsBadInputs) {
  EXPECT_THROW(disc_centre_radiance(1.0, 0.0, 550.0), std::invalid_argument);
  EXPECT_THROW(disc_centre_radiance(1.0, 2.0, 550.0), std::invalid_argument);
  EXPECT_THROW(disc_centre_radiance(-1.0, 0.01, 550.0), std::invalid_argument);
  EXPECT_THROW(disc_centre_radiance(std::nan(""), 0.01, 550.0), std::invalid_argument);
  EXPECT_THROW(disc_centre_radiance(1.0, 0.01, 0.0), std::invalid_argument);
  EXPECT_THROW(disc_centre_radiance(1.0, 0.01, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::scene
