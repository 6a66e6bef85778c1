// The master's table versions without tables or sockets
// (cluster/master/table_versions.h; docs/cluster.md, "Table versions").
#include "cluster/master/table_versions.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace zenith::cluster {
namespace {

using test::digest;

atmosphere::LoadedAtmosphere atmosphere_with(const char* name) {
  atmosphere::LoadedAtmosphere loaded;
  loaded.parameters = {{"name", name}};
  return loaded;
}

TEST(TableVersions, WantsEveryCurrentVersionOnce) {
  TableVersions versions;
  versions.add_current("Earth", digest(1));
  versions.add_current("Mars", digest(2));
  versions.add_current("Moon-ish", digest(1));
  EXPECT_EQ(versions.wanted_sets(), (std::vector<Digest>{digest(1), digest(2)}));
  EXPECT_EQ(versions.current().size(), 3u);
  EXPECT_EQ(versions.current()[1].body_name, "Mars");
  EXPECT_EQ(versions.current()[1].effective_from_frame, 0u);
}

TEST(TableVersions, ANodeIsReadyWhenItHoldsEveryCurrentVersion) {
  TableVersions versions;
  versions.add_current("Earth", digest(1));
  versions.add_current("Mars", digest(2));
  EXPECT_FALSE(versions.ready_with({digest(1)}));
  EXPECT_TRUE(versions.ready_with({digest(1), digest(2)}));
  EXPECT_TRUE(versions.ready_with({digest(1), digest(2), digest(9)}));
}

TEST(TableVersions, APendingVersionIsWantedOnlyOnceDistributed) {
  TableVersions versions;
  versions.add_current("Earth", digest(1));
  versions.begin_pending(0, digest(5));
  ASSERT_TRUE(versions.pending());
  EXPECT_FALSE(versions.pending()->distributed);
  EXPECT_EQ(versions.wanted_sets(), (std::vector<Digest>{digest(1)}));
  const auto now = TableVersions::Clock::now();
  versions.mark_distributed(now);
  EXPECT_TRUE(versions.pending()->distributed);
  EXPECT_EQ(versions.pending()->distributed_at, now);
  EXPECT_EQ(versions.wanted_sets(), (std::vector<Digest>{digest(1), digest(5)}));
  EXPECT_TRUE(versions.ready_with({digest(1)})) << "a pending version does not hold a node back";
}

TEST(TableVersions, ApplyingThePendingVersionChangesTheCurrentOneFromAFrame) {
  TableVersions versions;
  versions.add_current("Earth", digest(1));
  versions.add_current("Mars", digest(2));
  versions.begin_pending(1, digest(7));
  versions.mark_distributed(TableVersions::Clock::now());
  const AtmosphereTableRef before = versions.apply_pending(12);
  EXPECT_EQ(before.body_name, "Mars");
  EXPECT_EQ(before.table_hash, digest(2));
  EXPECT_FALSE(versions.pending());
  EXPECT_EQ(versions.current()[1].table_hash, digest(7));
  EXPECT_EQ(versions.current()[1].effective_from_frame, 12u);
  EXPECT_EQ(versions.current()[0].table_hash, digest(1));
  EXPECT_FALSE(versions.ready_with({digest(1), digest(2)}));
  EXPECT_TRUE(versions.ready_with({digest(1), digest(7)}));
  EXPECT_FALSE(versions.show_mode());
}

TEST(TableVersions, AnAbandonedVersionLeavesTheCurrentOne) {
  TableVersions versions;
  versions.add_current("Earth", digest(1));
  versions.begin_pending(0, digest(3));
  versions.abandon_pending();
  EXPECT_FALSE(versions.pending());
  EXPECT_EQ(versions.current()[0].table_hash, digest(1));
}

TableSetFile set_of(const Digest& hash) {
  TableSetFile set;
  set.body_name = "Earth";
  set.table_hash = hash;
  return set;
}

TEST(TableVersions, AShowWantsEverySetItUsesOnceItIsPrepared) {
  TableVersions versions;
  AtmosphereTableRef first;
  first.body_name = "Earth";
  first.table_hash = digest(1);
  versions.use_show_sets({digest(1), digest(2), digest(3)}, {first});
  EXPECT_EQ(versions.current().size(), 1u);
  EXPECT_TRUE(versions.wanted_sets().empty()) << "nothing prepared yet";
  EXPECT_FALSE(versions.ready_with({})) << "the first frame's versions, always";

  versions.add_set(set_of(digest(1)));
  EXPECT_EQ(versions.wanted_sets(), (std::vector<Digest>{digest(1)}));
  EXPECT_TRUE(versions.ready_with({digest(1)})) << "sets still being prepared do not hold a node back";

  versions.add_set(set_of(digest(3)));  // out of order: wanted in the show's order all the same
  versions.add_set(set_of(digest(2)));
  EXPECT_EQ(versions.wanted_sets(), (std::vector<Digest>{digest(1), digest(2), digest(3)}));
  EXPECT_FALSE(versions.ready_with({digest(1)})) << "every prepared set of the show";
  EXPECT_FALSE(versions.ready_with({digest(2), digest(3)}));
  EXPECT_TRUE(versions.ready_with({digest(1), digest(2), digest(3)}));
}

/// A show of Earth (sets 1, 2, 3; its first frame uses 1) and Mars (set 4).
TableVersions show_of_earth_and_mars() {
  TableVersions versions;
  AtmosphereTableRef earth, mars;
  earth.body_name = "Earth";
  earth.table_hash = digest(1);
  mars.body_name = "Mars";
  mars.table_hash = digest(4);
  versions.use_show_sets({digest(1), digest(2), digest(3), digest(4)}, {earth, mars});
  for (int i = 1; i <= 4; ++i) versions.add_set(set_of(digest(i)));
  return versions;
}

/// A show frame's versions: Earth `earth`, Mars 4, both effective from frame 0.
std::vector<AtmosphereTableRef> show_frame(int earth) {
  AtmosphereTableRef e, m;
  e.body_name = "Earth";
  e.table_hash = digest(earth);
  m.body_name = "Mars";
  m.table_hash = digest(4);
  return {e, m};
}

TEST(TableVersions, AnOperatorVersionOverridesAShowsAtmosphereFromItsFrameUntilCleared) {
  TableVersions versions = show_of_earth_and_mars();
  EXPECT_TRUE(versions.show_mode());
  EXPECT_TRUE(versions.is_show_set(digest(2)));
  EXPECT_FALSE(versions.is_show_set(digest(8)));
  EXPECT_FALSE(versions.override_of(0));
  EXPECT_EQ(versions.with_overrides(show_frame(2)), show_frame(2)) << "no override: the show's versions";

  // The operator's version of Earth: prepared, distributed, then in effect from frame 30.
  versions.begin_pending(0, digest(8));
  versions.add_set(set_of(digest(8)));
  EXPECT_EQ(versions.wanted_sets(), (std::vector<Digest>{digest(1), digest(2), digest(3), digest(4)}))
      << "not before it is distributed";
  versions.mark_distributed(TableVersions::Clock::now());
  EXPECT_EQ(versions.wanted_sets(), (std::vector<Digest>{digest(1), digest(2), digest(3), digest(4), digest(8)}));
  const std::set<Digest> show_sets = {digest(1), digest(2), digest(3), digest(4)};
  EXPECT_TRUE(versions.ready_with(show_sets)) << "a pending version does not hold a node back";
  const AtmosphereTableRef before = versions.apply_pending(30);
  EXPECT_EQ(before.table_hash, digest(1)) << "the show's first frame's";
  EXPECT_FALSE(versions.pending());
  ASSERT_TRUE(versions.override_of(0));
  EXPECT_EQ(versions.override_of(0)->table_hash, digest(8));
  EXPECT_EQ(versions.override_of(0)->effective_from_frame, 30u);
  EXPECT_FALSE(versions.override_of(1));
  EXPECT_EQ(versions.current()[0].table_hash, digest(1)) << "the show's own versions stay";

  // Every frame of the show has the override in Earth's place, whatever the track gives Earth.
  for (const int earth : {1, 2, 3}) {
    const std::vector<AtmosphereTableRef> refs = versions.with_overrides(show_frame(earth));
    EXPECT_EQ(refs[0].table_hash, digest(8));
    EXPECT_EQ(refs[0].effective_from_frame, 30u);
    EXPECT_EQ(refs[1], show_frame(earth)[1]);
  }
  // Nodes need it: joining ones are sent it and are ready only with it.
  EXPECT_EQ(versions.wanted_sets(), (std::vector<Digest>{digest(1), digest(2), digest(3), digest(4), digest(8)}));
  EXPECT_FALSE(versions.ready_with(show_sets));
  std::set<Digest> with_override = show_sets;
  with_override.insert(digest(8));
  EXPECT_TRUE(versions.ready_with(with_override));

  // A later operator version replaces the override; a version of the show's own may be one.
  versions.begin_pending(0, digest(3));
  versions.mark_distributed(TableVersions::Clock::now());
  EXPECT_EQ(versions.apply_pending(41).table_hash, digest(8)) << "the override it replaces";
  EXPECT_EQ(versions.with_overrides(show_frame(1))[0].table_hash, digest(3));
  EXPECT_EQ(versions.with_overrides(show_frame(1))[0].effective_from_frame, 41u);

  versions.clear_override(0);
  EXPECT_FALSE(versions.override_of(0));
  EXPECT_EQ(versions.with_overrides(show_frame(2)), show_frame(2)) << "the show's track again";
  EXPECT_TRUE(versions.ready_with(show_sets));
  EXPECT_TRUE(versions.has_set(digest(8))) << "kept for a later override";
}

TEST(TableVersions, VersionsAndTheirDefinitions) {
  TableVersions versions;
  EXPECT_EQ(versions.definition(digest(4)), nullptr);
  versions.add_version("Earth", atmosphere_with("first"), digest(4));
  versions.add_version("Earth", atmosphere_with("second"), digest(4));  // the first one stays
  EXPECT_EQ(versions.version(digest(4)).body, "Earth");
  EXPECT_EQ(versions.version(digest(4)).table_hash, digest(4));
  EXPECT_EQ(versions.version(digest(4)).parameters.at("name"), "first");
  const auto encoded = versions.definition(digest(4));
  ASSERT_NE(encoded, nullptr);
  EXPECT_EQ(*encoded, encode(AtmosphereDefinition{"Earth", digest(4), atmosphere_with("first").parameters.dump()}));
  EXPECT_THROW(versions.version(digest(5)), std::out_of_range);
}

TEST(TableVersions, SetsByHash) {
  TableVersions versions;
  EXPECT_FALSE(versions.has_set(digest(1)));
  TableSetFile set;
  set.body_name = "Earth";
  set.table_hash = digest(1);
  versions.add_set(set);
  EXPECT_TRUE(versions.has_set(digest(1)));
  EXPECT_EQ(versions.set(digest(1)).body_name, "Earth");
  set.body_name = "Earth again";
  versions.add_set(set);
  EXPECT_EQ(versions.set(digest(1)).body_name, "Earth again");
}

}  // namespace
}  // namespace zenith::cluster
