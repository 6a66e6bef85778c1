#pragma once
// The window tests' view of the screen: the root window of the X display
// (DISPLAY) captured with XGetImage, as RGB bytes. Kept apart so that no X11
// header (its macros: None, Bool, Status…) reaches the tests.
#include <array>
#include <cstdint>
#include <vector>

namespace zenith::render::window::testing {

struct Screen {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< 3 bytes a pixel, row 0 at the top
  std::array<int, 3> at(int x, int y) const {
    const std::size_t i =
        (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

/// The whole screen now. Throws std::runtime_error without a display.
Screen capture_screen();

}  // namespace zenith::render::window::testing
