#pragma once
// CPU time of the benchmark's own process, for the frame benchmarks'
// cpu_ms figures (render_bench, render_bench --present).
#include <sys/resource.h>

namespace zenith::bench {

/// CPU time of the whole process so far (user + system, every thread) [s]:
/// on a machine shared with other work, a frame's CPU time moves less than its
/// wall time (llvmpipe runs the shaders on the process's own threads; a GPU
/// driver may spin while it waits).
inline double process_cpu_s() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
}

}  // namespace zenith::bench
