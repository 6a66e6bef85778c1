#pragma once
// Private to zenith_image: libpng's error path, shared by the PNG reader and writer.
//
// libpng reports an error by calling the error callback, which must not return;
// the documented way out is longjmp to a setjmp point (png_jmpbuf). C++
// exceptions must not unwind through libpng's C frames, and a longjmp is only
// defined when a throw in its place would run no non-trivial destructor
// ([csetjmp.syn]). So every libpng call goes through png_guarded(): it sets the
// jump point in its own small frame and runs `step`, a lambda that calls libpng
// and touches only trivially destructible locals (pointers, integers, floats;
// containers are declared outside and reached through pointers). On an error
// the callback copies the message into PngErrorState and longjmps back into
// png_guarded, which returns false; the caller then throws an ordinary exception.
// After an error the png struct may only be destroyed.
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>

namespace zenith::image::detail {

/// The last libpng error message (set by png_error_callback).
struct PngErrorState {
  char message[256] = "unknown libpng error";
};

/// png_error_ptr: records the message, then leaves through png_longjmp.
[[noreturn]] inline void png_error_callback(png_structp png, png_const_charp message) {
  auto* state = static_cast<PngErrorState*>(png_get_error_ptr(png));
  if (state) std::snprintf(state->message, sizeof state->message, "%s", message ? message : "(no message)");
  png_longjmp(png, 1);
}

/// png_error_ptr for warnings (e.g. a bad ancillary chunk, which libpng skips): ignored.
inline void png_warning_callback(png_structp, png_const_charp) {}

/// Runs `step` under libpng's error jump; returns false if libpng reported an error.
template <class Step>
bool png_guarded(png_structp png, const Step& step) {
  if (setjmp(png_jmpbuf(png))) return false;
  step();
  return true;
}

}  // namespace zenith::image::detail
