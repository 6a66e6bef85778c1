#include "cluster/master/table_preparer.h"

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include "core/strings.h"

namespace zenith::cluster {

namespace {

/// Thrown from a precompute's progress report to end it early (stop()).
struct PreparationCancelled : std::runtime_error {
  PreparationCancelled() : std::runtime_error("table preparation cancelled: the master is stopping") {}
};

}  // namespace

TablePreparer::TablePreparer(Prepared on_prepared, Failed on_failed, Obtain obtain)
    : on_prepared_(std::move(on_prepared)), on_failed_(std::move(on_failed)), obtain_(std::move(obtain)) {}

TablePreparer::~TablePreparer() {
  stop();
  if (worker_.joinable()) worker_.join();
}

void TablePreparer::enqueue(Job job) {
  std::lock_guard lock(mutex_);
  if (stopping_) return;
  jobs_.push_back(std::move(job));
  if (!worker_.joinable()) worker_ = std::thread([this] { run(); });
  wake_.notify_one();
}

std::size_t TablePreparer::outstanding() const {
  std::lock_guard lock(mutex_);
  return jobs_.size() + (running_ ? 1 : 0);
}

std::optional<TablePreparer::Progress> TablePreparer::running() const {
  std::lock_guard lock(mutex_);
  return running_;
}

void TablePreparer::stop() {
  std::lock_guard lock(mutex_);
  stopping_ = true;
  jobs_.clear();
  wake_.notify_one();
}

TableSetFile TablePreparer::obtain_set(const Job& job, bool* from_cache, const Cancelled& cancelled) {
  render::TableRequest request = job.request;
  if (cancelled) {
    request.options.progress = [cancelled,
                                caller = request.options.progress](const atmosphere::lut::PrecomputeProgress& p) {
      if (caller) caller(p);
      if (cancelled()) throw PreparationCancelled();
    };
  }
  render::ObtainedTables obtained = render::obtain_tables(job.model, request);
  if (obtained.cache_file.empty())
    throw std::runtime_error(core::cat("the tables of '", job.body,
                                       "' could not be stored in the cache: nodes get "
                                       "the cache file's bytes, so the master needs a writable table cache directory"));
  if (from_cache != nullptr) *from_cache = obtained.from_cache;
  return make_table_set_file(job.body, job.table_hash, obtained.cache_file);
}

void TablePreparer::run() {
  const Cancelled cancelled = [this] {
    std::lock_guard lock(mutex_);
    return stopping_;
  };
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
      if (stopping_) return;
      job = std::move(jobs_.front());
      jobs_.pop_front();
      running_ = Progress{job.table_hash, "starting", 0.0};
    }
    job.request.options.progress =
        [this, caller = job.request.options.progress](const atmosphere::lut::PrecomputeProgress& p) {
          {
            std::lock_guard lock(mutex_);
            if (running_) {
              running_->stage = p.stage;
              running_->fraction = p.fraction;
            }
          }
          if (caller) caller(p);
        };
    const auto started = std::chrono::steady_clock::now();
    bool from_cache = false;
    std::optional<TableSetFile> set;
    std::exception_ptr error;
    try {
      set = obtain_ ? obtain_(job, &from_cache, cancelled) : obtain_set(job, &from_cache, cancelled);
    } catch (...) {
      error = std::current_exception();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    {
      std::lock_guard lock(mutex_);
      running_.reset();  // done: the callback only reports it
      if (stopping_) return;
    }
    if (set)
      on_prepared_(std::move(*set), seconds, from_cache);
    else
      on_failed_(job.table_hash, error);
  }
}

TablePreparer::Obtain TablePreparer::obtain_with_delay(std::uint32_t delay_ms) {
  return [delay_ms, jobs = std::make_shared<std::atomic<int>>(0)](const Job& job, bool* from_cache,
                                                                  const Cancelled& cancelled) {
    if (delay_ms > 0 && (*jobs)++ > 0)
      for (std::uint32_t ms = 0; ms < delay_ms && !cancelled(); ms += 10)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return obtain_set(job, from_cache, cancelled);
  };
}

}  // namespace zenith::cluster
