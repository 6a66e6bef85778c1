// Which program variant a live frame draws with (render/frame/live_variants.h).
#include "render/frame/live_variants.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace zenith::render {
namespace {

FrameVariant variant(int projection_kind, bool eclipses, bool albedo_lod0) {
  return {.projection_kind = projection_kind, .eclipses = eclipses, .albedo_lod0 = albedo_lod0};
}

TEST(LiveVariants, AVariantServesThoseThatNeedLess) {
  EXPECT_TRUE(variant_serves(variant(0, true, false), variant(0, false, true)));
  EXPECT_TRUE(variant_serves(variant(0, true, false), variant(0, true, false)));
  EXPECT_FALSE(variant_serves(variant(0, false, false), variant(0, true, false))) << "no eclipse code";
  EXPECT_FALSE(variant_serves(variant(0, true, true), variant(0, true, false))) << "level 0 only";
  EXPECT_FALSE(variant_serves(variant(1, true, false), variant(0, false, false))) << "another projection";
}

TEST(LiveVariants, OnlyAVariantWithTheAirShadowCodeServesAFrameWithAnAirShadow) {
  FrameVariant solid = variant(0, true, false), air = solid;
  solid.air_shadows = false;
  EXPECT_TRUE(variant_serves(air, solid));
  EXPECT_FALSE(variant_serves(solid, air)) << "a lunar eclipse seen from space needs the air shadows' code";
  EXPECT_NE(solid.key(), air.key());
  FrameVariant none = variant(0, false, false), none_air = none;
  none.air_shadows = false;
  EXPECT_EQ(none.key(), none_air.key()) << "without eclipses there is no air shadow code either way";
}

TEST(LiveVariants, TheVariantInUseDrawsWhileTheLeanerOneBuilds) {
  LiveVariants live;
  std::set<std::string> built;  // the frame's programs built, by variant
  const LiveVariants::Built is_built = [&](const FrameVariant& v) { return built.contains(v.key()); };
  const FrameVariant general = variant(2, true, false), lean = variant(2, false, true);
  EXPECT_EQ(live.provisional(general).key(), general.key());
  EXPECT_EQ(live.choose(general, is_built).key(), general.key()) << "nothing built: the frame builds its own";
  built.insert(general.key());
  EXPECT_FALSE(live.drew(general, general, true, is_built)) << "the general variant is the one drawn";

  EXPECT_EQ(live.provisional(lean).key(), general.key()) << "started before the tiles are known: the one in use";
  EXPECT_EQ(live.choose(lean, is_built).key(), general.key());
  const std::optional<FrameVariant> next = live.drew(general, lean, true, is_built);
  ASSERT_TRUE(next);
  EXPECT_EQ(next->key(), lean.key());
  EXPECT_FALSE(live.drew(general, lean, true, is_built)) << "one build ahead at a time";
  EXPECT_EQ(live.choose(lean, is_built).key(), general.key()) << "not built yet";

  built.insert(lean.key());
  live.built_ahead();
  EXPECT_FALSE(live.building());
  EXPECT_EQ(live.choose(lean, is_built).key(), lean.key());
  EXPECT_FALSE(live.drew(lean, lean, true, is_built));
  EXPECT_EQ(live.choose(general, is_built).key(), general.key()) << "built before: no wait either way";

  // A frame with a tile kind the lean variant has no program for: the general one draws it meanwhile.
  built.erase(lean.key());
  EXPECT_EQ(live.choose(lean, is_built).key(), lean.key()) << "the lean variant in use serves only itself";
  live.drew(general, general, true, is_built);
  EXPECT_EQ(live.choose(lean, is_built).key(), general.key());
}

TEST(LiveVariants, TheGeneralVariantIsBuiltAheadOfTheFrameThatNeedsIt) {
  // A show that starts with no shadow possible: the lean variant is built by
  // the first frame, the general one ahead, for the frame where the bodies
  // come near enough to shadow one another.
  LiveVariants live;
  std::set<std::string> built;
  const LiveVariants::Built is_built = [&](const FrameVariant& v) { return built.contains(v.key()); };
  const FrameVariant lean = variant(0, false, false), general = variant(0, true, false);
  built.insert(lean.key());
  const std::optional<FrameVariant> next = live.drew(lean, lean, true, is_built);
  ASSERT_TRUE(next);
  EXPECT_EQ(next->key(), general.key());
  EXPECT_EQ(live.choose(general, is_built).key(), general.key()) << "no variant serves it yet: the frame builds it";
  built.insert(general.key());
  live.built_ahead();
  EXPECT_FALSE(live.drew(general, general, true, is_built));
  EXPECT_FALSE(LiveVariants().drew(lean, lean, false, is_built)) << "one body: the lean variant is the general one";
}

}  // namespace
}  // namespace zenith::render
