// What a standby master keeps while it follows the active master, without
// sockets (cluster/standby/standby_follower.h; docs/cluster.md, "Standby
// master"): table sets reassembled and verified with their definitions, the
// last frames and the show-time step, and what it hands over at a takeover.
#include "cluster/standby/standby_follower.h"

#include <gtest/gtest.h>

#include <memory>
#include <numeric>
#include <stdexcept>

#include "test_support.h"

namespace zenith::cluster {
namespace {

using test::digest;

/// A table set of `bytes` bytes for Earth, as the master encodes it (chunks of 1000 bytes).
TableSetFile set_of(std::uint8_t first, std::size_t bytes) {
  auto content = std::make_shared<std::vector<std::uint8_t>>(bytes);
  std::iota(content->begin(), content->end(), first);
  return make_table_set("Earth", digest(first), content, 1000);
}

AtmosphereDefinition definition_of(std::uint8_t first) {
  return AtmosphereDefinition{"Earth", digest(first), R"({"zenith_atmosphere": 1})"};
}

/// Feeds the follower a set's definition, then its announce and chunks as the master sends them.
void send_set(StandbyFollower& follower, std::uint8_t first, std::size_t bytes) {
  follower.on_message(definition_of(first));
  const TableSetFile set = set_of(first, bytes);
  for (const auto& frame : set.frames) {
    const FrameHeader header = parse_header(std::span<const std::uint8_t, kHeaderBytes>(frame->data(), kHeaderBytes));
    follower.on_message(decode_payload(static_cast<std::uint16_t>(header.type),
                                       std::span<const std::uint8_t>(*frame).subspan(kHeaderBytes)));
  }
}

FrameState frame(std::uint64_t number, double show_time_s, std::uint8_t tables = 1) {
  FrameState f;
  f.frame = number;
  f.show_time_s = show_time_s;
  f.atmospheres.push_back({"Earth", digest(tables), 0});
  return f;
}

TEST(StandbyFollower, KeepsEverySetWithItsDefinitionReadyToSend) {
  StandbyFollower follower;
  follower.on_welcome();
  send_set(follower, 1, 2500);
  ASSERT_EQ(follower.versions().size(), 1u);
  const TakeoverState::Version& v = follower.versions()[0];
  EXPECT_EQ(v.definition, definition_of(1));
  EXPECT_EQ(*v.set.bytes, *set_of(1, 2500).bytes);
  EXPECT_EQ(v.set.content_sha256, set_of(1, 2500).content_sha256);
  EXPECT_EQ(v.set.frames.size(), 1u + 1u) << "an announce and its chunks, encoded for the nodes at kTableChunkBytes";
  EXPECT_EQ(v.set.body_name, "Earth");

  send_set(follower, 1, 2500);  // sent again after a new Welcome: still one version
  send_set(follower, 2, 10);
  ASSERT_EQ(follower.versions().size(), 2u);
  EXPECT_EQ(follower.versions()[1].definition.table_hash, digest(2));
}

TEST(StandbyFollower, RefusesASetWithoutDefinitionACorruptSetAndMessagesNotMeantForIt) {
  StandbyFollower follower;
  const TableSetFile set = set_of(3, 100);
  const auto announce =
      std::get<TableAnnounce>(decode_payload(static_cast<std::uint16_t>(MessageType::table_announce),
                                             std::span<const std::uint8_t>(*set.frames[0]).subspan(kHeaderBytes)));
  EXPECT_THROW(follower.on_message(announce), std::runtime_error) << "a set it could not describe to nodes";

  follower.on_message(definition_of(3));
  follower.on_message(announce);
  TableChunk chunk{digest(3), 0, std::vector<std::uint8_t>(100, 0)};  // not the announced content
  EXPECT_THROW(follower.on_message(chunk), std::runtime_error) << "SHA-256 mismatch";
  EXPECT_TRUE(follower.versions().empty());

  for (const Message& m : std::vector<Message>{Welcome{}, RenderDone{}, TableReady{}, Hello{}}) {
    try {
      follower.on_message(m);
      ADD_FAILURE() << to_string(message_type(m)) << " accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), std::string(to_string(message_type(m))) + " is not sent to a standby master");
    }
  }
}

TEST(StandbyFollower, TheShowContinuesFromTheFrameAfterTheLastItSawAtItsSteadyStep) {
  StandbyFollower follower;
  EXPECT_FALSE(follower.takeover_problem().has_value()) << "no show yet: a fresh start";
  EXPECT_EQ(follower.takeover_state().next_frame(), 0u);

  send_set(follower, 1, 50);
  follower.on_message(frame(9, 0.9));
  follower.on_message(frame(10, 1.0));
  EXPECT_FALSE(follower.takeover_state().show_time_step_s.has_value()) << "one step is no playback rate yet";
  follower.on_message(Present{10});
  follower.on_message(frame(11, 1.1));
  TakeoverState state = follower.takeover_state();
  ASSERT_TRUE(state.last_frame.has_value());
  EXPECT_EQ(state.last_frame->frame, 11u);
  EXPECT_EQ(state.next_frame(), 12u) << "the frame in flight is not sent again";
  ASSERT_TRUE(state.show_time_step_s.has_value());
  EXPECT_NEAR(*state.show_time_step_s, 0.1, 1e-12);
  EXPECT_EQ(state.last_presented, std::optional<std::uint64_t>(10));
  EXPECT_TRUE(state.frame_in_flight()) << "frame 11 was sent, not seen presented";
  EXPECT_EQ(state.versions.size(), 1u);
  EXPECT_EQ(follower.frames_seen(), 3u);

  follower.on_message(Present{11});
  EXPECT_FALSE(follower.takeover_state().frame_in_flight());
  follower.on_message(frame(12, 0.0));  // a loop's wrap (or a seek): a one-off step
  ASSERT_TRUE(follower.takeover_state().show_time_step_s.has_value());
  EXPECT_NEAR(*follower.takeover_state().show_time_step_s, 0.1, 1e-12) << "the playback's step, not the wrap's";
  follower.on_message(frame(13, 0.1));
  follower.on_message(frame(14, 0.1));  // paused: the show time holds
  follower.on_message(frame(15, 0.1));
  EXPECT_EQ(follower.takeover_state().show_time_step_s, std::optional<double>(0.0));
}

TEST(StandbyFollower, CannotContinueAFrameWhoseTablesItDoesNotHold) {
  StandbyFollower follower;
  send_set(follower, 1, 50);
  follower.on_message(frame(5, 0.5, 9));
  ASSERT_TRUE(follower.takeover_problem().has_value());
  EXPECT_NE(follower.takeover_problem()->find("frame 5 uses table set"), std::string::npos)
      << *follower.takeover_problem();
  EXPECT_THROW((void)follower.takeover_state(), std::logic_error);
}

TEST(StandbyFollower, ANewWelcomeDropsTransfersInProgressButKeepsWhatItHolds) {
  StandbyFollower follower;
  send_set(follower, 1, 50);
  follower.on_message(frame(3, 0.3));
  follower.on_message(definition_of(2));
  const TableSetFile set = set_of(2, 3000);
  follower.on_message(decode_payload(static_cast<std::uint16_t>(MessageType::table_announce),
                                     std::span<const std::uint8_t>(*set.frames[0]).subspan(kHeaderBytes)));
  follower.on_welcome();  // the connection was lost mid-transfer, and welcomed again
  const Message chunk = decode_payload(static_cast<std::uint16_t>(MessageType::table_chunk),
                                       std::span<const std::uint8_t>(*set.frames[1]).subspan(kHeaderBytes));
  EXPECT_THROW(follower.on_message(chunk), std::runtime_error) << "its announce belonged to the lost connection";
  EXPECT_EQ(follower.versions().size(), 1u);
  EXPECT_EQ(follower.last_frame()->frame, 3u);
}

}  // namespace
}  // namespace zenith::cluster
