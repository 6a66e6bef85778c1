#pragma once
// Tuning of Mesa's llvmpipe, the CPU rasterizer the project renders with on
// machines without a GPU (docs/rendering-performance.md, "Threads of llvmpipe").
#include <optional>
#include <string>
#include <string_view>

namespace zenith::render::gl {

/// Worker threads llvmpipe should run for a machine with `cpus` CPUs: twice
/// the CPUs up to 8 CPUs, else none chosen (Mesa's default, one per CPU).
std::optional<int> software_rasterizer_threads_for(unsigned cpus);

/// llvmpipe splits each compute dispatch into one equal share of work groups
/// per worker thread (LP_NUM_THREADS, by default one per CPU), and the dispatch
/// ends with its slowest share. On the 2-vCPU machines this project runs on, a
/// worker descheduled for a few milliseconds holds up the whole dispatch: the
/// no-atmosphere ground view took 7.5–14.9 ms a frame (median of six runs 12.4)
/// with 2 threads and 7.9–8.4 ms (8.2) with 4, for the same CPU time. So, unless
/// the user set LP_NUM_THREADS, it is set to software_rasterizer_threads_for()
/// once per process, before the first GL display is initialized (Mesa reads it
/// when it creates its screen). Other drivers ignore it. Returns the setting in
/// effect ("4 (set by zenith)", "3 (LP_NUM_THREADS)", or "Mesa's default").
std::string default_software_rasterizer_threads();

/// Whether a GL_RENDERER string names a CPU rasterizer (llvmpipe, softpipe,
/// swrast, SWR, "software rasterizer"; any case).
bool renderer_is_software(std::string_view gl_renderer);
/// renderer_is_software() of the current context's GL_RENDERER (needs one).
bool current_renderer_is_software();

}  // namespace zenith::render::gl
