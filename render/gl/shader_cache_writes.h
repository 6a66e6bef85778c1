#pragma once
// Whether the driver's shader cache has written what this process compiled.
//
// The first-dispatch warm-up (render/gl/first_dispatch_warmup.h) hands the
// machine code it has llvmpipe generate to the rendering context through
// Mesa's on-disk shader cache. Mesa writes the cache on threads of its own
// ("<process>:disk$N"), at the lowest priority (SCHED_BATCH, nice 19): on a
// busy machine a write lags the warm-up by hundreds of milliseconds, and a
// frame that dispatches the program before it lands generates the code again.
// On the network rig, under load, a node switched to a leaner variant 4 ms
// after its warm-up generated resolve.comp in 356 ms: that frame took 329 ms
// (17 frames lost), while the node that found the code in the cache 166 ms
// later took 0.001 s for it.
namespace zenith::render::gl {

/// True when no thread of this process named as Mesa's shader-cache writers
/// are (":disk$" in its name) is running or waiting for the disk (state R or
/// D in /proc/self/task/TID/stat): every write queued so far is done. True
/// where there is no such thread (another driver, the cache off, no /proc).
bool shader_cache_writes_done();

}  // namespace zenith::render::gl
