// The master's table preparation thread with a stand-in for the precompute
// (cluster/master/table_preparer.h): order, failures, stop.
#include "cluster/master/table_preparer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace zenith::cluster {
namespace {

using namespace std::chrono_literals;

TablePreparer::Job job(std::uint8_t first, const char* body = "Earth") {
  TablePreparer::Job j;
  j.body = body;
  j.table_hash[0] = first;
  return j;
}

/// What the callbacks saw, waited for from the test's thread.
struct Results {
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<std::uint8_t> prepared;  // first byte of each hash, in callback order
  std::vector<std::uint8_t> failed;
  std::vector<std::string> errors;

  void on_prepared(const TableSetFile& set) {
    std::lock_guard lock(mutex);
    prepared.push_back(set.table_hash[0]);
    changed.notify_all();
  }
  void on_failed(const Digest& hash, std::exception_ptr error) {
    std::lock_guard lock(mutex);
    failed.push_back(hash[0]);
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      errors.emplace_back(e.what());
    }
    changed.notify_all();
  }
  bool wait_for(std::size_t callbacks) {
    std::unique_lock lock(mutex);
    return changed.wait_for(lock, 10s, [&] { return prepared.size() + failed.size() >= callbacks; });
  }
};

TEST(TablePreparer, PreparesInOrderOnItsOwnThreadAndReportsFailures) {
  Results results;
  std::atomic<std::thread::id> worker_id{};
  std::map<std::uint8_t, double> seconds_of;  // the worker's; read once every callback came
  const auto start = std::chrono::steady_clock::now();
  TablePreparer preparer(
      [&](TableSetFile set, double seconds, bool from_cache) {
        seconds_of[set.table_hash[0]] = seconds;
        EXPECT_EQ(from_cache, set.table_hash[0] == 2);
        results.on_prepared(set);
      },
      [&](const Digest& hash, std::exception_ptr error) { results.on_failed(hash, error); },
      [&](const TablePreparer::Job& j, bool* from_cache, const TablePreparer::Cancelled&) {
        worker_id = std::this_thread::get_id();
        if (j.table_hash[0] == 4) std::this_thread::sleep_for(50ms);  // a set that takes a while
        if (j.table_hash[0] == 3) throw std::runtime_error("the tables of 'Mars' could not be stored in the cache");
        *from_cache = j.table_hash[0] == 2;
        TableSetFile set;
        set.body_name = j.body;
        set.table_hash = j.table_hash;
        return set;
      });
  preparer.enqueue(job(1));
  preparer.enqueue(job(2));
  preparer.enqueue(job(3, "Mars"));
  preparer.enqueue(job(4));
  ASSERT_TRUE(results.wait_for(4));
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(results.prepared, (std::vector<std::uint8_t>{1, 2, 4})) << "a failure does not stop the later jobs";
  // Each set's time is its own job's: the 50 ms set took at least that, and none more than the whole run.
  EXPECT_GE(seconds_of.at(4), 0.050);
  for (const auto& [first, seconds] : seconds_of) EXPECT_LE(seconds, wall_s) << "set " << int(first);
  EXPECT_EQ(results.failed, (std::vector<std::uint8_t>{3}));
  ASSERT_EQ(results.errors.size(), 1u);
  EXPECT_NE(results.errors[0].find("'Mars'"), std::string::npos);
  EXPECT_NE(worker_id.load(), std::this_thread::get_id());
  EXPECT_EQ(preparer.outstanding(), 0u);
}

TEST(TablePreparer, StopDropsWaitingJobsAndCallsNothingMore) {
  Results results;
  std::mutex gate_mutex;
  std::condition_variable gate;
  bool open = false, started = false;
  std::atomic<int> obtained{0};
  {
    TablePreparer preparer([&](TableSetFile set, double, bool) { results.on_prepared(set); },
                           [&](const Digest& hash, std::exception_ptr e) { results.on_failed(hash, e); },
                           [&](const TablePreparer::Job& j, bool*, const TablePreparer::Cancelled&) {
                             std::unique_lock lock(gate_mutex);
                             started = true;
                             gate.notify_all();
                             gate.wait(lock, [&] { return open; });
                             ++obtained;
                             TableSetFile set;
                             set.table_hash = j.table_hash;
                             return set;
                           });
    preparer.enqueue(job(1));
    preparer.enqueue(job(2));
    {
      std::unique_lock lock(gate_mutex);
      gate.wait(lock, [&] { return started; });
    }
    EXPECT_EQ(preparer.outstanding(), 2u);
    preparer.stop();
    EXPECT_EQ(preparer.outstanding(), 1u) << "the waiting job is dropped, the running one finishes";
    preparer.enqueue(job(3));  // ignored once stopped
    {
      std::lock_guard lock(gate_mutex);
      open = true;
    }
    gate.notify_all();
  }  // joins
  EXPECT_EQ(obtained.load(), 1);
  EXPECT_TRUE(results.prepared.empty()) << "no callback after stop()";
  EXPECT_TRUE(results.failed.empty());
}

TEST(TablePreparer, AnIdlePreparerStopsAtOnce) {
  const auto t0 = std::chrono::steady_clock::now();
  {
    TablePreparer preparer([](TableSetFile, double, bool) {}, [](const Digest&, std::exception_ptr) {},
                           [](const TablePreparer::Job& j, bool*, const TablePreparer::Cancelled&) {
                             TableSetFile set;
                             set.table_hash = j.table_hash;
                             return set;
                           });
  }
  {
    std::atomic<int> prepared{0};
    TablePreparer preparer([&](TableSetFile, double, bool) { ++prepared; }, [](const Digest&, std::exception_ptr) {},
                           [](const TablePreparer::Job& j, bool*, const TablePreparer::Cancelled&) {
                             TableSetFile set;
                             set.table_hash = j.table_hash;
                             return set;
                           });
    preparer.enqueue(job(1));
    while (prepared.load() == 0 && std::chrono::steady_clock::now() - t0 < 10s) std::this_thread::sleep_for(1ms);
    EXPECT_EQ(prepared.load(), 1);
  }  // the worker waits for jobs: the destructor wakes and joins it
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 5s);
}

TEST(TablePreparer, ReportsTheRunningJobsProgress) {
  Results results;
  std::mutex step;
  std::condition_variable stepped;
  int stage = 0;  // 0: reported; 1: the test looked; the job then ends
  TablePreparer preparer([&](TableSetFile set, double, bool) { results.on_prepared(set); },
                         [&](const Digest& hash, std::exception_ptr error) { results.on_failed(hash, error); },
                         [&](const TablePreparer::Job& j, bool*, const TablePreparer::Cancelled&) {
                           j.request.options.progress({"single scattering", 0.25});
                           std::unique_lock lock(step);
                           stepped.wait_for(lock, 10s, [&] { return stage == 1; });
                           TableSetFile set;
                           set.table_hash = j.table_hash;
                           return set;
                         });
  EXPECT_FALSE(preparer.running());
  preparer.enqueue(job(7));
  std::optional<TablePreparer::Progress> seen;
  for (int i = 0; i < 1000 && !(seen && seen->fraction > 0.0); ++i) {
    seen = preparer.running();
    std::this_thread::sleep_for(5ms);
  }
  ASSERT_TRUE(seen);
  EXPECT_EQ(seen->table_hash[0], 7);
  EXPECT_EQ(seen->stage, "single scattering");
  EXPECT_EQ(seen->fraction, 0.25);
  {
    std::lock_guard lock(step);
    stage = 1;
  }
  stepped.notify_all();
  ASSERT_TRUE(results.wait_for(1));
  EXPECT_FALSE(preparer.running());
}

}  // namespace
}  // namespace zenith::cluster
