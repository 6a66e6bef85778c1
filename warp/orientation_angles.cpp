#include "warp/orientation_angles.h"

#include <cmath>

namespace zenith::warp {
namespace {

/// a + k · 360 in (−180, 180].
double wrapped_deg(double a) {
  double r = std::fmod(a, 360.0);  // (−360, 360), the sign of a
  if (r > 180.0) r -= 360.0;
  if (r <= -180.0) r += 360.0;
  return r;
}

}  // namespace

YawPitchRollDeg normalized_yaw_pitch_roll(const YawPitchRollDeg& angles) {
  YawPitchRollDeg out{wrapped_deg(angles.yaw_deg), wrapped_deg(angles.pitch_deg), wrapped_deg(angles.roll_deg)};
  if (std::abs(out.pitch_deg) > 90.0) {
    out.pitch_deg = std::copysign(180.0, out.pitch_deg) - out.pitch_deg;
    out.yaw_deg = wrapped_deg(out.yaw_deg + 180.0);
    out.roll_deg = wrapped_deg(out.roll_deg + 180.0);
  }
  return out;
}

}  // namespace zenith::warp
