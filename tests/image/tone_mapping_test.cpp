// Tone mapping operators, the sRGB transfer function and the 8-bit quantizer.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "image/srgb_quantizer.h"
#include "image/tone_mapping.h"

namespace zenith::image {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(ToneMapping, ExponentialHasItsClosedForm) {
  EXPECT_FLOAT_EQ(tone_map(1.0f, ToneMapping::exponential), float(1.0 - std::exp(-1.0)));  // 0.632121
  EXPECT_FLOAT_EQ(tone_map(2.0f, ToneMapping::exponential), float(1.0 - std::exp(-2.0)));
  EXPECT_FLOAT_EQ(tone_map(0.25f, ToneMapping::exponential), float(1.0 - std::exp(-0.25)));
  // Small x keep their relative precision: 1 − e^−x ≈ x − x²/2.
  EXPECT_FLOAT_EQ(tone_map(1e-6f, ToneMapping::exponential), 1e-6f * (1.0f - 0.5e-6f));
  EXPECT_EQ(tone_map(0.0f, ToneMapping::exponential), 0.0f);
  EXPECT_EQ(tone_map(100.0f, ToneMapping::exponential), 1.0f);
  EXPECT_EQ(tone_map(kInf, ToneMapping::exponential), 1.0f);
}

TEST(ToneMapping, NegativeAndNaNGiveZero) {
  for (ToneMapping tone : {ToneMapping::exponential, ToneMapping::clamp}) {
    EXPECT_EQ(tone_map(-1.0f, tone), 0.0f) << to_string(tone);
    EXPECT_EQ(tone_map(-kInf, tone), 0.0f) << to_string(tone);
    EXPECT_EQ(tone_map(kNaN, tone), 0.0f) << to_string(tone);
    EXPECT_EQ(display_byte(kNaN, tone), 0) << to_string(tone);
  }
}

TEST(ToneMapping, ClampIsMinOfXAndOne) {
  EXPECT_EQ(tone_map(0.3f, ToneMapping::clamp), 0.3f);
  EXPECT_EQ(tone_map(1.0f, ToneMapping::clamp), 1.0f);
  EXPECT_EQ(tone_map(7.0f, ToneMapping::clamp), 1.0f);
  EXPECT_EQ(tone_map(kInf, ToneMapping::clamp), 1.0f);
}

TEST(ToneMapping, NamesRoundTripAndUnknownNamesAreListed) {
  for (ToneMapping tone : {ToneMapping::exponential, ToneMapping::clamp})
    EXPECT_EQ(parse_tone_mapping(to_string(tone)), tone);
  try {
    parse_tone_mapping("reinhard");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("reinhard"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("exponential, clamp"), std::string::npos) << e.what();
  }
}

TEST(Srgb, EncodeMatchesIec61966Values) {
  EXPECT_NEAR(srgb_encode(0.0031308f), 0.0404482f, 2e-6f);  // the knee: 12.92 · 0.0031308 = 0.0404499
  EXPECT_NEAR(srgb_encode(0.5f), 0.735357f, 1e-6f);         // 1.055 · 0.5^(1/2.4) − 0.055
  EXPECT_NEAR(srgb_encode(0.18f), 0.461356f, 1e-6f);
  EXPECT_FLOAT_EQ(srgb_encode(0.001f), 0.01292f);  // linear segment
  EXPECT_EQ(srgb_encode(0.0f), 0.0f);
  EXPECT_EQ(srgb_encode(1.0f), 1.0f);
  EXPECT_EQ(srgb_encode(-0.5f), 0.0f);  // clamped
  EXPECT_EQ(srgb_encode(2.0f), 1.0f);
  EXPECT_EQ(srgb_encode(kNaN), 0.0f);
  EXPECT_NEAR(srgb_decode(0.735357f), 0.5f, 1e-6f);
  EXPECT_FLOAT_EQ(srgb_decode(0.04f), 0.04f / 12.92f);
  EXPECT_EQ(srgb_decode(1.0f), 1.0f);
  EXPECT_EQ(srgb_decode(kNaN), 0.0f);
}

TEST(Srgb, DecodeInvertsEncode) {
  float worst = 0.0f;
  for (int i = 0; i <= 200000; ++i) {
    const float x = float(i) / 200000.0f;
    worst = std::max(worst, std::fabs(srgb_decode(srgb_encode(x)) - x));
  }
  for (float x : {0.0031307f, 0.0031308f, 0.0031309f, 1e-30f, 1e-7f})
    worst = std::max(worst, std::fabs(srgb_decode(srgb_encode(x)) - x));
  EXPECT_LE(worst, 1e-6f);
}

TEST(Srgb, EncodeIsMonotonic) {
  float previous = 0.0f;
  for (int i = 0; i <= 100000; ++i) {
    const float e = srgb_encode(float(i) / 100000.0f);
    ASSERT_GE(e, previous) << i;
    previous = e;
  }
}

TEST(DisplayByte, IsTheRoundedEncodedToneMappedValue) {
  EXPECT_EQ(display_byte(0.0f, ToneMapping::exponential), 0);
  EXPECT_EQ(display_byte(kInf, ToneMapping::exponential), 255);
  EXPECT_EQ(display_byte(1.0f, ToneMapping::clamp), 255);
  EXPECT_EQ(display_byte(0.5f, ToneMapping::clamp), 188);  // 255 · 0.735357 = 187.52
  // 1 − e^−1 = 0.632121 → 0.8167 → 208.26
  EXPECT_EQ(display_byte(1.0f, ToneMapping::exponential), 208);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 3.0);
  for (int i = 0; i < 10000; ++i) {
    const float x = float(u(rng));
    const double t = 1.0 - std::exp(-double(x));
    const double e = t <= 0.0031308 ? 12.92 * t : 1.055 * std::pow(t, 1.0 / 2.4) - 0.055;
    // Away from the rounding ties the float pipeline agrees with double arithmetic.
    if (std::fabs(255.0 * e - std::floor(255.0 * e) - 0.5) > 1e-3) {
      ASSERT_EQ(display_byte(x, ToneMapping::exponential), int(std::lround(255.0 * e))) << x;
    }
  }
}

TEST(DisplaySlope, IsTheDerivativeOfTheChainAndBoundsEveryChangeAboveIt) {
  // The closed forms: 255 · 12.92 at black for either operator; on the power
  // branch 255 · (1.055/2.4) T^(1/2.4 − 1) e^(−x) (exponential) against the
  // same at T = x (clamp, the larger below 1); 0 beyond white for clamp.
  EXPECT_DOUBLE_EQ(display_code_slope_bound(0.0), 255.0 * 12.92);
  EXPECT_DOUBLE_EQ(srgb_encode_slope(0.0031308), 12.92);
  EXPECT_NEAR(srgb_encode_slope(0.0031309), 12.703, 1e-3);
  EXPECT_DOUBLE_EQ(tone_map_slope(2.0, ToneMapping::exponential), std::exp(-2.0));
  EXPECT_DOUBLE_EQ(tone_map_slope(2.0, ToneMapping::clamp), 0.0);
  EXPECT_NEAR(display_code_slope_bound(0.5), 255.0 * 1.055 / 2.4 * std::pow(0.5, 1.0 / 2.4 - 1.0), 1e-9);
  EXPECT_NEAR(display_code_slope_bound(2.0),
              255.0 * 1.055 / 2.4 * std::pow(1.0 - std::exp(-2.0), 1.0 / 2.4 - 1.0) * std::exp(-2.0), 1e-9);
  // The bound: from any background x' ≥ x, a change by Δ moves the code value
  // 255 · E(T(·)) by at most slope(x) · Δ (concavity), for both operators, and
  // a central difference at x approaches the slope of the steeper operator.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> log_x(-7.0, 1.5), log_d(-9.0, -1.0), above(0.0, 3.0);
  for (int i = 0; i < 20000; ++i) {
    const double x = std::pow(10.0, log_x(rng)), delta = std::pow(10.0, log_d(rng)), at = x * (1.0 + above(rng));
    const double bound = display_code_slope_bound(x) * delta;
    for (ToneMapping tone : {ToneMapping::exponential, ToneMapping::clamp}) {
      const double t0 = tone == ToneMapping::exponential ? -std::expm1(-at) : std::min(at, 1.0);
      const double t1 = tone == ToneMapping::exponential ? -std::expm1(-(at + delta)) : std::min(at + delta, 1.0);
      const auto encode = [](double t) {
        return t >= 1.0 ? 1.0 : t <= 0.0031308 ? 12.92 * t : 1.055 * std::pow(t, 1.0 / 2.4) - 0.055;
      };
      ASSERT_LE(255.0 * (encode(t1) - encode(t0)), bound * (1.0 + 1e-9) + 1e-12) << x << " " << at << " " << delta;
    }
  }
  for (double x : {1e-4, 0.01, 0.2, 1.5}) {
    const double h = 1e-7 * x, up = x + h, down = x - h;
    const auto code = [](double v) {
      const double t = std::min(v, 1.0);  // clamp: the steeper below 1
      return 255.0 * (t <= 0.0031308 ? 12.92 * t : 1.055 * std::pow(t, 1.0 / 2.4) - 0.055);
    };
    if (x < 1.0) {
      EXPECT_NEAR((code(up) - code(down)) / (2 * h), display_code_slope_bound(x), 1e-4 * x + 1e-3) << x;
    }
  }
}

int formula(float t) { return int(std::lround(255.0f * srgb_encode(t))); }

TEST(SrgbQuantizer, EqualsTheFormulaForEveryFloatNearEachStep) {
  const SrgbQuantizer q;
  for (int k = 1; k <= 255; ++k) {
    const float step = q.step(k);
    ASSERT_EQ(formula(step), k);
    ASSERT_LT(formula(std::nextafter(step, 0.0f)), k);
    // Exhaustively, the 4096 floats around the step.
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(step);
    for (std::uint32_t b = bits - 2048; b <= bits + 2048; ++b) {
      const float t = std::bit_cast<float>(b);
      ASSERT_EQ(q(t), formula(t)) << "t = " << t << " near step " << k;
    }
  }
}

TEST(SrgbQuantizer, EqualsTheFormulaAcrossTheRangeAndAtSpecialValues) {
  const SrgbQuantizer q;
  const std::uint32_t one = std::bit_cast<std::uint32_t>(1.0f);
  for (std::uint32_t b = 0; b <= one; b += 4099)
    ASSERT_EQ(q(std::bit_cast<float>(b)), formula(std::bit_cast<float>(b)));
  for (float t : {0.0f, -0.0f, -1.0f, 1e-45f, 1.0f, 1.5f, kInf, -kInf}) EXPECT_EQ(q(t), formula(t)) << t;
  EXPECT_EQ(q(kNaN), 0);
}

}  // namespace
}  // namespace zenith::image
