// The fade on the CPU (image/display_fade.h): the GPU's mix(P, colour, f).
#include "image/display_fade.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace zenith::image {
namespace {

TEST(DisplayFade, MixesEachPixelTowardTheColour) {
  std::vector<float> rgb = {0.8f, 0.4f, 0.0f, 1.0f, 1.0f, 1.0f};
  apply_fade(rgb, 0.5, {0.0, 0.0, 1.0});
  const std::vector<float> expected = {0.4f, 0.2f, 0.5f, 0.5f, 0.5f, 1.0f};
  for (std::size_t i = 0; i < rgb.size(); ++i) EXPECT_NEAR(rgb[i], expected[i], 1e-7f) << i;
  std::vector<float> black = {0.3f, 0.6f, 0.9f};
  apply_fade(black, 1.0, {0.0, 0.0, 0.0});  // a blackout: exactly 0
  EXPECT_EQ(black, (std::vector<float>{0.0f, 0.0f, 0.0f}));
  std::vector<float> same = {0.3f, 0.6f, 0.9f};
  apply_fade(same, 0.0, {1.0, 1.0, 1.0});  // level 0: untouched, bit for bit
  EXPECT_EQ(same, (std::vector<float>{0.3f, 0.6f, 0.9f}));
}

TEST(DisplayFade, RefusesLevelsColoursAndSizesOutOfRange) {
  std::vector<float> rgb(3, 0.5f);
  EXPECT_THROW(apply_fade(rgb, 1.5, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(apply_fade(rgb, -0.1, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(apply_fade(rgb, 0.5, {0, 1.1, 0}), std::invalid_argument);
  std::vector<float> odd(4, 0.5f);
  EXPECT_THROW(apply_fade(odd, 0.5, {0, 0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::image
