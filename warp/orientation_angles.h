#pragma once
// Yaw, pitch and roll as calibration tools write them, brought into the ranges
// PlanarFrustum takes (yaw and roll in [−180, 180], pitch in [−90, 90]) without
// changing the rotation they describe.
//
// Vendors write angles in [0, 360) (350° for −10°) as often as in
// (−180, 180]. Wrapping each angle by 360° keeps the rotation. A pitch past
// ±90° (looking over the top and backwards) is the same rotation as the pitch
// mirrored about ±90° with the yaw and the roll turned half way round:
//     R_yaw(ψ) · R_pitch(θ) · R_roll(φ) = R_yaw(ψ + 180°) · R_pitch(±180° − θ) · R_roll(φ + 180°),
// the identity of Tait–Bryan angles this order uses (warp/planar_projection.h:
// R_yaw · R_pitch · R_roll).
#include <string>

namespace zenith::warp {

/// Orientation angles are read in [−kMaxOrientationDeg, kMaxOrientationDeg]
/// degrees: both [0, 360) and (−180, 180] conventions, and a turn either way.
inline constexpr double kMaxOrientationDeg = 360.0;

/// Angles in degrees, PlanarFrustum's conventions (yaw turns right, pitch up,
/// roll banks right).
struct YawPitchRollDeg {
  double yaw_deg = 0.0, pitch_deg = 0.0, roll_deg = 0.0;
};

/// a + k · 360 in (−180, 180] (finite a; non-finite stays non-finite).
double wrapped_deg(double a);

/// The same rotation with yaw and roll in (−180, 180] and pitch in [−90, 90].
/// Finite input expected (non-finite angles stay non-finite).
YawPitchRollDeg normalized_yaw_pitch_roll(const YawPitchRollDeg& angles);

/// normalized_yaw_pitch_roll() of angles given by a user: each must be finite
/// and in [−360, 360], else std::invalid_argument
/// "<owner>: yaw_deg = 400: must be in [-360, 360] degrees ([0, 360) and
/// (-180, 180] both read)" naming the first offending angle.
YawPitchRollDeg checked_yaw_pitch_roll(const YawPitchRollDeg& angles, const std::string& owner);

/// checked_yaw_pitch_roll() of the yaw_deg, pitch_deg and roll_deg members of
/// a projection's parameters, written back normalized (PlanarFrustum,
/// CylindricalParameters).
template <class Parameters>
void check_and_normalize_orientation(Parameters& parameters, const std::string& owner) {
  const YawPitchRollDeg o =
      checked_yaw_pitch_roll({parameters.yaw_deg, parameters.pitch_deg, parameters.roll_deg}, owner);
  parameters.yaw_deg = o.yaw_deg;
  parameters.pitch_deg = o.pitch_deg;
  parameters.roll_deg = o.roll_deg;
}

}  // namespace zenith::warp
