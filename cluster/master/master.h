#pragma once
// The cluster master (docs/cluster.md): accepts render nodes, authenticates
// them (handshake.h), sends them the lookup tables of every atmosphere of the
// scene, then drives the frame barrier:
//
//   FrameState N ──► every live node ──► RenderDone N from each (or the barrier
//   timeout: late nodes are dropped from the frame with a log line naming them)
//   ──► Present N to every node that finished N ──► FrameState N + 1 …
//
// Nodes join or rejoin at any time; they get the tables (only those their
// cache lacks: the inventory), then enter at the next frame boundary. All
// networking runs on one thread (the io_context's); the caller's thread
// prepares the scene's tables and then runs that loop. Table sets prepared
// while frames go on — a show's later sets, a new version of an atmosphere
// (AtmosphereSwitch) — are obtained in order on one worker thread
// (table_preparer.h) and sent to every node as they are ready (table_schedule.h). A show
// starts once the sets of its first frame are ready (live: once the rest are
// predicted ready in time, show_start_rule.h); a frame whose set is not
// yet held by every node waits for it. A switch takes effect at one frame on
// all nodes once every ready node holds it (docs/cluster.md, "Table versions").
#include <memory>

#include "cluster/master/master_options.h"
#include "cluster/protocol/handshake.h"

namespace zenith::cluster {

class Master {
 public:
  Master(MasterOptions options, SharedSecret secret);
  ~Master();
  Master(const Master&) = delete;
  Master& operator=(const Master&) = delete;

  /// Prepares the tables, listens and runs the show. Returns 0 when the frames
  /// were presented (or on SIGINT/SIGTERM, after Goodbye to every node).
  /// Throws for configuration, table or socket errors (port in use).
  int run();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace zenith::cluster
