#pragma once
// A fragment pass drawn into some rows of a texture: a framebuffer with the
// texture as its colour attachment, the rows as the viewport, and one triangle
// from an empty vertex array (the vertex shader makes the triangle that covers
// the viewport from gl_VertexID, as shaders/render/present.vert does).
// Fragment (x, y) writes texel (x, y). Used by the renderer's band copy
// (render/band/band_to_texture.h) and the display pass
// (render/display/display_encoder.h).
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"

namespace zenith::render::gl {

class TextureRowsDraw {
 public:
  TextureRowsDraw() = default;
  ~TextureRowsDraw();
  TextureRowsDraw(TextureRowsDraw&& other) noexcept;
  TextureRowsDraw& operator=(TextureRowsDraw&& other) noexcept;
  TextureRowsDraw(const TextureRowsDraw&) = delete;
  TextureRowsDraw& operator=(const TextureRowsDraw&) = delete;

  /// Binds the framebuffer (created on first use) with `target` as its colour
  /// attachment and rows [first_row, first_row + rows) as the viewport; no sRGB
  /// conversion, scissor, depth test or blending, every channel written.
  void bind(const Texture& target, int first_row, int rows);
  /// The triangle, drawn with `program` (ShaderProgram::draw_triangles).
  void draw(const ShaderProgram& program) const;
  /// The triangle, drawn with the program in use (glUseProgram): a warm-up
  /// thread's draw, which holds the program's id only.
  void draw_with_program_in_use() const;
  /// Binds the default draw framebuffer and detaches the texture (the
  /// framebuffer keeps no texture alive).
  void unbind() const;

 private:
  unsigned framebuffer_ = 0;   // the target as colour attachment
  unsigned vertex_array_ = 0;  // empty: the triangle comes from gl_VertexID
};

}  // namespace zenith::render::gl
