#pragma once
// Shows a finished frame — the Renderer's linear sRGB × exposure floats — on a
// framebuffer: tone mapping and sRGB encoding on the GPU
// (shaders/render/present.vert/.frag), letterboxed to keep the frame's aspect
// ratio, scaled nearest-neighbour (no filtering between pixels). The bytes it
// writes equal image::display_byte of the input within 1, i.e. what the PNG
// writer stores. Needs a current GL 4.5 context: a window's
// (render/window/window_context.h) or a headless one drawing into an FBO.
#include <span>

#include "image/tone_mapping.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"

namespace zenith::render::window {

/// Where FramePresenter draws: a draw framebuffer (0: the default one, the
/// window) and its size in pixels. GL has no query for the default
/// framebuffer's size, hence explicit (WindowContext::framebuffer_size()).
struct PresentTarget {
  unsigned framebuffer = 0;
  int width = 0;
  int height = 0;
};

/// The rectangle a frame occupies in a target: the largest one with the frame's
/// aspect ratio, centred (pixels, origin at the bottom left as for glViewport).
/// The rest of the target is black bars.
struct Letterbox {
  int x = 0, y = 0, width = 0, height = 0;
};
/// Throws std::invalid_argument for a non-positive size.
Letterbox letterbox(int frame_width, int frame_height, int target_width, int target_height);

class FramePresenter {
 public:
  /// Compiles the present program; throws std::runtime_error on GL failures.
  FramePresenter();
  ~FramePresenter();
  FramePresenter(FramePresenter&& other) noexcept;
  FramePresenter& operator=(FramePresenter&& other) noexcept;
  FramePresenter(const FramePresenter&) = delete;
  FramePresenter& operator=(const FramePresenter&) = delete;

  /// Uploads a frame: width · height · 3 floats, row 0 at the top, x fastest
  /// (Renderer::render_image). The texture is (re)allocated when the size
  /// changes. Throws std::invalid_argument when `rgb` has another size.
  void upload(std::span<const float> rgb, int width, int height);
  /// Draws the last uploaded frame into `target`: clears it to black, then the
  /// letterboxed frame, tone mapped by `tone` and sRGB encoded. Throws
  /// std::logic_error before any upload.
  void draw(image::ToneMapping tone, const PresentTarget& target) const;
  /// upload() then draw().
  void present(std::span<const float> rgb, int width, int height, image::ToneMapping tone, const PresentTarget& target);

  /// Size of the last uploaded frame (0 × 0 before the first).
  int frame_width() const { return texture_.width(); }
  int frame_height() const { return texture_.height(); }

 private:
  void release() noexcept;

  gl::ShaderProgram program_;
  gl::Texture texture_;
  unsigned vertex_array_ = 0;  // empty: the full-screen triangle comes from gl_VertexID
};

}  // namespace zenith::render::window
