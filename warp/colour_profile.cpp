#include "warp/colour_profile.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace zenith::warp {
namespace {

double unit(double x) { return std::isnan(x) ? 0.0 : std::clamp(x, 0.0, 1.0); }

std::array<double, 3> clamped(const std::array<double, 3>& v) { return {unit(v[0]), unit(v[1]), unit(v[2])}; }

std::string lut_text(const std::optional<CubeLut>& lut) {
  if (!lut) return "";
  return lut->is_3d() ? fmt::format(" ({}^3)", lut->size) : fmt::format(" ({} entries)", lut->size);
}

}  // namespace

std::array<double, 3> MpcdiColourProfile::decoded(const std::array<double, 3>& signal) const {
  const std::array<double, 3> e = clamped(signal);
  if (decode.type == Decode::Type::lut1d) return decode.lut->apply(e);
  // §2.5.1.2.4: Linear = (Encoded / Scale)^gamma.
  return {std::pow(e[0], decode.gamma), std::pow(e[1], decode.gamma), std::pow(e[2], decode.gamma)};
}

std::array<double, 3> MpcdiColourProfile::corrected(const std::array<double, 3>& linear) const {
  switch (correct.type) {
    case Correct::Type::none: return clamped(linear);
    case Correct::Type::lut3d: return clamped(correct.lut->apply(linear));  // correctColor3D
    case Correct::Type::lut1d_primary: {  // correctColor1D: the 1D LUT, then the primaries matrix
      const std::array<double, 3> l = correct.lut ? correct.lut->apply(linear) : linear;
      std::array<double, 3> out{};
      for (std::size_t i = 0; i < 3; ++i)
        out[i] = correct.primaries[i][0] * l[0] + correct.primaries[i][1] * l[1] + correct.primaries[i][2] * l[2];
      return clamped(out);
    }
  }
  return clamped(linear);
}

std::array<double, 3> MpcdiColourProfile::encoded(const std::array<double, 3>& linear) const {
  const std::array<double, 3> l = clamped(linear);
  switch (encode.type) {
    case Encode::Type::none: return l;
    case Encode::Type::gamma: {  // §2.5.1.2.4: Encoded = Scale · Linear^(1 / gamma)
      const double inverse = 1.0 / encode.gamma;
      return {std::pow(l[0], inverse), std::pow(l[1], inverse), std::pow(l[2], inverse)};
    }
    case Encode::Type::lut1d:
    case Encode::Type::lut3d: return clamped(encode.lut->apply(l));
  }
  return l;
}

std::array<double, 3> MpcdiColourProfile::process(const std::array<double, 3>& signal, double alpha,
                                                  double black_level) const {
  std::array<double, 3> l = corrected(decoded(signal));
  for (double& c : l) c = alpha * c * (1.0 - black_level) + black_level;  // processPixel's local correction
  return encoded(l);
}

std::string describe(const MpcdiColourProfile& p) {
  using D = MpcdiColourProfile::Decode::Type;
  using C = MpcdiColourProfile::Correct::Type;
  using E = MpcdiColourProfile::Encode::Type;
  const std::string decode = p.decode.type == D::gamma ? fmt::format("decode gamma {}", p.decode.gamma)
                                                       : "decode lut1d" + lut_text(p.decode.lut);
  const std::string correct = p.correct.type == C::none            ? "correct none"
                              : p.correct.type == C::lut1d_primary ? "correct lut1d-primary" + lut_text(p.correct.lut)
                                                                   : "correct lut3d" + lut_text(p.correct.lut);
  std::string encode = "encode none";
  if (p.encode.type == E::gamma) encode = fmt::format("encode gamma {}", p.encode.gamma);
  if (p.encode.type == E::lut1d) encode = "encode lut1d" + lut_text(p.encode.lut);
  if (p.encode.type == E::lut3d) encode = "encode lut3d" + lut_text(p.encode.lut);
  return decode + ", " + correct + ", " + encode;
}

}  // namespace zenith::warp
