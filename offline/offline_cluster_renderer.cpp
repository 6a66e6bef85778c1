#include "offline/offline_cluster_renderer.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <stdexcept>

#include "atmosphere/lut/table_cache.h"
#include "cluster/launcher/child_process.h"
#include "cluster/launcher/launcher_signals.h"
#include "cluster/master/master.h"
#include "cluster/protocol/handshake.h"
#include "show/show.h"

namespace zenith::app::offline {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

ClusterFrameRenderer::ClusterFrameRenderer(ClusterRenderSettings settings)
    : settings_(std::move(settings)),
      config_(cluster::load_cluster_config(settings_.cluster_file)),
      feed_(std::make_shared<cluster::FrameFeed>()) {
  ensure_local_secret(config_);
  const show::Show show = show::load_show(settings_.show_file);  // its scene, for the nodes

  cluster::MasterOptions options;
  options.config = config_;
  options.show = settings_.show_file;
  options.show_fps = settings_.fps;
  options.paced = false;
  options.feed = feed_;
  options.cache_directory = settings_.cache_directory;
  options.cpu_precompute = settings_.cpu_precompute;
  options.wait_for_nodes_ms = 600000;  // every configured node: a frame must hold all outputs
  cluster::SharedSecret secret = cluster::load_shared_secret(config_.secret_file, config_.secret_env.c_str());
  master_ = std::thread([this, options = std::move(options), secret = std::move(secret)]() mutable {
    try {
      cluster::Master master(std::move(options), std::move(secret));
      master.run();
    } catch (const std::exception& e) {
      spdlog::error("master: {}", e.what());
    }
  });

  mark_children_as_launched();  // the nodes die with this process (kill -9 included): no orphan holds a name
  for (const cluster::ClusterNodeConfig& node : config_.nodes) {
    if (!is_local_host(node.host)) {
      stop();
      throw std::invalid_argument(fmt::format(
          "--cluster {}: node '{}' runs on {}: offline rendering starts every node itself, so all must be on this "
          "machine",
          settings_.cluster_file.string(), node.name, node.host));
    }
    std::vector<std::string> args = {"--log-level",
                                     log_level_argument(),
                                     "node",
                                     "--cluster",
                                     settings_.cluster_file.string(),
                                     "--name",
                                     node.name,
                                     "--out",
                                     settings_.out_dir.string(),
                                     "--layout",
                                     "offline",
                                     "--scene",
                                     show.scene_path().string(),
                                     "--connect-timeout-ms",
                                     "900000"};
    if (settings_.cache_directory)
      args.insert(args.end(), {"--cache", (*settings_.cache_directory / "nodes" / node.name).string()});
    nodes_.emplace_back(spawn_self(args), node.name);
    spdlog::info("cluster: node '{}' started (pid {})", node.name, nodes_.back().first);
  }
}

ClusterFrameRenderer::~ClusterFrameRenderer() { stop(); }

void ClusterFrameRenderer::stop() {
  if (stopped_) return;
  stopped_ = true;
  feed_->finish();  // the master stops within a heartbeat, even while it still waits for nodes
  if (master_.joinable()) master_.join();
  for (const auto& [pid, name] : nodes_) {
    const int status = stop_child(pid, fmt::format("node '{}'", name), 10s);
    if (status != 0) spdlog::warn("cluster: node '{}' exited with status {}", name, status);
  }
}

void ClusterFrameRenderer::render_frame(const scene::FrameDescription& state,
                                        const std::vector<std::vector<fs::path>>& files) {
  feed_->push(state);
  // Table preparation and the nodes' start come before the first frame: be patient, but not forever,
  // and not at all once a node has exited (the master would wait for it).
  const auto limit = std::chrono::milliseconds(config_.barrier_timeout_ms) + 900s;
  const auto give_up = std::chrono::steady_clock::now() + limit;
  bool presented = false;
  while (!presented && !feed_->stopped() && std::chrono::steady_clock::now() < give_up) {
    presented = feed_->wait_presented(state.frame, 500ms);
    for (const auto& [pid, name] : nodes_)
      if (const std::optional<int> status = wait_for(pid, 0ms))
        throw std::runtime_error(
            fmt::format("node '{}' exited with status {} before frame {} was presented (see "
                        "its log lines above)",
                        name, *status, state.frame));
  }
  if (!presented)
    throw std::runtime_error(feed_->stopped()
                                 ? fmt::format("the cluster stopped before presenting frame {} (see the "
                                               "master's and nodes' log lines above)",
                                               state.frame)
                                 : fmt::format("frame {} was not presented within {} s", state.frame,
                                               std::chrono::duration_cast<std::chrono::seconds>(limit).count()));
  // Presented: each node renames its files on the Present it received; wait until they are all there.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(config_.barrier_timeout_ms);
  for (const auto& per_output : files)
    for (const fs::path& file : per_output)
      while (!fs::exists(file)) {
        if (std::chrono::steady_clock::now() > deadline)
          throw std::runtime_error(
              fmt::format("frame {}: {} did not appear after the present (did its node miss "
                          "the barrier?)",
                          state.frame, file.string()));
        std::this_thread::sleep_for(2ms);
      }
}

}  // namespace zenith::app::offline
