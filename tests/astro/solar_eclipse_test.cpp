// Solar eclipses as a site sees them (astro/solar_eclipse.h): the covered
// share of two discs against the closed forms, and the eclipse of 2017-08-21
// at its point of greatest eclipse against NASA's figures.
#include "astro/solar_eclipse.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/units.h"

namespace zenith::astro {
namespace {

using core::kPi;

TEST(SolarEclipse, DiscObscurationIsTheLensOfTwoCircles) {
  EXPECT_EQ(disc_obscuration(2.1, 1.0, 1.0), 0.0);           // apart
  EXPECT_DOUBLE_EQ(disc_obscuration(0.0, 1.0, 1.2), 1.0);    // total
  EXPECT_DOUBLE_EQ(disc_obscuration(0.05, 1.0, 0.9), 0.81);  // annular: the Moon's whole disc
  // Equal circles one radius apart: (2π/3 − √3/2) / π of each.
  EXPECT_NEAR(disc_obscuration(1.0, 1.0, 1.0), (2.0 * kPi / 3.0 - std::sqrt(3.0) / 2.0) / kPi, 1e-14);
  // Half the Sun's area is covered by an equal disc at d = 0.8079455 r (the root of the lens formula).
  EXPECT_NEAR(disc_obscuration(0.8079455, 1.0, 1.0), 0.5, 1e-6);
  // Continuous at the contacts: first/fourth (d = r_s + r_m) and second/third (d = |r_s − r_m|).
  EXPECT_NEAR(disc_obscuration(2.0 - 1e-9, 1.0, 1.0), 0.0, 1e-12);
  EXPECT_NEAR(disc_obscuration(0.2 + 1e-9, 1.0, 1.2), 1.0, 1e-6);
  EXPECT_NEAR(disc_obscuration(0.1 + 1e-9, 1.0, 0.9), 0.81, 1e-6);
  EXPECT_THROW(disc_obscuration(-0.1, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(disc_obscuration(0.1, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(disc_obscuration(std::nan(""), 1.0, 1.0), std::invalid_argument);
}

TEST(SolarEclipse, TheLimbDarkenedShareIsTheLightBehindTheMoon) {
  using atmosphere::LimbDarkening;
  const LimbDarkening sun_550 = atmosphere::solar_limb_darkening(550.0);
  // Uniform: the area share.
  EXPECT_NEAR(limb_darkened_obscuration(1.0, 1.0, 1.0, LimbDarkening{}), disc_obscuration(1.0, 1.0, 1.0), 1e-15);
  // Centred annulus ρ = 0.9 r_s: the light outside it is the ring μ < μ_0 = sqrt(0.19), whose share is
  // Σ a_k μ_0^{k+2}/(k+2) / Σ a_k/(k+2) (sun_disc.h's normalisation up to ρ): for the linear law I = μ,
  // 0.19^{3/2}; for the Sun's at every wavelength, the same sum over its polynomial.
  const double mu_0 = std::sqrt(0.19);
  EXPECT_NEAR(limb_darkened_obscuration(0.0, 1.0, 0.9, LimbDarkening{{0.0, 1.0, 0.0, 0.0, 0.0, 0.0}}),
              1.0 - std::pow(0.19, 1.5), 1e-12);
  for (double nm : {320.0, 440.0, 550.0, 680.0, 1000.0}) {
    const LimbDarkening law = atmosphere::solar_limb_darkening(nm);
    double outside = 0.0, whole = 0.0;
    for (std::size_t k = 0; k < law.coefficients.size(); ++k) {
      outside += law.coefficients[k] * std::pow(mu_0, double(k + 2)) / double(k + 2);
      whole += law.coefficients[k] / double(k + 2);
    }
    EXPECT_NEAR(limb_darkened_obscuration(0.0, 1.0, 0.9, law), 1.0 - outside / whole, 1e-12) << nm;
  }
  // Total and none as the geometry says.
  EXPECT_EQ(limb_darkened_obscuration(0.01, 1.0, 1.03, sun_550), 1.0);
  EXPECT_EQ(limb_darkened_obscuration(2.5, 1.0, 1.03, sun_550), 0.0);
  // A Moon over the limb hides less light than area (the limb is dark); over the centre, more.
  EXPECT_LT(limb_darkened_obscuration(1.6, 1.0, 1.03, sun_550), disc_obscuration(1.6, 1.0, 1.03));
  EXPECT_GT(limb_darkened_obscuration(0.3, 1.0, 0.5, sun_550), disc_obscuration(0.3, 1.0, 0.5));
  // Continuous and monotone as the Moon slides across, from first contact to second.
  double previous = 0.0;
  for (double d = 2.03; d >= 0.03; d -= 0.01) {
    const double share = limb_darkened_obscuration(d, 1.0, 1.03, sun_550);
    EXPECT_GE(share, previous - 1e-12) << d;
    EXPECT_LT(share - previous, 0.03) << d;
    previous = share;
  }
  // A law that is not one: coefficients that do not sum to 1, or a negative intensity.
  EXPECT_THROW(limb_darkened_obscuration(1.0, 1.0, 1.0, LimbDarkening{{0.5, 0.0, 0.0, 0.0, 0.0, 0.0}}),
               std::invalid_argument);
  EXPECT_THROW(limb_darkened_obscuration(1.0, 1.0, 1.0, LimbDarkening{{-0.5, 1.5, 0.0, 0.0, 0.0, 0.0}}),
               std::invalid_argument);
}

TEST(SolarEclipse, TheGreatEclipseOf2017IsTotalWhereNasaPutsItsGreatestEclipse) {
  // NASA (Espenak, Five Millennium Canon): 2017 August 21, greatest eclipse at
  // 36°58′N 87°40′W, magnitude 1.0306 (for a total eclipse the ratio of the
  // discs' diameters), totality 2 min 40 s, around 18:25 UT.
  // Scanned every 2 s from 18:15 to 18:35 UT: the largest magnitude there.
  const Site site{36.9667, -87.6667, 150.0};
  SolarEclipseView greatest;
  int total_steps = 0;
  for (int s = 0; s <= 1200; s += 2) {
    const SkyPositions sky(AstroTime::from_utc(UtcTime{2017, 8, 21, 18, 15, 0.0}).plus_seconds(s), site);
    const SolarEclipseView v = solar_eclipse_view(sky);
    if (v.magnitude > greatest.magnitude) greatest = v;
    if (v.kind == EclipseKind::total) ++total_steps;
  }
  std::printf("greatest: magnitude %.4f, totality %d s\n", greatest.magnitude, 2 * total_steps);
  EXPECT_EQ(greatest.kind, EclipseKind::total);
  // Ours 1.0315: the IAU's nominal radii (Moon 1737.4 km, Sun 695 700 km) where NASA's canon takes the
  // smaller k = 0.272281 for the Moon's umbral profile and 696 000 km: 0.09 % between them.
  EXPECT_NEAR(greatest.magnitude, 1.0306, 0.0015);
  EXPECT_DOUBLE_EQ(greatest.obscuration, 1.0);
  // 2 min 40 s of totality: 80 two-second steps, give or take the ephemeris' few seconds.
  EXPECT_NEAR(total_steps, 80, 4);
  // A day later the Moon is 12° away: no eclipse.
  const SkyPositions later(AstroTime::from_utc(UtcTime{2017, 8, 22, 18, 25, 0.0}), site);
  const SolarEclipseView none = solar_eclipse_view(later);
  EXPECT_EQ(none.kind, EclipseKind::none);
  EXPECT_EQ(none.obscuration, 0.0);
  EXPECT_LT(none.magnitude, 0.0);
}

}  // namespace
}  // namespace zenith::astro
