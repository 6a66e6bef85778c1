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
//
// Limb darkening (optional, per wavelength): I(μ)/I(1) = Σ a_k μ^k
// (atmosphere/solar_limb_darkening.h) with μ = sqrt(1 − sin²θ / sin²α) at an
// angle θ from the centre. Normalised to the same irradiance, the centre
// radiance is L_0 = 1 / (π sin²α m), m = 2 Σ a_k/(k + 2) the disc's mean over
// its centre, so a direction sampled uniformly over the cone weighs
// L(θ)/L_uniform = I(μ)/(I(1) m) times the uniform disc's weight.
//
// An occulter (optional): a sphere between the air and the sun — the Moon in
// a solar eclipse. Light from a direction of the disc that passes through it
// does not arrive, so every point of the air, the ground and the camera sees
// exactly the part of the (limb-darkened) disc the sphere leaves uncovered:
// the umbra, the penumbra and the antumbra follow from the geometry.
#include <vector>

#include "atmosphere/solar_limb_darkening.h"
#include "atmosphere/vec3.h"

namespace zenith::atmosphere::reference {

/// A sphere that can stand in front of the sun, in the planet's frame.
struct Occulter {
  Vec3 centre_m{0.0, 0.0, 0.0};  ///< from the planet's centre
  double radius_m = 0.0;         ///< 0: nothing in the way
};

struct SunDisc {
  Vec3 direction{0.0, 0.0, 1.0};        ///< unit vector from the planet toward the disc's centre
  double angular_radius_rad = 4.65e-3;  ///< half the apparent diameter (Earth: 4.65e-3); 0 = point sun
  /// The limb darkening per wavelength of the model; empty: a uniform disc.
  std::vector<LimbDarkening> limb_darkening = {};
  Occulter occulter = {};
};

/// Throws std::invalid_argument unless the direction is non-zero and finite,
/// 0 ≤ α < π/2, every limb darkening law is valid (check_limb_darkening; a
/// point sun has none), and the occulter's centre is finite and its radius finite and
/// ≥ 0. Returns the disc with its direction normalized.
SunDisc validated(const SunDisc& sun);

/// Whether the half-line from `point_m` along the unit `direction` passes
/// through the occulter's sphere (a point inside it sees nothing either).
bool occulted(const Occulter& occulter, const Vec3& point_m, const Vec3& direction);

/// The weight of a direction sampled uniformly over the disc's cone relative
/// to the uniform disc's: I(μ)/(I(1) m) for the law of wavelength
/// `wavelength` (1 for a uniform disc or a point sun; 0 outside the disc).
double limb_weight(const SunDisc& sun, const Vec3& to_sun, std::size_t wavelength);

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
