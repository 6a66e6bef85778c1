#pragma once
// Mathematical constants and unit conversions shared by every module. One
// spelling of π for the whole code base (GLSL has its own, in
// shaders/atmosphere_common.glsl).
#include <numbers>

namespace zenith::core {

inline constexpr double kPi = std::numbers::pi;
/// Radians per degree: angle_rad = angle_deg * kDeg.
inline constexpr double kDeg = kPi / 180.0;
/// Degrees per radian: angle_deg = angle_rad * kRadToDeg.
inline constexpr double kRadToDeg = 180.0 / kPi;

}  // namespace zenith::core
