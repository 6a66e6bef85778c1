#pragma once
// The master's side of the operator's door (cluster/operator/desk_master.h):
// what the desk may read of the master's parts and ask of them — where the
// frames are, the atmospheres' table versions, the status of nodes and
// tables, the end of the show. Holds references to the parts; they outlive it.
// Networking thread only.
#include <functional>
#include <optional>
#include <string>

#include "cluster/link/cluster_config.h"
#include "cluster/master/frame_barrier.h"
#include "cluster/master/frame_progress.h"
#include "cluster/master/node_sessions.h"
#include "cluster/master/node_statistics.h"
#include "cluster/master/table_preparer.h"
#include "cluster/master/table_schedule.h"
#include "cluster/operator/desk_master.h"
#include "show/playback_clock.h"
#include "show/show.h"

namespace zenith::cluster {

class MasterDesk final : public DeskMaster {
 public:
  struct Parts {
    const ClusterConfig& config;
    const NodeSessions& sessions;
    const FrameBarrier& barrier;
    TableSchedule& tables;
    const NodeStatistics& statistics;
    const FrameProgress& progress;
    const show::Show* show = nullptr;            ///< nullptr: the default show
    const show::PlaybackClock* clock = nullptr;  ///< a show's clock
    double fps = 30.0;
    std::function<std::optional<TablePreparer::Progress>()> preparing;  ///< the preparer's running job
    std::function<void(const std::string& reason)> stop;
    /// The chase of the house's timecode at the latest frame; nullptr: the show runs on its clock.
    const show::ChasePosition* timecode = nullptr;
  };
  explicit MasterDesk(Parts parts) : p_(std::move(parts)) {}

  const FrameState* latest_frame() const override { return p_.progress.started ? &p_.progress.in_flight : nullptr; }
  std::uint64_t barrier_frame() const override { return p_.barrier.frame(); }
  std::string set_atmosphere(const operator_command::Set& set) override { return p_.tables.set_atmosphere(set); }
  std::string clear_atmosphere(const std::string& body) override { return p_.tables.clear_atmosphere(body); }
  nlohmann::json status(const DeskStatus& desk) const override;
  void stop(const std::string& reason) override { p_.stop(reason); }

 private:
  Parts p_;
};

}  // namespace zenith::cluster
