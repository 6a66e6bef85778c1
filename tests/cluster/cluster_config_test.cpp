// The cluster configuration: the shipped local-dome config, strict keys and
// messages with the file, the JSON pointer and the range.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cluster/link/cluster_config.h"
#include "core/json_reader.h"
#include "warp/viewport_config.h"

namespace zenith::cluster {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = ZENITH_SOURCE_DIR;

nlohmann::json valid() {
  return nlohmann::json::parse(R"({
    "zenith_cluster": 1, "name": "t",
    "master": {"host": "127.0.0.1", "port": 47000},
    "scene": "scenes/earth-sunset.json", "viewports": "viewports/dome-quadrants.json",
    "timing": {"heartbeat_ms": 100, "barrier_timeout_ms": 2000, "frame_rate_hz": 10},
    "secret": {"env": "ZENITH_CLUSTER_SECRET"},
    "nodes": [{"name": "a", "host": "127.0.0.1", "outputs": ["top-left", "top-right"]},
              {"name": "b", "host": "127.0.0.1", "outputs": ["bottom-left"]}]
  })");
}

ClusterConfig parse(const nlohmann::json& j) { return parse_cluster_config(j, "t.json", kSource / "configs"); }

std::string error_of(const nlohmann::json& j) {
  try {
    parse(j);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ClusterConfig, LocalDomeLoads) {
  const ClusterConfig c = load_cluster_config(kSource / "configs/clusters/local-dome.json");
  EXPECT_EQ(c.name, "local-dome");
  EXPECT_EQ(c.nodes.size(), 4u);
  EXPECT_EQ(c.master_host, "127.0.0.1");
  EXPECT_FALSE(c.secret_file.has_value());
  EXPECT_EQ(c.secret_env, "ZENITH_CLUSTER_SECRET");
  EXPECT_EQ(c.output_format, "png");
  EXPECT_TRUE(fs::exists(c.scene));
}

TEST(ClusterConfig, ValidParsesWithDefaults) {
  const ClusterConfig c = parse(valid());
  EXPECT_EQ(c.master_port, 47000);
  EXPECT_EQ(c.heartbeat_ms, 100u);
  EXPECT_EQ(c.barrier_timeout_ms, 2000u);
  EXPECT_EQ(c.table_sizes, "paper");
  EXPECT_EQ(c.output_directory, fs::path("out/cluster"));
  ASSERT_NE(c.find_node("a"), nullptr);
  EXPECT_EQ(c.find_node("a")->outputs.size(), 2u);
  EXPECT_EQ(c.find_node("zz"), nullptr);
}

TEST(ClusterConfig, ErrorsNameFilePointerAndRange) {
  auto j = valid();
  j["timing"]["barrier_timeout_ms"] = 5;
  EXPECT_NE(error_of(j).find("t.json: /timing/barrier_timeout_ms = 5"), std::string::npos) << error_of(j);
  j = valid();
  j["master"]["port"] = 70000;
  EXPECT_NE(error_of(j).find("/master/port"), std::string::npos) << error_of(j);
  j = valid();
  j["nodes"][1]["outputs"][0] = "nowhere";
  EXPECT_NE(error_of(j).find("/nodes/1/outputs/0 = \"nowhere\": no such output"), std::string::npos) << error_of(j);
  j = valid();
  j["nodes"][1]["outputs"][0] = "top-left";
  EXPECT_NE(error_of(j).find("already rendered by node \"a\""), std::string::npos) << error_of(j);
  j = valid();
  j["nodes"][1]["name"] = "a";
  EXPECT_NE(error_of(j).find("duplicate node name"), std::string::npos) << error_of(j);
}

TEST(ClusterConfig, ReconnectTimeIsOptionalInSecondsAndChecked) {
  EXPECT_EQ(parse(valid()).reconnect_ms, kDefaultReconnectMs) << "5 minutes unless said";
  auto j = valid();
  j["timing"]["reconnect_s"] = 2.5;
  EXPECT_EQ(parse(j).reconnect_ms, 2500u);
  j["timing"]["reconnect_s"] = 0;
  EXPECT_EQ(parse(j).reconnect_ms, 0u) << "0: no reconnection";
  j["timing"]["reconnect_s"] = 90000;
  EXPECT_NE(error_of(j).find("t.json: /timing/reconnect_s = 90000"), std::string::npos) << error_of(j);
  EXPECT_NE(error_of(j).find("86400"), std::string::npos) << error_of(j);
  j["timing"]["reconnect_s"] = -1;
  EXPECT_NE(error_of(j).find("/timing/reconnect_s"), std::string::npos) << error_of(j);
}

TEST(ClusterConfig, ThePresentPriorityIsRealtimeUnlessSaidAndChecked) {
  EXPECT_TRUE(parse(valid()).realtime_presents) << "docs/cluster.md, \"Presenting on time\"";
  auto j = valid();
  j["timing"]["present_priority"] = "normal";
  EXPECT_FALSE(parse(j).realtime_presents);
  j["timing"]["present_priority"] = "realtime";
  EXPECT_TRUE(parse(j).realtime_presents);
  j["timing"]["present_priority"] = "high";
  const std::string error = error_of(j);
  EXPECT_NE(error.find("t.json: /timing/present_priority"), std::string::npos) << error;
  EXPECT_NE(error.find("realtime"), std::string::npos) << error;
  EXPECT_NE(error.find("normal"), std::string::npos) << error;
}

TEST(ClusterConfig, TheCapOfUnauthenticatedConnectionsIsOptionalAndChecked) {
  EXPECT_EQ(parse(valid()).max_unauthenticated_connections, 16u) << "docs/cluster.md, \"Threat model\"";
  nlohmann::json j = valid();
  j["limits"]["max_unauthenticated_connections"] = 4;
  EXPECT_EQ(parse(j).max_unauthenticated_connections, 4u);
  j["limits"]["max_unauthenticated_connections"] = 0;
  EXPECT_NE(error_of(j).find("/limits/max_unauthenticated_connections = 0: must be in [1, 4096]"), std::string::npos)
      << error_of(j);
  j["limits"] = {{"max_connections", 3}};
  EXPECT_NE(error_of(j).find("/limits/max_connections"), std::string::npos) << error_of(j);
}

TEST(ClusterConfig, StandbyIsOptionalAndChecked) {
  EXPECT_FALSE(parse(valid()).standby.has_value()) << "no standby unless configured";
  auto j = valid();
  j["standby"] = {{"host", "10.0.0.2"}, {"port", 47001}};
  const ClusterConfig c = parse(j);
  ASSERT_TRUE(c.standby.has_value());
  EXPECT_EQ(c.standby->text(), "10.0.0.2:47001");
  EXPECT_EQ(c.master_address().text(), "127.0.0.1:47000");
  j["standby"]["port"] = 0;
  EXPECT_NE(error_of(j).find("t.json: /standby/port = 0: must be in [1, 65535]"), std::string::npos) << error_of(j);
  j["standby"] = {{"host", ""}, {"port", 47001}};
  EXPECT_NE(error_of(j).find("t.json: /standby/host = \"\": must be a host name or address"), std::string::npos)
      << error_of(j);
  j["standby"] = {{"host", "127.0.0.1"}, {"port", 47000}};
  EXPECT_NE(
      error_of(j).find("t.json: /standby/port = 47000: the standby must listen on another address than the master"),
      std::string::npos)
      << error_of(j);
  j["standby"] = {{"host", "127.0.0.1"}, {"port", 47001}, {"weight", 2}};
  EXPECT_NE(error_of(j).find("/standby/weight"), std::string::npos) << error_of(j);
  j["standby"] = "127.0.0.1:47001";
  EXPECT_NE(error_of(j).find("/standby"), std::string::npos) << error_of(j);
}

TEST(ClusterConfig, UnknownKeysAndInlineSecretsAreRefused) {
  auto j = valid();
  j["timing"]["heartbeat"] = 5;
  EXPECT_NE(error_of(j).find("/timing/heartbeat"), std::string::npos) << error_of(j);
  j = valid();
  j["secret"] = {{"value", "hunter2hunter2hunter2"}};
  EXPECT_NE(error_of(j).find("/secret"), std::string::npos) << error_of(j);
  j = valid();
  j["secret"] = {{"env", "A"}, {"file", "x"}};
  EXPECT_NE(error_of(j).find("exactly one"), std::string::npos) << error_of(j);
  j = valid();
  j["zenith_cluster"] = 2;
  EXPECT_NE(error_of(j).find("/zenith_cluster"), std::string::npos) << error_of(j);
  j = valid();
  j["output"] = {{"format", "jpg"}};
  EXPECT_NE(error_of(j).find("/output/format"), std::string::npos) << error_of(j);
}

TEST(ClusterConfig, TheSixProjectorDomeOnThreePcsLoadsWithAWindowPerProjector) {
  // The worked example of docs/cluster.md, "Setting up a node".
  const ClusterConfig c = load_cluster_config(kSource / "configs/clusters/dome-6-projectors-3-pcs.json");
  const warp::ViewportConfig v = warp::load_viewport_config(c.viewports);
  ASSERT_EQ(c.nodes.size(), 3u);
  ASSERT_EQ(v.outputs.size(), 6u);
  std::size_t outputs = 0;
  for (const auto& node : c.nodes) {
    EXPECT_EQ(node.outputs.size(), 2u) << node.name;
    for (const std::string& name : node.outputs) {
      const warp::OutputConfig* o = v.find(name);
      ASSERT_NE(o, nullptr) << name;
      ASSERT_TRUE(o->window.has_value()) << name;
      EXPECT_TRUE(o->window->fullscreen) << name;
      ++outputs;
    }
  }
  EXPECT_EQ(outputs, 6u);
  // render-1: two connectors by name; render-2: one Mosaic window, each output in its half.
  EXPECT_EQ(v.find("p1")->window->monitor_name, "DP-0");
  EXPECT_EQ(v.find("p2")->window->monitor_name, "DP-2");
  const warp::OutputWindow& p3 = *v.find("p3")->window;
  const warp::OutputWindow& p4 = *v.find("p4")->window;
  EXPECT_EQ(p3.name, "mosaic");
  EXPECT_EQ(p4.name, "mosaic");
  EXPECT_EQ(p3.rect, (std::array<int, 4>{0, 0, 1920, 1200}));
  EXPECT_EQ(p4.rect, (std::array<int, 4>{1920, 0, 1920, 1200}));
  EXPECT_EQ(v.find("p6-zenith")->window->gamma, 2.4);
  EXPECT_EQ(c.frame_rate_hz, 60.0);
}

}  // namespace
}  // namespace zenith::cluster
