#include "warp/orientation_angles.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace zenith::warp {
namespace {

/// The shortest text that reads back as `value` ("-30", "326.7").
std::string number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

void check_orientation(const std::string& owner, const char* name, double value) {
  if (!(value >= -kMaxOrientationDeg && value <= kMaxOrientationDeg))  // NaN fails too
    throw std::invalid_argument(owner + ": " + name + " = " + number(value) + ": must be in [" +
                                number(-kMaxOrientationDeg) + ", " + number(kMaxOrientationDeg) +
                                "] degrees ([0, 360) and (-180, 180] both read)");
}

}  // namespace

double wrapped_deg(double a) {
  double r = std::fmod(a, 360.0);  // (−360, 360), the sign of a
  if (r > 180.0) r -= 360.0;
  if (r <= -180.0) r += 360.0;
  return r;
}

YawPitchRollDeg normalized_yaw_pitch_roll(const YawPitchRollDeg& angles) {
  YawPitchRollDeg out{wrapped_deg(angles.yaw_deg), wrapped_deg(angles.pitch_deg), wrapped_deg(angles.roll_deg)};
  if (std::abs(out.pitch_deg) > 90.0) {
    out.pitch_deg = std::copysign(180.0, out.pitch_deg) - out.pitch_deg;
    out.yaw_deg = wrapped_deg(out.yaw_deg + 180.0);
    out.roll_deg = wrapped_deg(out.roll_deg + 180.0);
  }
  return out;
}

YawPitchRollDeg checked_yaw_pitch_roll(const YawPitchRollDeg& angles, const std::string& owner) {
  check_orientation(owner, "yaw_deg", angles.yaw_deg);
  check_orientation(owner, "pitch_deg", angles.pitch_deg);
  check_orientation(owner, "roll_deg", angles.roll_deg);
  return normalized_yaw_pitch_roll(angles);
}

}  // namespace zenith::warp
