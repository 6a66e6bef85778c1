#include "render/frame/pass_timer.h"

#include <epoxy/gl.h>

namespace zenith::render {

void PassTimer::begin_gpu() {
  glFinish();  // earlier work must not count
  start_ = std::chrono::steady_clock::now();
}

double PassTimer::end_gpu_ms() {
  glFinish();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
}

}  // namespace zenith::render
