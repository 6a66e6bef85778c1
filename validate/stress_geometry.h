#pragma once
// Geometry of the numerical-stability stress (`zenith validate stress`,
// docs/validation.md "Numerical stability"): cameras from 1 m above the ground
// to 40 AU away, view directions placed exactly on and within 1e-6 rad of the
// geometric horizon, and the regions the results are reported by. No GL.
//
// The geometric horizon of a camera at distance r from the centre of a planet
// of radius R is the cone of rays tangent to the ground sphere. Measured from
// the nadir (the direction to the planet's centre) its half-angle is
//
//   β(r) = asin(R/r) = atan2(R, √((r − R)(r + R)))
//
// (the atan2 form keeps full relative precision both 1 m above the ground,
// where R/r = 1 − 1.6e-7 and acos/asin of it would lose 7 digits, and at 40 AU,
// where β ≈ 1e-6 rad). A view direction at nadir angle a in the vertical plane
// of the unit horizontal tangent t̂ is
//
//   v(a) = −cos a · ĉ + sin a · t̂          (ĉ = camera / r, the local zenith)
//
// and its offset from the horizon is δ = a − β: δ > 0 above the horizon (the
// ray's closest approach to the centre, r·sin a, exceeds R), δ < 0 below (the
// ray hits the ground), δ = 0 tangent.
#include <array>
#include <string_view>

#include "atmosphere/vec3.h"
#include "core/units.h"

namespace zenith::validate {

using atmosphere::Vec3;

/// 1 au [m] (IAU 2012 resolution B2).
inline constexpr double kAstronomicalUnit_m = 1.495978707e11;
/// The farthest camera of the stress: 40 au (Pluto's distance), 5.98e12 m.
inline constexpr double kMaxCameraDistance_m = 40.0 * kAstronomicalUnit_m;
/// The lowest camera: 1 m above the ground.
inline constexpr double kMinCameraAltitude_m = 1.0;
/// Half-width of the horizon band [rad]: |δ| < 1°.
inline constexpr double kHorizonBandHalfWidth_rad = 1.0 * core::kPi / 180.0;
/// Sun zenith angle [rad] where twilight ends and night begins (astronomical twilight: 108°).
inline constexpr double kTwilightEndZenith_rad = 108.0 * core::kPi / 180.0;

/// β(r): nadir angle of the geometric horizon [rad] for a camera at r ≥ R from the centre.
double horizon_nadir_angle_rad(double r_m, double ground_radius_m);

/// v(a) = −cos a · ĉ + sin a · t̂ for unit `up` (ĉ) and a unit `tangent` t̂ ⟂ ĉ.
Vec3 direction_at_nadir_angle(const Vec3& up, const Vec3& tangent, double nadir_angle_rad);

/// The view direction δ = `offset_rad` above (δ > 0) or below (δ < 0) the
/// geometric horizon of `camera_m`, in the vertical plane of unit `tangent` ⟂ camera.
Vec3 horizon_direction(const Vec3& camera_m, const Vec3& tangent, double ground_radius_m, double offset_rad);

/// δ of a view direction: its nadir angle atan2(|ĉ × v|, −ĉ·v) minus β(r) [rad].
double offset_from_horizon_rad(const Vec3& camera_m, const Vec3& view, double ground_radius_m);

/// A unit vector perpendicular to unit `up`, at angle `azimuth_rad` about it
/// from a fixed reference (the component of x̂, or ŷ, orthogonal to `up`).
Vec3 tangent_at_azimuth(const Vec3& up, double azimuth_rad);

/// One configuration of the stress: camera, view and sun (planet-centred, unit directions).
struct Configuration {
  Vec3 camera_m{};
  Vec3 view{};
  Vec3 sun{};
};

/// Where a configuration is reported. Exclusive, assigned in this order:
///  * space    — the camera is above the top of the atmosphere (r > R_top);
///  * night    — the sun's centre more than 18° below the camera's horizontal (zenith > 108°);
///  * twilight — the sun's centre below the camera's horizontal (zenith in (90°, 108°]);
///  * horizon  — daytime, the view within 1° of the geometric horizon (|δ| < 1°);
///  * ground   — daytime, the view ray hits the ground (δ ≤ −1°);
///  * sky      — daytime, the view above the horizon band (δ ≥ 1°).
enum class Region { space, night, twilight, horizon, ground, sky };
inline constexpr std::array<Region, 6> kRegions = {Region::space,   Region::night,  Region::twilight,
                                                   Region::horizon, Region::ground, Region::sky};
inline constexpr std::size_t kRegionCount = kRegions.size();
std::string_view region_name(Region region);

Region classify(const Configuration& c, double ground_radius_m, double top_radius_m);

}  // namespace zenith::validate
