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
