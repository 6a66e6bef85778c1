#include "scene/albedo_map_cache.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "scene/albedo_map.h"

namespace zenith::scene {
namespace {

AlbedoSource procedural(const std::string& generator, std::uint32_t seed, int width_px, int height_px) {
  AlbedoSource s;
  s.kind = AlbedoSource::Kind::procedural;
  s.procedural = generator;
  s.seed = seed;
  s.width_px = width_px;
  s.height_px = height_px;
  return s;
}

/// A fresh directory under the system's temporary one, removed with the test.
class AlbedoMapCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = std::filesystem::temp_directory_path() / ("zenith-albedo-cache-" + std::to_string(::getpid()));
    std::filesystem::remove_all(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }
  std::filesystem::path directory_;
};

TEST_F(AlbedoMapCacheTest, AStoredMapComesBackWithTheSameBitsAndSkipsTheGenerator) {
  const AlbedoSource mars = procedural("mars", 3, 64, 32);
  const image::LinearImage generated = generate_albedo_map("mars", 3, 64, 32);
  {
    AlbedoMapCache cache(directory_);
    const image::LinearImage first = cache.load(mars);
    EXPECT_EQ(first.rgb, generated.rgb);
    EXPECT_EQ(cache.statistics().generated, 1);
    EXPECT_EQ(cache.statistics().stored, 1);
    EXPECT_TRUE(std::filesystem::exists(cache.file_of(mars)));
  }
  AlbedoMapCache later(directory_);  // a later run
  const image::LinearImage again = later.load(mars);
  EXPECT_EQ(later.statistics().read, 1);
  EXPECT_EQ(later.statistics().generated, 0);
  ASSERT_EQ(again.width, 64);
  ASSERT_EQ(again.height, 32);
  EXPECT_EQ(again.rgb, generated.rgb) << "the same pixels to the bit";
}

TEST_F(AlbedoMapCacheTest, EverythingThatMakesTheMapIsInItsFileName) {
  const AlbedoMapCache cache(directory_);
  const std::filesystem::path base = cache.file_of(procedural("earth", 1, 64, 32));
  EXPECT_EQ(base.parent_path(), directory_);
  EXPECT_EQ(base, cache.file_of(procedural("earth", 1, 64, 32)));
  EXPECT_NE(base, cache.file_of(procedural("earth", 2, 64, 32)));
  EXPECT_NE(base, cache.file_of(procedural("mars", 1, 64, 32)));
  EXPECT_NE(base, cache.file_of(procedural("earth", 1, 128, 32)));
  EXPECT_NE(base, cache.file_of(procedural("earth", 1, 64, 64)));
  // The fingerprint follows the planet, not the map: any size, the same one; another seed, another.
  EXPECT_EQ(procedural_albedo_fingerprint("earth", 1), procedural_albedo_fingerprint("earth", 1));
  EXPECT_NE(procedural_albedo_fingerprint("earth", 1), procedural_albedo_fingerprint("earth", 2));
  EXPECT_EQ(procedural_albedo_fingerprint("earth", 1).size(), 64u);
}

TEST_F(AlbedoMapCacheTest, ABrokenFileIsGeneratedAgainAndReplaced) {
  const AlbedoSource moon = procedural("moon", 1, 32, 16);
  const image::LinearImage generated = generate_albedo_map("moon", 1, 32, 16);
  AlbedoMapCache cache(directory_);
  cache.load(moon);
  const std::filesystem::path file = cache.file_of(moon);
  const auto whole = std::filesystem::file_size(file);
  EXPECT_EQ(whole, 16u + 32u * 16u * 3u * 4u) << "magic, width, height, the floats";

  for (const auto& spoil : {+[](const std::filesystem::path& f) { std::filesystem::resize_file(f, 100); },
                            +[](const std::filesystem::path& f) { std::ofstream(f, std::ios::app) << "x"; },
                            +[](const std::filesystem::path& f) { std::ofstream(f) << "not a map at all"; }}) {
    spoil(file);
    AlbedoMapCache later(directory_);
    EXPECT_EQ(later.load(moon).rgb, generated.rgb);
    EXPECT_EQ(later.statistics().read, 0);
    EXPECT_EQ(later.statistics().generated, 1);
    EXPECT_EQ(std::filesystem::file_size(file), whole) << "replaced by a whole one";
  }
}

TEST_F(AlbedoMapCacheTest, ConstantsAndImagesAreNotCopiedAndAnUnwritableCacheStillGivesTheMap) {
  AlbedoMapCache cache(directory_);
  AlbedoSource constant;
  constant.colour_linear_rgb = {0.2, 0.4, 1.5};
  const image::LinearImage c = cache.load(constant);
  EXPECT_EQ(c.rgb, (std::vector<float>{0.2f, 0.4f, 1.0f}));
  EXPECT_FALSE(std::filesystem::exists(directory_)) << "nothing stored for a constant";

  std::ofstream(directory_.string() + "-file") << "a file where the directory should be";
  AlbedoMapCache blocked(directory_.string() + "-file");
  const AlbedoSource checker = procedural("checker", 1, 24, 12);
  EXPECT_EQ(blocked.load(checker).rgb, generate_albedo_map("checker", 1, 24, 12).rgb);
  EXPECT_EQ(blocked.statistics().stored, 0);
  std::filesystem::remove(directory_.string() + "-file");
}

}  // namespace
}  // namespace zenith::scene
