#pragma once
// A live renderer's switch to a leaner frame variant (render/frame/live_variants.h:
// drawn with the programs in use while the leaner ones build on a second
// thread), as the renderer's and the night sky's tests drive it.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <thread>

#include "render/renderer.h"

namespace zenith::render::testing {

/// Calls `render` (one frame of `renderer`) until the renderer draws with the
/// variant its frames want, 50 ms apart, at most `max_frames` times; none of
/// those frames may build a program. The frames it took, counting the held
/// frame before the call.
inline int frames_until_the_wanted_variant(const Renderer& renderer, const std::function<void()>& render,
                                           int max_frames = 400) {
  int frames = 1;
  for (; frames < max_frames && renderer.last_frame().variant_held; ++frames) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    render();
    EXPECT_EQ(renderer.last_frame().programs_built, 0) << "frame " << frames << " built a program";
  }
  return frames;
}

}  // namespace zenith::render::testing
