#include "tests/window/screen_capture.h"

#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <stdexcept>

namespace zenith::render::window::testing {
namespace {

/// A channel of a TrueColor pixel scaled to 8 bits.
std::uint8_t channel(unsigned long pixel, unsigned long mask) {
  if (mask == 0) return 0;
  int shift = 0;
  while ((mask & 1) == 0) {
    mask >>= 1;
    ++shift;
  }
  return static_cast<std::uint8_t>(((pixel >> shift) & mask) * 255 / mask);
}

}  // namespace

Screen capture_screen() {
  ::Display* display = XOpenDisplay(nullptr);
  if (display == nullptr) throw std::runtime_error("capture_screen: XOpenDisplay failed (no DISPLAY?)");
  const ::Window root = DefaultRootWindow(display);
  XWindowAttributes attributes{};
  XGetWindowAttributes(display, root, &attributes);
  XSync(display, False);
  XImage* image = XGetImage(display, root, 0, 0, static_cast<unsigned>(attributes.width),
                            static_cast<unsigned>(attributes.height), AllPlanes, ZPixmap);
  if (image == nullptr) {
    XCloseDisplay(display);
    throw std::runtime_error("capture_screen: XGetImage of the root window failed");
  }
  Screen s{attributes.width, attributes.height, {}};
  s.rgb.resize(static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height) * 3);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const unsigned long p = XGetPixel(image, x, y);
      std::uint8_t* out =
          &s.rgb[(static_cast<std::size_t>(y) * static_cast<std::size_t>(s.width) + static_cast<std::size_t>(x)) * 3];
      out[0] = channel(p, image->red_mask);
      out[1] = channel(p, image->green_mask);
      out[2] = channel(p, image->blue_mask);
    }
  XDestroyImage(image);
  XCloseDisplay(display);
  return s;
}

}  // namespace zenith::render::window::testing
