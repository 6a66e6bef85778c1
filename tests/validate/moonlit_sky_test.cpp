// Krisciunas & Schaefer's moonlit sky (validate/moonlit_sky.h), the published
// model the renderer's moonlight is held to (docs/night-sky.md, "Moonlight"):
// their formula reproduced to a worked value published with an independent
// implementation, and its pieces to their closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "validate/moonlit_sky.h"

namespace zenith::validate {
namespace {

TEST(MoonlitSky, ReproducesTheWorkedValueSpecsimPublishes) {
  // specsim (DESI's spectrograph simulator) documents its K&S 1991 model with
  // krisciunas_schaefer(obs_zenith 20°, moon_zenith 70°, separation 50°,
  // moon_phase 0.25, vband_extinction 0.15) = 19.855 mag/arcsec²
  // (specsim.readthedocs.io, specsim.atmosphere.krisciunas_schaefer), its phase
  // 0.25 being a phase angle of 180° × 0.25 = 45°, and its surface brightness
  // Garstang's conversion of the nanolamberts.
  const double nL = krisciunas_schaefer_moon_nL(45.0, 50.0, 70.0, 20.0, 0.15);
  EXPECT_NEAR(v_mag_arcsec2_from_nanolamberts(nL), 19.855, 0.0005);
}

TEST(MoonlitSky, ItsPiecesAreTheirClosedForms) {
  // A full Moon (α = 0) 60° from a sky point at the zenith with no extinction
  // lights nothing: 1 − 10^0 = 0.
  EXPECT_EQ(krisciunas_schaefer_moon_nL(0.0, 60.0, 60.0, 0.0, 0.0), 0.0);
  // Small k: 1 − 10^(−0.4 k X) → 0.4 ln10 k X; at the zenith X = 1 and
  // B → f(ρ) I* 0.4 ln10 k, with I* = 10^(−0.4·3.84) at full Moon (eq. 20) and
  // f(90°) = 10^5.36 · 1.06 + 10^(6.15 − 2.25) (eq. 21).
  const double k = 1e-7;
  const double f90 = std::pow(10.0, 5.36) * 1.06 + std::pow(10.0, 3.9);
  const double expected = f90 * std::pow(10.0, -0.4 * 3.84) * 0.4 * std::log(10.0) * k;
  EXPECT_NEAR(krisciunas_schaefer_moon_nL(0.0, 90.0, 90.0 - 1e-9, 0.0, k), expected, 1e-6 * expected);
  // Garstang: 34.08 nL · e^(20.7233 − 0.92104 μ) inverted; 54 nL is ~22 mag/arcsec².
  EXPECT_NEAR(v_mag_arcsec2_from_nanolamberts(34.08 * std::exp(20.7233 - 0.92104 * 21.0)), 21.0, 1e-12);
  // Their f(ρ) holds only beyond 10° of the Moon.
  EXPECT_THROW(krisciunas_schaefer_moon_nL(0.0, 5.0, 30.0, 30.0, 0.2), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::validate
