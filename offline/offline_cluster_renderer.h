#pragma once
// The FrameRenderer of `zenith show render --cluster` (docs/shows.md,
// "Offline rendering"): a master in this process, fed frame by frame
// (cluster/master/frame_feed.h), and the configuration's local nodes as child
// processes writing their outputs straight into the render folder
// (`zenith node --layout offline`). Each frame returns once every node has
// presented it and its files are in place, so the frame loop hashes finished
// files only.
#include <sys/types.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cluster/link/cluster_config.h"
#include "cluster/master/frame_feed.h"
#include "offline/offline_render.h"

namespace zenith::app::offline {

struct ClusterRenderSettings {
  std::filesystem::path cluster_file;  ///< the configuration (its nodes on this machine are started)
  std::filesystem::path show_file;     ///< the show (the master prepares its table sets; nodes render its scene)
  double fps = 30.0;
  std::filesystem::path out_dir;                         ///< the render folder
  std::optional<std::filesystem::path> cache_directory;  ///< master's table cache; nodes use CACHE/nodes/<node>
  bool cpu_precompute = false;
};

class ClusterFrameRenderer final : public FrameRenderer {
 public:
  /// Starts the master (its thread prepares the tables and waits for the
  /// nodes) and the local nodes. Throws for configuration errors.
  explicit ClusterFrameRenderer(ClusterRenderSettings settings);
  /// Ends the feed, waits for the master's Goodbye and the nodes' exit
  /// (stopping any that linger).
  ~ClusterFrameRenderer() override;

  void render_frame(const scene::FrameDescription& state,
                    const std::vector<std::vector<std::filesystem::path>>& files) override;

 private:
  void stop();

  ClusterRenderSettings settings_;
  cluster::ClusterConfig config_;
  std::shared_ptr<cluster::FrameFeed> feed_;
  std::thread master_;
  std::vector<std::pair<pid_t, std::string>> nodes_;
  bool stopped_ = false;
};

}  // namespace zenith::app::offline
