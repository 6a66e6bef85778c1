// The master's table schedule without sockets, threads or a clock
// (cluster/master/table_schedule.h; docs/cluster.md, "Table versions";
// docs/operator.md, "Live atmosphere parameters"): node sessions without
// connections, a fake preparer, a hand-set clock.
#include "cluster/master/table_schedule.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "atmosphere/model_hash.h"
#include "scene/scene_loader.h"
#include "test_support.h"

namespace zenith::cluster {
namespace {

namespace oc = operator_command;
using json = nlohmann::json;

const std::filesystem::path kSource = ZENITH_SOURCE_DIR;

/// A set of `bytes` bytes for `hash` (the wire encoding of make_table_set, no cache file).
TableSetFile set_for(const std::string& body, const Digest& hash, std::size_t bytes = 3000) {
  return make_table_set(body, hash, std::make_shared<const std::vector<std::uint8_t>>(bytes, std::uint8_t{7}), 1024);
}

class TableScheduleTest : public ::testing::Test {
 protected:
  TableScheduleTest() : scene_(scene::load_scene(kSource / "configs/scenes/earth-sunset.json")) {}

  /// The default show with `switches`, its scene's set prepared.
  void start(std::vector<AtmosphereSwitch> switches = {}) {
    TableSchedule::Options options;
    options.barrier_timeout_ms = 1000;
    options.switches = std::move(switches);
    schedule_.emplace(options, scene_, nullptr, sessions_, barrier_, actions());
    schedule_->check_switches();
    schedule_->prepare_initial([](const TablePreparer::Job& job) { return set_for(job.body, job.table_hash); });
  }

  TableSchedule::Actions actions() {
    TableSchedule::Actions a;
    a.send = [this](NodeSession& s, const TableSchedule::Bytes& bytes) { sent_[s.id].push_back(bytes); };
    a.close = [this](NodeSession& s, const std::string& reason) { closed_[s.id] = reason; };
    a.prepare = [this](TablePreparer::Job job) { jobs_.push_back(std::move(job)); };
    a.defer = [this](std::function<void()> f) { deferred_.push_back(std::move(f)); };
    a.node_ready = [this](NodeSession& s) {
      s.state = NodeSession::State::ready;  // as the master's become_ready
      joined_.push_back(s.name);
    };
    a.show_set_ready = [] {};
    a.started = [] { return true; };
    a.show_failed = [this](const std::string& reason, std::exception_ptr) { failure_ = reason; };
    a.now = [this] { return now_; };
    return a;
  }

  /// A node past its handshake with an empty inventory (cache): it is sent every set it needs.
  NodeSession& join(const std::string& name) {
    NodeSession& s =
        sessions_.add(nullptr, MasterHandshake(SharedSecret(std::vector<std::uint8_t>(32, 1), "test"), "c"));
    s.name = name;
    s.state = NodeSession::State::tables;
    schedule_->finish_inventory(s);
    return s;
  }

  /// The preparer finishes its oldest job.
  void prepare_next() {
    ASSERT_FALSE(jobs_.empty());
    const TablePreparer::Job job = jobs_.front();
    jobs_.erase(jobs_.begin());
    schedule_->on_set_prepared(set_for(job.body, job.table_hash), 1.0, false);
  }

  Digest scene_version() const {
    return digest_from_hex(atmosphere::lookup_table_hash(scene_.bodies[0].atmosphere->loaded.model));
  }
  static oc::Set turbidity(double value) {
    return oc::Set{"Earth", json::json_pointer("/aerosol/scattering/turbidity"), value};
  }

  scene::Scene scene_;
  NodeSessions sessions_;
  FrameBarrier barrier_;
  std::optional<TableSchedule> schedule_;
  TableSchedule::Clock::time_point now_{};
  std::map<std::uint32_t, std::vector<TableSchedule::Bytes>> sent_;
  std::map<std::uint32_t, std::string> closed_;
  std::vector<TablePreparer::Job> jobs_;
  std::vector<std::function<void()>> deferred_;
  std::vector<std::string> joined_;
  std::string failure_;
};

TEST_F(TableScheduleTest, ANodeIsSentTheScenesSetAndJoinsOnceItConfirmsIt) {
  start();
  ASSERT_EQ(schedule_->tables().current().size(), 1u);
  EXPECT_EQ(schedule_->tables().current()[0].table_hash, scene_version());
  EXPECT_EQ(schedule_->effective_version(0), scene_version());

  NodeSession& a = join("a");
  // The definition, the announce and three chunks of 1024 bytes (3000 bytes).
  EXPECT_EQ(sent_[a.id].size(), 5u);
  EXPECT_EQ(a.chunks_sent, 3u);
  EXPECT_TRUE(joined_.empty()) << "not before its TableReady";
  EXPECT_FALSE(schedule_->on_table_ready(a, test::digest(9))) << "a set never sent is a protocol violation";
  EXPECT_TRUE(schedule_->on_table_ready(a, scene_version()));
  EXPECT_EQ(joined_, std::vector<std::string>{"a"});
}

TEST_F(TableScheduleTest, ASetInTheNodesCacheIsOnlyAnnounced) {
  start();
  NodeSession& s = sessions_.add(nullptr, MasterHandshake(SharedSecret(std::vector<std::uint8_t>(32, 1), "test"), "c"));
  s.name = "b";
  s.state = NodeSession::State::tables;
  s.cached.insert(scene_version());
  schedule_->finish_inventory(s);
  EXPECT_EQ(sent_[s.id].size(), 2u) << "the definition and the TableAnnounce";
  EXPECT_EQ(s.chunks_sent, 0u);
}

TEST_F(TableScheduleTest, AnOperatorsChangeTakesEffectAtOneFrameOnceEveryReadyNodeHoldsIt) {
  start();
  NodeSession& a = join("a");
  NodeSession& b = join("b");
  schedule_->on_table_ready(a, scene_version());
  schedule_->on_table_ready(b, scene_version());
  barrier_.begin(4, {a.id, b.id});  // frame 4 in flight: the next boundary is frame 5

  const std::string reply = schedule_->set_atmosphere(turbidity(3.0));
  ASSERT_TRUE(schedule_->tables().pending());
  const Digest version = schedule_->tables().pending()->hash;
  EXPECT_NE(version, scene_version());
  EXPECT_EQ(reply, "'Earth' /aerosol/scattering/turbidity = 3.0: table version " + short_hex(version) +
                       " is being prepared; every node switches to it at one frame once all hold it");
  ASSERT_EQ(jobs_.size(), 1u);
  EXPECT_EQ(jobs_[0].table_hash, version);
  EXPECT_EQ(schedule_->pending_change(), "/aerosol/scattering/turbidity = 3.0");

  const std::size_t sent_to_a = sent_[a.id].size();
  prepare_next();
  EXPECT_TRUE(schedule_->tables().pending()->distributed);
  EXPECT_EQ(sent_[a.id].size(), sent_to_a + 5) << "sent to every node once prepared";
  schedule_->on_table_ready(a, version);
  EXPECT_TRUE(schedule_->tables().pending()) << "b has not confirmed it yet";
  EXPECT_EQ(schedule_->effective_version(0), scene_version());
  schedule_->on_table_ready(b, version);
  EXPECT_FALSE(schedule_->tables().pending());
  EXPECT_EQ(schedule_->effective_version(0), version);
  EXPECT_EQ(schedule_->tables().current()[0].effective_from_frame, 5u);
}

TEST_F(TableScheduleTest, ANodeThatDoesNotConfirmWithinAMinuteIsDisconnected) {
  start();
  NodeSession& a = join("a");
  NodeSession& b = join("b");
  schedule_->on_table_ready(a, scene_version());
  schedule_->on_table_ready(b, scene_version());
  schedule_->set_atmosphere(turbidity(3.0));
  prepare_next();
  const Digest version = schedule_->tables().pending()->hash;
  schedule_->on_table_ready(a, version);

  // The limit is max(60 s, the barrier timeout of 1 s).
  now_ += std::chrono::seconds(60);
  schedule_->check_confirmations();
  EXPECT_TRUE(closed_.empty()) << "60 s is not past the limit";
  now_ += std::chrono::milliseconds(1);
  schedule_->check_confirmations();
  ASSERT_EQ(closed_.size(), 1u);
  EXPECT_EQ(closed_.at(b.id), "table version not confirmed in time");
  // Its connection closes: the switch goes ahead on the others.
  sessions_.take(b.id);
  schedule_->on_node_left();
  EXPECT_FALSE(schedule_->tables().pending());
  EXPECT_EQ(schedule_->effective_version(0), version);
}

TEST_F(TableScheduleTest, ASwitchStartsWhenItsFrameComesAndTheSameVersionAgainIsNoSwitch) {
  start({AtmosphereSwitch{3, "Earth", "earth-standard"}, AtmosphereSwitch{1, "Earth", "earth-advanced"}});
  schedule_->maybe_start_switch();
  EXPECT_FALSE(schedule_->tables().pending()) << "frame 0: no switch is due";
  barrier_.start_at(1);
  schedule_->maybe_start_switch();
  EXPECT_FALSE(schedule_->tables().pending()) << "frame 1's switch is the scene's own atmosphere: nothing to switch";
  EXPECT_TRUE(jobs_.empty());
  barrier_.start_at(3);
  schedule_->maybe_start_switch();
  ASSERT_TRUE(schedule_->tables().pending());
  EXPECT_EQ(schedule_->pending_change(), "earth-standard");
  ASSERT_EQ(jobs_.size(), 1u);
  EXPECT_EQ(jobs_[0].body, "Earth");
  EXPECT_NE(jobs_[0].table_hash, scene_version());
}

TEST_F(TableScheduleTest, ASwitchToABodyWithoutAtmosphereIsRefusedBeforeAnyPrecompute) {
  TableSchedule::Options options;
  options.switches = {AtmosphereSwitch{2, "Moon", "earth-standard"}};
  TableSchedule schedule(options, scene_, nullptr, sessions_, barrier_, actions());
  try {
    schedule.check_switches();
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    // The scene's path as a std::filesystem::path prints it: in quotes.
    EXPECT_EQ(std::string(e.what()), "atmosphere switch at frame 2: the scene \"" + scene_.source.string() +
                                         "\" has no body 'Moon' with an atmosphere");
  }
}

TEST_F(TableScheduleTest, AFailedVersionIsAbandonedAndTheShowGoesOnWithTheCurrentOne) {
  start();
  schedule_->set_atmosphere(turbidity(3.0));
  const Digest version = schedule_->tables().pending()->hash;
  schedule_->on_set_failed(version, std::make_exception_ptr(std::runtime_error("disk full")));
  EXPECT_FALSE(schedule_->tables().pending());
  EXPECT_EQ(schedule_->last_error(),
            "table version " + short_hex(version) + " (/aerosol/scattering/turbidity = 3.0): disk full");
  EXPECT_EQ(schedule_->effective_version(0), scene_version());
  EXPECT_TRUE(failure_.empty()) << "the default show goes on";
}

TEST_F(TableScheduleTest, ClearingGivesTheScenesOwnAtmosphereBackAsANewVersion) {
  start();
  NodeSession& a = join("a");
  schedule_->on_table_ready(a, scene_version());
  EXPECT_EQ(schedule_->clear_atmosphere("Earth"),
            "'Earth' has the scene's own atmosphere (table version " + short_hex(scene_version()) + ")");
  schedule_->set_atmosphere(turbidity(3.0));
  prepare_next();
  schedule_->on_table_ready(a, schedule_->tables().pending()->hash);
  ASSERT_FALSE(schedule_->tables().pending());
  EXPECT_EQ(schedule_->clear_atmosphere("Earth"), "'Earth': the scene's own atmosphere, table version " +
                                                      short_hex(scene_version()) +
                                                      "; every node switches to it at one frame once all hold it");
  // The scene's set is held already: no precompute, it goes out on the next turn of the loop.
  EXPECT_TRUE(jobs_.empty());
  ASSERT_EQ(deferred_.size(), 1u);
  deferred_[0]();
  EXPECT_FALSE(schedule_->tables().pending()) << "a holds it: it takes effect at once";
  EXPECT_EQ(schedule_->effective_version(0), scene_version());
}

TEST_F(TableScheduleTest, AFrameWaitsUntilEveryParticipantHoldsItsSets) {
  start();
  NodeSession& a = join("a");
  FrameState frame;
  frame.frame = 0;
  frame.atmospheres = schedule_->tables().current();
  EXPECT_FALSE(schedule_->participants_hold(frame, {a.id}, false));
  schedule_->on_table_ready(a, scene_version());
  EXPECT_TRUE(schedule_->participants_hold(frame, {a.id}, false));
  frame.atmospheres[0].table_hash = test::digest(42);
  EXPECT_FALSE(schedule_->participants_hold(frame, {a.id}, false)) << "a set not prepared yet";
}

}  // namespace
}  // namespace zenith::cluster
