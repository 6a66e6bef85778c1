#pragma once
// Mathematical constants and unit conversions shared by every module. One
// spelling of π for the whole code base, the shaders' included (PI of
// render/lut/shader_model.cpp, PI_F of render/shader_bindings.cpp).
#include <numbers>

namespace zenith::core {

inline constexpr double kPi = std::numbers::pi;
/// Radians per degree: angle_rad = angle_deg * kDeg.
inline constexpr double kDeg = kPi / 180.0;
/// Degrees per radian: angle_deg = angle_rad * kRadToDeg.
inline constexpr double kRadToDeg = 180.0 / kPi;

}  // namespace zenith::core
