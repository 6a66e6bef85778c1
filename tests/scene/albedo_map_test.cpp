#include "scene/albedo_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/units.h"

namespace zenith::scene {
namespace {

using core::kPi;

struct Pixel {
  double r, g, b;
};
Pixel at(const image::LinearImage& img, int x, int y) {
  const float* p = &img.rgb[(std::size_t(y) * img.width + x) * 3];
  return {p[0], p[1], p[2]};
}
double latitude_of_row(const image::LinearImage& img, int y) {
  return (90.0 - (y + 0.5) * 180.0 / img.height) * kPi / 180;
}

/// Mean |difference| between two columns, and between neighbouring columns inside the map.
double column_difference(const image::LinearImage& img, int a, int b) {
  double sum = 0.0;
  for (int y = 0; y < img.height; ++y) {
    const Pixel p = at(img, a, y), q = at(img, b, y);
    sum += std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b);
  }
  return sum / img.height;
}

/// Every generator; NoiseGenerators: the random ones (the checker is a fixed pattern with a cell edge at 180°).
class Generators : public ::testing::TestWithParam<std::string> {};
class NoiseGenerators : public ::testing::TestWithParam<std::string> {};

TEST_P(Generators, DeterministicInRangeAndSizedAsAsked) {
  const auto a = generate_albedo_map(GetParam(), 7, 128, 64);
  const auto b = generate_albedo_map(GetParam(), 7, 128, 64);
  ASSERT_EQ(a.width, 128);
  ASSERT_EQ(a.height, 64);
  ASSERT_EQ(a.rgb.size(), 128u * 64u * 3u);
  EXPECT_EQ(a.rgb, b.rgb);
  for (float v : a.rgb) {
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
  }
}

TEST_P(NoiseGenerators, SeedsGiveDifferentMaps) {
  EXPECT_NE(generate_albedo_map(GetParam(), 1, 64, 32).rgb, generate_albedo_map(GetParam(), 2, 64, 32).rgb);
}

TEST_P(NoiseGenerators, SeamlessAcrossLongitude180) {
  // The first and last columns are neighbours on the sphere (half a pixel either
  // side of 180°): they differ no more than any two neighbouring columns do.
  const auto img = generate_albedo_map(GetParam(), 3, 512, 256);
  const double seam = column_difference(img, 0, img.width - 1);
  double interior = 0.0;
  for (int x = 0; x + 1 < img.width; ++x) interior += column_difference(img, x, x + 1);
  interior /= img.width - 1;
  EXPECT_LT(seam, 2.0 * interior + 1e-3) << "seam " << seam << ", neighbouring columns " << interior;
}

TEST_P(NoiseGenerators, NoPinchingAtThePoles) {
  // All pixels of the top row are within a few pixel heights of the pole: on the
  // sphere they are close together, so the row is nearly uniform.
  const auto img = generate_albedo_map(GetParam(), 5, 256, 128);
  for (int y : {0, img.height - 1}) {
    double lo = 1.0, hi = 0.0;
    for (int x = 0; x < img.width; ++x) {
      lo = std::min(lo, at(img, x, y).g);
      hi = std::max(hi, at(img, x, y).g);
    }
    EXPECT_LT(hi - lo, 0.12) << "row " << y;
  }
}

INSTANTIATE_TEST_SUITE_P(All, Generators, ::testing::Values("earth", "moon", "mars", "checker"));
INSTANTIATE_TEST_SUITE_P(All, NoiseGenerators, ::testing::Values("earth", "moon", "mars"));

TEST(EarthMap, OceanLandAndIceFractions) {
  for (std::uint32_t seed : {1u, 2u, 42u}) {
    const auto img = generate_albedo_map("earth", seed, 256, 128);
    double ocean = 0.0, ice = 0.0, land = 0.0, total = 0.0, ocean_reflectance = 0.0;
    for (int y = 0; y < img.height; ++y) {
      const double w = std::cos(latitude_of_row(img, y));  // area weight
      for (int x = 0; x < img.width; ++x) {
        const Pixel p = at(img, x, y);
        total += w;
        if (std::min({p.r, p.g, p.b}) > 0.5) {
          ice += w;
        } else if (p.b > p.r + 0.02 && p.b < 0.2) {
          ocean += w;
          ocean_reflectance += w * (p.r + p.g + p.b) / 3.0;
        } else {
          land += w;
        }
      }
    }
    EXPECT_GT(ocean / total, 0.5) << seed;
    EXPECT_LT(ocean / total, 0.8) << seed;
    EXPECT_GT(land / total, 0.15) << seed;
    EXPECT_GT(ice / total, 0.02) << seed;
    EXPECT_LT(ice / total, 0.15) << seed;
    EXPECT_NEAR(ocean_reflectance / ocean, 0.06, 0.03) << seed;
    // Ice at both poles.
    EXPECT_GT(at(img, 10, 0).r, 0.5);
    EXPECT_GT(at(img, 10, img.height - 1).r, 0.5);
  }
}

TEST(EarthMap, SameSeedSamePlanetAtAnySize) {
  // Thresholds do not depend on the map size: a pixel of the small map equals
  // the co-located pixel of a map twice as large... up to the sampling offset,
  // so compare the small map with the large one averaged 2×2.
  const auto small = generate_albedo_map("earth", 9, 128, 64);
  const auto large = generate_albedo_map("earth", 9, 256, 128);
  double differ = 0.0;
  for (int y = 0; y < small.height; ++y)
    for (int x = 0; x < small.width; ++x) {
      double mean = 0.0;
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) mean += at(large, 2 * x + i, 2 * y + j).g / 4.0;
      differ += std::abs(mean - at(small, x, y).g);
    }
  EXPECT_LT(differ / (small.width * small.height), 0.02);
}

TEST(MoonMap, GreyWithDarkMaria) {
  const auto img = generate_albedo_map("moon", 1, 256, 128);
  double dark = 0.0, total = 0.0, mean = 0.0;
  for (int y = 0; y < img.height; ++y) {
    const double w = std::cos(latitude_of_row(img, y));
    for (int x = 0; x < img.width; ++x) {
      const Pixel p = at(img, x, y);
      EXPECT_NEAR(p.r, p.g, 0.03);
      EXPECT_NEAR(p.b, p.g, 0.03);
      EXPECT_GT(p.g, 0.03);
      EXPECT_LT(p.g, 0.35);
      total += w;
      mean += w * p.g;
      if (p.g < 0.1) dark += w;
    }
  }
  EXPECT_GT(mean / total, 0.08);
  EXPECT_LT(mean / total, 0.2);
  EXPECT_GT(dark / total, 0.08);  // maria (and crater floors)
  EXPECT_LT(dark / total, 0.4);
}

TEST(MarsMap, RustWithDarkRegionsAndCaps) {
  const auto img = generate_albedo_map("mars", 1, 256, 128);
  double r = 0.0, g = 0.0, b = 0.0, total = 0.0, dark = 0.0;
  for (int y = 8; y < img.height - 8; ++y) {  // away from the caps
    const double w = std::cos(latitude_of_row(img, y));
    for (int x = 0; x < img.width; ++x) {
      const Pixel p = at(img, x, y);
      r += w * p.r;
      g += w * p.g;
      b += w * p.b;
      total += w;
      if (p.r < 0.22) dark += w;
    }
  }
  EXPECT_NEAR(r / total, 0.33, 0.06);
  EXPECT_NEAR(g / total, 0.17, 0.04);
  EXPECT_NEAR(b / total, 0.08, 0.03);
  EXPECT_GT(dark / total, 0.1);
  EXPECT_LT(dark / total, 0.45);
  EXPECT_GT(at(img, 0, 0).g, 0.5);               // north cap
  EXPECT_GT(at(img, 0, img.height - 1).g, 0.5);  // south cap
}

TEST(CheckerMap, ThirtyDegreeCells) {
  const auto img = generate_albedo_map("checker", 0, 360, 180);  // 1 px per degree
  EXPECT_FLOAT_EQ(at(img, 0, 0).g, 0.8f);                        // lon −180..−150, lat 90..60
  EXPECT_FLOAT_EQ(at(img, 29, 29).g, 0.8f);
  EXPECT_FLOAT_EQ(at(img, 30, 0).g, 0.2f);     // next cell east
  EXPECT_FLOAT_EQ(at(img, 0, 30).g, 0.2f);     // next cell south
  EXPECT_FLOAT_EQ(at(img, 359, 179).g, 0.8f);  // 11 + 5 even
  EXPECT_FLOAT_EQ(at(img, 181, 91).r, 0.2f);   // lon 1, lat −1: cell (6, 3)
}

TEST(AlbedoMaps, UnknownGeneratorAndBadSizesAreRejected) {
  try {
    generate_albedo_map("venus", 1, 64, 32);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("venus"), std::string::npos) << what;
    for (const auto& name : albedo_generators()) EXPECT_NE(what.find(name), std::string::npos) << what;
  }
  EXPECT_THROW(generate_albedo_map("earth", 1, 1, 32), std::invalid_argument);
  EXPECT_THROW(generate_albedo_map("earth", 1, 64, 9000), std::invalid_argument);
}

TEST(AlbedoMaps, LoadConstantAndProcedural) {
  AlbedoSource constant;
  constant.colour_linear_rgb = {0.1, 0.5, 1.5};
  const auto c = load_albedo_map(constant);
  ASSERT_EQ(c.width, 1);
  ASSERT_EQ(c.height, 1);
  EXPECT_FLOAT_EQ(c.rgb[0], 0.1f);
  EXPECT_FLOAT_EQ(c.rgb[1], 0.5f);
  EXPECT_FLOAT_EQ(c.rgb[2], 1.0f);  // clamped

  AlbedoSource procedural;
  procedural.kind = AlbedoSource::Kind::procedural;
  procedural.procedural = "checker";
  procedural.width_px = 24;
  procedural.height_px = 12;
  const auto p = load_albedo_map(procedural);
  EXPECT_EQ(p.width, 24);
  EXPECT_EQ(p.rgb, generate_albedo_map("checker", 1, 24, 12).rgb);

  AlbedoSource missing;
  missing.kind = AlbedoSource::Kind::image;
  missing.image_path = "/nonexistent/map.png";
  EXPECT_THROW(load_albedo_map(missing), std::runtime_error);
}

TEST(AlbedoMaps, TheKeyNamesTheSource) {
  AlbedoSource a, b;
  b.colour_linear_rgb = {0.3, 0.3, 0.31};
  EXPECT_NE(albedo_key(a), albedo_key(b));
  AlbedoSource p = a;
  p.kind = AlbedoSource::Kind::procedural;
  p.procedural = "moon";
  AlbedoSource q = p;
  q.seed = 2;
  EXPECT_NE(albedo_key(p), albedo_key(q));
  EXPECT_EQ(albedo_key(p), albedo_key(AlbedoSource(p)));
}

}  // namespace
}  // namespace zenith::scene
