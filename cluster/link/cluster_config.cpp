#include "cluster/link/cluster_config.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "atmosphere/named_inputs.h"
#include "core/json_reader.h"
#include "core/strings.h"
#include "warp/viewport_config.h"

namespace zenith::cluster {
namespace {

using core::cat;

using nlohmann::json;
namespace fs = std::filesystem;

constexpr std::size_t kMaxNameLength = 64;
constexpr int kMaxNodes = 256;

bool valid_name(const std::string& name) {
  return !name.empty() && name.size() <= kMaxNameLength && name != "." && name != ".." &&
         std::all_of(name.begin(), name.end(), [](char c) {
           return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' ||
                  c == '.';
         });
}

std::string checked_name(JsonReader& r, const std::string& key, const char* what) {
  const std::string name = r.string(key);
  if (!valid_name(name))
    r.fail(key, cat("= \"", name, "\": ", what, " must be 1 to ", kMaxNameLength, " letters, digits, '-', '_' or '.'"));
  return name;
}

/// An object under `key` (required), as a reader.
JsonReader child(JsonReader& r, const std::string& key) {
  const json& v = r.raw(key);
  if (!v.is_object()) r.fail(key, cat("must be an object, got ", v.dump()));
  return JsonReader(v, r.file(), r.key_path(key));
}

void read_timing(JsonReader& t, ClusterConfig& c) {
  c.heartbeat_ms = static_cast<std::uint32_t>(t.integer("heartbeat_ms", 10, 60000));
  c.barrier_timeout_ms = static_cast<std::uint32_t>(t.integer("barrier_timeout_ms", 10, 600000));
  c.frame_rate_hz = t.number("frame_rate_hz", kMinFrameRateHz, kMaxFrameRateHz, "Hz");
  c.lookahead_frames = static_cast<int>(
      std::lround(t.number_or("lookahead_frames", kDefaultLookaheadFrames, 0, kMaxLookaheadFrames, "frames")));
  c.black_when_link_lost = t.string_or("link_lost", "hold", {"hold", "black"}) == "black";
  c.realtime_presents = t.string_or("present_priority", "realtime", {"realtime", "normal"}) == "realtime";
  if (t.has("lookahead_frames") && !t.raw("lookahead_frames").is_number_integer())
    t.fail("lookahead_frames",
           cat("must be an integer in [0, ", kMaxLookaheadFrames, "], got ", t.raw("lookahead_frames").dump()));
  c.reconnect_ms = static_cast<std::uint32_t>(
      std::lround(1000.0 * t.number_or("reconnect_s", kDefaultReconnectMs / 1000.0, 0.0, kMaxReconnectS, "s")));
  t.finish();
}

void read_secret(JsonReader& s, const json& v, const fs::path& base_dir, ClusterConfig& c) {
  if (s.has("file") == s.has("env") || v.size() != 1)
    s.fail("",
           "give exactly one of \"file\" (a file holding the secret, mode 600) or \"env\" (the name of an "
           "environment variable holding it); never the secret itself");
  if (s.has("file")) {
    c.secret_file = s.existing_file("file", base_dir);
  } else {
    c.secret_env = s.string("env");
    const bool ok = !c.secret_env.empty() && c.secret_env.size() <= 128 &&
                    std::all_of(c.secret_env.begin(), c.secret_env.end(),
                                [](char ch) {
                                  return (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') ||
                                         (ch >= '0' && ch <= '9') || ch == '_';
                                }) &&
                    !(c.secret_env[0] >= '0' && c.secret_env[0] <= '9');
    if (!ok)
      s.fail("env", cat("= \"", c.secret_env, "\": must be an environment variable name ([A-Za-z_][A-Za-z0-9_]*)"));
  }
  s.finish();
}

/// {"host": …, "port": …} of the active master or the standby.
MasterAddress read_address(JsonReader& m) {
  MasterAddress address;
  address.host = m.string("host");
  if (address.host.empty() || address.host.size() > 253)
    m.fail("host", cat("= \"", address.host, "\": must be a host name or address"));
  address.port = static_cast<std::uint16_t>(m.integer("port", 1, 65535));
  m.finish();
  return address;
}

ClusterNodeConfig read_node(JsonReader& n) {
  ClusterNodeConfig node;
  node.name = checked_name(n, "name", "a node name");
  node.host = n.string("host");
  if (node.host.empty() || node.host.size() > 253)
    n.fail("host", cat("= \"", node.host, "\": must be a host name or address"));
  const json& outs = n.raw("outputs");
  if (!outs.is_array() || outs.empty())
    n.fail("outputs", cat("= ", outs.dump(), ": must be a non-empty array of output names of the viewport config"));
  for (std::size_t i = 0; i < outs.size(); ++i) {
    if (!outs[i].is_string()) n.fail(cat("outputs/", i), cat("= ", outs[i].dump(), ": must be an output name"));
    node.outputs.push_back(outs[i].get<std::string>());
  }
  n.finish();
  return node;
}

}  // namespace

std::string MasterAddress::text() const { return cat(host, ":", port); }

std::string standby_name(const MasterAddress& standby) {
  return cat("standby@", standby.text()).substr(0, kMaxNameLength);
}

const ClusterNodeConfig* ClusterConfig::find_node(const std::string& node_name) const {
  for (const auto& n : nodes)
    if (n.name == node_name) return &n;
  return nullptr;
}

ClusterConfig parse_cluster_config(const json& config, const std::string& source, const fs::path& base_dir) {
  if (!config.is_object()) throw ConfigError(source, "", "a cluster config must be a JSON object");
  JsonReader r(config, source);
  ClusterConfig c;
  c.source = source;
  if (!r.has("zenith_cluster")) r.fail("zenith_cluster", "missing: a cluster config starts with \"zenith_cluster\": 1");
  r.integer("zenith_cluster", kClusterConfigVersion, kClusterConfigVersion);
  c.name = checked_name(r, "name", "the cluster name");
  if (r.has("description")) r.string("description");

  JsonReader m = child(r, "master");
  const MasterAddress master = read_address(m);
  c.master_host = master.host;
  c.master_port = master.port;
  if (r.has("standby")) {
    JsonReader s = child(r, "standby");
    c.standby = read_address(s);
    if (*c.standby == master)
      r.fail("standby/port", cat("= ", master.port, ": the standby must listen on another address than the master (",
                                 "/master is ", master.text(), ")"));
  }

  c.scene = r.existing_file("scene", base_dir);
  c.viewports = r.existing_file("viewports", base_dir);

  if (r.has("timing")) {
    JsonReader t = child(r, "timing");
    read_timing(t, c);
  } else {
    r.fail("timing", "missing required key: {\"heartbeat_ms\", \"barrier_timeout_ms\", \"frame_rate_hz\"}");
  }
  {
    const json& sv = r.raw("secret");
    if (!sv.is_object()) r.fail("secret", cat("must be an object {\"file\": ...} or {\"env\": ...}, got ", sv.dump()));
    JsonReader s(sv, r.file(), r.key_path("secret"));
    read_secret(s, sv, base_dir, c);
  }
  if (r.has("swap_group")) c.swap_group = static_cast<unsigned>(r.integer("swap_group", 0, kMaxSwapGroup));
  if (r.has("limits")) {
    JsonReader l = child(r, "limits");
    if (l.has("max_unauthenticated_connections"))
      c.max_unauthenticated_connections =
          static_cast<std::uint32_t>(l.integer("max_unauthenticated_connections", 1, 4096));
    l.finish();
  }
  if (r.has("tables")) {
    JsonReader t = child(r, "tables");
    c.table_sizes = t.string_or("sizes", c.table_sizes, atmosphere::table_size_names());
    if (t.has("orders")) c.table_orders = t.integer("orders", 1, 50);
    t.finish();
  }

  const json& nodes = r.raw("nodes");
  if (!nodes.is_array() || nodes.empty() || nodes.size() > static_cast<std::size_t>(kMaxNodes))
    r.fail("nodes", cat("must be an array of 1 to ", kMaxNodes, " nodes"));
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!nodes[i].is_object()) r.fail(cat("nodes/", i), "must be an object {\"name\", \"host\", \"outputs\"}");
    JsonReader n(nodes[i], r.file(), r.key_path(cat("nodes/", i)));
    c.nodes.push_back(read_node(n));
    for (std::size_t k = 0; k < i; ++k)
      if (c.nodes[k].name == c.nodes[i].name)
        r.fail(cat("nodes/", i, "/name"),
               cat("= \"", c.nodes[i].name, "\": duplicate node name (also /nodes/", k, ")"));
  }

  if (r.has("output")) {
    JsonReader o = child(r, "output");
    if (o.has("directory")) {
      const std::string dir = o.string("directory");
      if (dir.empty()) o.fail("directory", "= \"\": must name a folder");
      c.output_directory = dir;
    }
    c.output_format = o.string_or("format", c.output_format, {"png", "exr"});
    o.finish();
  }
  r.finish();

  // Every output a node renders exists in the viewport config, and belongs to one node only.
  const warp::ViewportConfig viewports = warp::load_viewport_config(c.viewports);
  std::map<std::string, std::string> owner;
  for (std::size_t i = 0; i < c.nodes.size(); ++i) {
    for (std::size_t k = 0; k < c.nodes[i].outputs.size(); ++k) {
      const std::string& output = c.nodes[i].outputs[k];
      const std::string key = cat("/nodes/", i, "/outputs/", k);
      if (viewports.find(output) == nullptr) {
        std::string names;
        for (const auto& o : viewports.outputs) names += cat(names.empty() ? "" : ", ", o.name);
        throw ConfigError(
            source, key,
            cat("= \"", output, "\": no such output in ", c.viewports.string(), " (outputs: ", names, ")"));
      }
      if (const auto [it, inserted] = owner.emplace(output, c.nodes[i].name); !inserted)
        throw ConfigError(source, key, cat("= \"", output, "\": already rendered by node \"", it->second, "\""));
    }
  }
  return c;
}

ClusterConfig load_cluster_config(const fs::path& path) {
  return parse_cluster_config(read_json_file(path), path.string(), path.parent_path());
}

}  // namespace zenith::cluster
