#include "render/gl/program_builds.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <utility>

#include "render/gl/first_dispatch_warmup.h"
#include "render/gl/program_binary_cache.h"

namespace zenith::render::gl {

namespace {

double seconds_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

const char* to_string(CompileMode mode) {
  switch (mode) {
    case CompileMode::parallel: return "parallel";
    case CompileMode::serial: return "serial";
    case CompileMode::contexts: return "contexts";
  }
  return "?";
}

ProgramBuilds::ProgramBuilds(CompileMode mode) : mode_(mode), driver_threads_(has_parallel_shader_compile()) {
  if (!driver_threads_) return;
  glGetIntegerv(GL_MAX_SHADER_COMPILER_THREADS_KHR, &previous_threads_);
  set_shader_compiler_threads(mode == CompileMode::serial ? 0u : kAllCompilerThreads);
}

ProgramBuilds::~ProgramBuilds() {
  pending_.clear();  // builds never asked for: abandoned
  if (driver_threads_) set_shader_compiler_threads(static_cast<unsigned>(previous_threads_));
}

ShaderBuild ProgramBuilds::timed_start(const Starter& starter) {
  const auto now = std::chrono::steady_clock::now();
  ShaderBuild build = starter();
  statistics_.start_s += seconds_between(now, std::chrono::steady_clock::now());
  return build;
}

void ProgramBuilds::start(const std::string& key, const Starter& starter, BuildFor build_for) {
  if (mode_ == CompileMode::serial || programs_.contains(key) || pending_.contains(key)) return;
  if (!threads_.empty()) {
    FirstDispatchWarmup* thread = threads_[next_thread_++ % threads_.size()];
    pending_.emplace(key, OnThread{thread->build([starter] { return starter().finish(); }), starter});
  } else
    pending_.emplace(key, timed_start(starter));
  (build_for == BuildFor::this_frame ? started_ : ahead_).push_back(key);
  statistics_.most_in_flight = std::max(statistics_.most_in_flight, static_cast<int>(pending_.size()));
}

ShaderProgram ProgramBuilds::finish(Pending& build) {
  if (auto* here = std::get_if<ShaderBuild>(&build)) return here->finish();
  OnThread& there = std::get<OnThread>(build);
  // Queued behind others on the one thread and not begun there yet: built
  // here rather than waited for, while the thread builds the others (two
  // cores compile instead of one). A thread per build begins at once.
  const bool taken_back = threads_.size() == 1 && there.queued.take_back();
  if (!taken_back) {
    try {
      ShaderProgram program = there.queued.program.get();
      ++statistics_.built_on_thread;
      return program;
    } catch (const std::future_error&) {  // dropped by the thread: built here
    }
  }
  ShaderProgram program = timed_start(there.starter).finish();
  if (taken_back) ++statistics_.built_while_waiting;
  return program;
}

bool ProgramBuilds::ready(const Pending& build) {
  if (const auto* here = std::get_if<ShaderBuild>(&build)) return here->ready();
  return std::get<OnThread>(build).queued.program.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

bool ProgramBuilds::finish_ahead(FirstDispatchWarmup* warmup, const DispatchShapes& shapes) {
  std::erase_if(ahead_, [&](const std::string& key) {
    const auto pending = pending_.find(key);
    if (pending != pending_.end() && !ready(pending->second)) return false;
    if (pending != pending_.end()) {  // else a frame needed it first and finished it
      Pending build = std::move(pending->second);
      pending_.erase(pending);  // a build that throws is not tried again
      const int on_thread = statistics_.built_on_thread;
      programs_.emplace(key, finish(build));
      statistics_.built_on_thread = on_thread;  // built_on_thread counts the frames' builds
      ++statistics_.built_ahead;
    }
    const auto program = programs_.find(key);  // absent: it failed where a frame asked for it
    if (program != programs_.end() && warmup != nullptr && !program->second.dispatched())
      warmup->warm(program->second, shapes);
    return true;
  });
  return ahead_.empty();
}

const ShaderProgram& ProgramBuilds::get(const std::string& key, const Starter& starter) {
  if (auto it = programs_.find(key); it != programs_.end()) return it->second;
  Pending build;
  const bool ahead = pending_.contains(key);
  if (auto it = pending_.find(key); it != pending_.end()) {
    build = std::move(it->second);
    pending_.erase(it);
  } else {
    build = timed_start(starter);
    statistics_.most_in_flight = std::max(statistics_.most_in_flight, static_cast<int>(pending_.size()) + 1);
  }
  const auto start = std::chrono::steady_clock::now();
  ShaderProgram program = finish(build);
  const auto end = std::chrono::steady_clock::now();
  statistics_.wait_s += seconds_between(start, end);
  spdlog::debug("program {}: {} {:.3f} s", key,
                !ahead                                    ? "built in"
                : std::holds_alternative<OnThread>(build) ? "started ahead on a second thread, waited"
                                                          : "started ahead, waited",
                seconds_between(start, end));
  ++statistics_.built;
  return programs_.emplace(key, std::move(program)).first->second;
}

void ProgramBuilds::warm_started(FirstDispatchWarmup& warmup, const DispatchShapes& shapes,
                                 const std::function<int(const ShaderProgram&)>& order) {
  std::vector<std::pair<int, ShaderProgram*>> queue;  // the last started first, then by `order`
  const std::vector<std::string> started = std::exchange(started_, {});
  for (auto key_it = started.rbegin(); key_it != started.rend(); ++key_it) {
    const std::string& key = *key_it;
    if (pending_.contains(key)) get(key, {});
    auto it = programs_.find(key);
    if (it == programs_.end() || it->second.dispatched()) continue;
    if (const int place = order(it->second); place >= 0) queue.emplace_back(place, &it->second);
  }
  std::stable_sort(queue.begin(), queue.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (const auto& [place, program] : queue) warmup.warm(*program, shapes);
}

void ProgramBuilds::warm(FirstDispatchWarmup& warmup, const DispatchShapes& shapes,
                         const std::vector<const ShaderProgram*>& programs) {
  for (auto& [key, program] : programs_)
    if (!program.dispatched() && std::find(programs.begin(), programs.end(), &program) != programs.end())
      warmup.warm(program, shapes);
}

std::string ProgramBuilds::summary() const {
  const Statistics& s = statistics_;
  std::string how;
  if (s.built_on_thread > 0 && threads_.size() > 1)
    how = fmt::format("{} of them compiled on {} threads of their own, a context each", s.built_on_thread,
                      threads_.size());
  else if (s.built_on_thread + s.built_while_waiting > 0)
    how = fmt::format(
        "{} of them compiled on a second thread, one at a time, {} here while waiting for it (the driver compiles "
        "in the calling thread)",
        s.built_on_thread, s.built_while_waiting);
  else if (mode_ == CompileMode::serial)
    how = driver_threads_ ? "one at a time (serial; the driver's compiler threads off)" : "one at a time (serial)";
  else if (driver_threads_)
    how =
        fmt::format("at most {} at once on the driver's compiler threads (parallel shader compile)", s.most_in_flight);
  else
    how = fmt::format("{} started at once, compiled one at a time (the driver has no parallel shader compile)",
                      s.most_in_flight);
  std::string out = fmt::format("{} programs, {:.3f} s building them ({:.3f} s starting, {:.3f} s waiting), {}",
                                s.built, s.seconds(), s.start_s, s.wait_s, how);
  if (s.built_ahead > 0) out += fmt::format("; {} more built ahead for later frames", s.built_ahead);
  if (binaries_ != nullptr) {
    const ProgramBinaryCache::Statistics b = binaries_->statistics();
    out += binaries_->enabled() ? fmt::format("; binaries: {} of {} loaded, {} stored, {} refused ({})", b.loaded,
                                              s.built, b.stored, b.refused, binaries_->directory().string())
                                : std::string("; binaries: none (the driver offers no binary format)");
  }
  return out;
}

}  // namespace zenith::render::gl
