#include "render/window/frame_presenter.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "render/gl/gl_error.h"
#include "render/shader_bindings.h"
#include "render/shader_programs.h"

namespace zenith::render::window {

Letterbox letterbox(int frame_width, int frame_height, int target_width, int target_height) {
  if (frame_width < 1 || frame_height < 1 || target_width < 1 || target_height < 1)
    throw std::invalid_argument(fmt::format("letterbox: frame {}x{} into target {}x{}: sizes must be ≥ 1", frame_width,
                                            frame_height, target_width, target_height));
  // Scale by the tighter of the two ratios; the other axis gets bars.
  const double scale =
      std::min(static_cast<double>(target_width) / frame_width, static_cast<double>(target_height) / frame_height);
  Letterbox box;
  box.width = std::clamp(static_cast<int>(std::lround(frame_width * scale)), 1, target_width);
  box.height = std::clamp(static_cast<int>(std::lround(frame_height * scale)), 1, target_height);
  box.x = (target_width - box.width) / 2;
  box.y = (target_height - box.height) / 2;
  return box;
}

FramePresenter::FramePresenter() : program_(load_graphics_program("render/present.vert", "render/present.frag")) {
  glCreateVertexArrays(1, &vertex_array_);
  gl::check_gl_error("FramePresenter: creating the vertex array");
}

FramePresenter::~FramePresenter() { release(); }

FramePresenter::FramePresenter(FramePresenter&& other) noexcept
    : program_(std::move(other.program_)),
      texture_(std::move(other.texture_)),
      vertex_array_(std::exchange(other.vertex_array_, 0u)) {}

FramePresenter& FramePresenter::operator=(FramePresenter&& other) noexcept {
  if (this != &other) {
    release();
    program_ = std::move(other.program_);
    texture_ = std::move(other.texture_);
    vertex_array_ = std::exchange(other.vertex_array_, 0u);
  }
  return *this;
}

void FramePresenter::release() noexcept {
  if (vertex_array_ != 0) glDeleteVertexArrays(1, &vertex_array_);
  vertex_array_ = 0;
}

void FramePresenter::upload(std::span<const float> rgb, int width, int height) {
  if (width < 1 || height < 1)
    throw std::invalid_argument(fmt::format("FramePresenter::upload: frame size {}x{}: must be ≥ 1", width, height));
  const std::size_t expected = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3;
  if (rgb.size() != expected)
    throw std::invalid_argument(fmt::format("FramePresenter::upload: {} floats given, a {}x{} RGB frame has {}",
                                            rgb.size(), width, height, expected));
  if (texture_.id() == 0 || texture_.width() != width || texture_.height() != height) {
    texture_ = gl::Texture::create_2d(gl::TextureFormat::rgba32f, width, height);
    // Pixels are shown as rendered: nearest-neighbour scaling, so a window of
    // the frame's size shows exactly its pixels (and a stray NaN stays in its
    // own pixel instead of blackening its neighbours through filtering).
    glTextureParameteri(texture_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  // RGB client data into the RGBA texture (GL sets alpha to 1): no CPU copy.
  // Rows go in as given, the top row at t = 0; present.frag flips when
  // sampling. Rows are 12·width bytes, a multiple of the default alignment 4.
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
  glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
  glTextureSubImage2D(texture_.id(), 0, 0, 0, width, height, GL_RGB, GL_FLOAT, rgb.data());
  gl::check_gl_error("FramePresenter::upload");
}

void FramePresenter::draw(image::ToneMapping tone, const PresentTarget& target) const {
  if (texture_.id() == 0) throw std::logic_error("FramePresenter::draw before any upload");
  if (target.width < 1 || target.height < 1)
    throw std::invalid_argument(
        fmt::format("FramePresenter::draw: target size {}x{}: must be ≥ 1", target.width, target.height));
  const Letterbox box = letterbox(texture_.width(), texture_.height(), target.width, target.height);

  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target.framebuffer);
  glDisable(GL_FRAMEBUFFER_SRGB);  // present.frag encodes sRGB itself
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glViewport(0, 0, target.width, target.height);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);

  glViewport(box.x, box.y, box.width, box.height);
  program_.set_uniform("tone_mapping", tone == image::ToneMapping::clamp ? 1 : 0);
  program_.use();
  texture_.bind(binding::kPresentFrameUnit);
  glBindVertexArray(vertex_array_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  gl::check_gl_error("FramePresenter::draw");
}

void FramePresenter::present(std::span<const float> rgb, int width, int height, image::ToneMapping tone,
                             const PresentTarget& target) {
  upload(rgb, width, height);
  draw(tone, target);
}

}  // namespace zenith::render::window
