#pragma once
// The master's table preparation (docs/cluster.md, "Shared tables"): one
// worker thread that obtains table sets (from the cache, else by
// precomputing them) and encodes them for the wire, one job after another in
// the order they were asked for, while the networking thread goes on serving
// nodes and frames. The show's later sets and the default show's atmosphere
// switches are prepared this way, so frames start once the first sets are
// there rather than after the last.
//
// Results come back through the callbacks given at construction, called on
// the worker thread: the master posts them to its own thread.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "atmosphere/parameters.h"
#include "cluster/protocol/table_transfer.h"
#include "render/lut/table_provider.h"

namespace zenith::cluster {

/// Invariants: jobs run one at a time, in the order they were enqueued; every
/// job ends in exactly one callback (prepared or failed) unless the preparer
/// is stopped first; after stop() no callback is called any more.
class TablePreparer {
 public:
  /// One set to prepare: the atmosphere `model` of body `body`, whose table
  /// hash is `table_hash`, with the precompute options and cache of `request`.
  struct Job {
    std::string body;
    Digest table_hash{};
    atmosphere::AtmosphereModel model;
    render::TableRequest request;
  };
  /// A prepared set and how long it took (cache read or precompute, plus encoding).
  using Prepared = std::function<void(TableSetFile set, double seconds, bool from_cache)>;
  /// A job that failed: its hash and the error (std::exception_ptr to rethrow).
  using Failed = std::function<void(const Digest& table_hash, std::exception_ptr error)>;
  /// Whether the preparer was stopped (a running job should end early).
  using Cancelled = std::function<bool()>;
  /// How a job obtains its set; the default is obtain_set (cache or
  /// precompute, then the wire encoding). Tests pass their own.
  using Obtain = std::function<TableSetFile(const Job& job, bool* from_cache, const Cancelled& cancelled)>;

  TablePreparer(Prepared on_prepared, Failed on_failed, Obtain obtain = {});
  /// Stops (see stop()) and joins the worker.
  ~TablePreparer();
  TablePreparer(const TablePreparer&) = delete;
  TablePreparer& operator=(const TablePreparer&) = delete;

  /// Adds a job after those already waiting; starts the worker on first use.
  void enqueue(Job job);
  /// Jobs waiting or running.
  std::size_t outstanding() const;

  /// How far the running job is: its table hash and the precompute's last
  /// progress report (stage "starting", fraction 0, before the first; a cache
  /// read reports none).
  struct Progress {
    Digest table_hash{};
    std::string stage;
    double fraction = 0.0;  ///< of the whole precompute, [0, 1]
  };
  /// The running job's progress; nullopt when no job runs. Any thread.
  std::optional<Progress> running() const;
  /// Drops the waiting jobs and asks the running one to end: a precompute
  /// stops at its next progress report (a fraction of a second on the GPU,
  /// a few seconds at most on the CPU); a cache read finishes. No callback
  /// follows. Returns at once; the destructor joins.
  void stop();

  /// Obtains one job's set the default way: render::obtain_tables, which must
  /// leave a cache file (the nodes get its bytes), then the wire encoding.
  /// `cancelled` is polled at every progress report of a precompute. Throws
  /// std::runtime_error when the set cannot be stored in the cache.
  static TableSetFile obtain_set(const Job& job, bool* from_cache, const Cancelled& cancelled = {});
  /// obtain_set, every set after the first taking `delay_ms` longer (the test
  /// hook `--debug-table-delay-ms` plays a slow precompute; the wait ends when
  /// cancelled). 0: obtain_set itself.
  static Obtain obtain_with_delay(std::uint32_t delay_ms);

 private:
  void run();

  Prepared on_prepared_;
  Failed on_failed_;
  Obtain obtain_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Job> jobs_;
  std::optional<Progress> running_;  ///< the job running now
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace zenith::cluster
