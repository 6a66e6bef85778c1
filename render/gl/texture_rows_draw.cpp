#include "render/gl/texture_rows_draw.h"

#include <epoxy/gl.h>

#include <utility>

namespace zenith::render::gl {

TextureRowsDraw::~TextureRowsDraw() {
  if (framebuffer_ != 0) glDeleteFramebuffers(1, &framebuffer_);
  if (vertex_array_ != 0) glDeleteVertexArrays(1, &vertex_array_);
}

TextureRowsDraw::TextureRowsDraw(TextureRowsDraw&& other) noexcept
    : framebuffer_(std::exchange(other.framebuffer_, 0u)), vertex_array_(std::exchange(other.vertex_array_, 0u)) {}

TextureRowsDraw& TextureRowsDraw::operator=(TextureRowsDraw&& other) noexcept {
  if (this != &other) {
    std::swap(framebuffer_, other.framebuffer_);
    std::swap(vertex_array_, other.vertex_array_);
  }
  return *this;
}

void TextureRowsDraw::bind(const Texture& target, int first_row, int rows) {
  if (framebuffer_ == 0) {
    glCreateFramebuffers(1, &framebuffer_);
    glCreateVertexArrays(1, &vertex_array_);
  }
  glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, target.id(), 0);
  glNamedFramebufferDrawBuffer(framebuffer_, GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glViewport(0, first_row, target.width(), rows);
}

void TextureRowsDraw::draw(const ShaderProgram& program) const {
  glBindVertexArray(vertex_array_);
  program.draw_triangles(3);
  glBindVertexArray(0);
}

void TextureRowsDraw::draw_with_program_in_use() const {
  glBindVertexArray(vertex_array_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

void TextureRowsDraw::unbind() const {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, 0, 0);
}

}  // namespace zenith::render::gl
