#pragma once
// The sun as a distant uniform disc.
//
// Radiometric convention of the reference solver: the sun's spectral irradiance
// at the top of the atmosphere, on a surface perpendicular to the direction of
// the disc's centre, is 1 at every wavelength. All radiances the solver returns
// are therefore in sr^-1 per unit solar irradiance, and irradiances are
// dimensionless (per unit solar irradiance). A uniform disc of angular radius α
// then has radiance
//   L_sun = E / ∫_cone cos θ dω = 1 / (π sin²α)     [sr^-1].
// α = 0 is a point sun (a delta in direction with irradiance 1).
#include "atmosphere/vec3.h"

namespace zenith::atmosphere::reference {

struct SunDisc {
  Vec3 direction{0.0, 0.0, 1.0};        ///< unit vector from the planet toward the disc's centre
  double angular_radius_rad = 4.65e-3;  ///< half the apparent diameter (Earth: 4.65e-3); 0 = point sun
};

/// Throws std::invalid_argument unless the direction is non-zero and finite and
/// 0 ≤ α < π/2. Returns the disc with its direction normalized.
SunDisc validated(const SunDisc& sun);

/// Ω = 2π(1 − cos α) = 4π sin²(α/2) [sr] (0 for a point sun).
double sun_solid_angle_sr(const SunDisc& sun);

/// A direction uniformly distributed in solid angle over the disc's cone
/// (pdf 1/Ω), from two uniform numbers in [0, 1): 1 − cos θ = u1 (1 − cos α),
/// φ = 2π u2. Returns the centre direction for a point sun.
Vec3 sample_sun_direction(const SunDisc& sun, double u1, double u2);

/// The next-event weight of one such sample, L_sun / pdf = L_sun Ω = 2/(1 + cos α)
/// (→ 1 for a point sun): the estimator of ∫_cone L_sun f(ω) dω is
/// sun_sample_weight · f(ω_sample).
double sun_sample_weight(const SunDisc& sun);

}  // namespace zenith::atmosphere::reference
