#include "render/gl/texture.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include "render/gl/gl_error.h"

namespace zenith::render::gl {

unsigned internal_format(TextureFormat f) {
  switch (f) {
    case TextureFormat::r32f: return GL_R32F;
    case TextureFormat::rg32f: return GL_RG32F;
    case TextureFormat::rgba32f: return GL_RGBA32F;
    case TextureFormat::rgba16f: return GL_RGBA16F;
    case TextureFormat::rgba8: return GL_RGBA8;
    case TextureFormat::rgba16: return GL_RGBA16;
  }
  return GL_RGBA32F;
}

namespace {

GLenum pixel_format(TextureFormat f) {
  switch (f) {
    case TextureFormat::r32f: return GL_RED;
    case TextureFormat::rg32f: return GL_RG;
    case TextureFormat::rgba32f:
    case TextureFormat::rgba16f:
    case TextureFormat::rgba8:
    case TextureFormat::rgba16: return GL_RGBA;
  }
  return GL_RGBA;
}

/// The levels of a full mipmap chain of a width × height image, down to 1 × 1.
int full_mip_levels(int width, int height) {
  int levels = 1;
  for (int extent = std::max(width, height); extent > 1; extent /= 2) ++levels;
  return levels;
}

/// Fills `texture` with `data`, or with zeros when `data` is empty.
void upload_or_zero(Texture& texture, TextureFormat format, std::span<const float> data) {
  if (data.empty()) {
    const float zero[4] = {0, 0, 0, 0};
    glClearTexImage(texture.id(), 0, pixel_format(format), GL_FLOAT, zero);
  } else {
    texture.upload(data);
  }
}

GLenum access_enum(ImageAccess a) {
  switch (a) {
    case ImageAccess::read_only: return GL_READ_ONLY;
    case ImageAccess::write_only: return GL_WRITE_ONLY;
    case ImageAccess::read_write: return GL_READ_WRITE;
  }
  return GL_READ_WRITE;
}

/// Transfers go from/to client memory: no pixel buffer object may be bound.
/// Float rows are multiples of 4 bytes long, so the default alignment of 4 holds.
void unbind_pixel_buffer(GLenum buffer_target) { glBindBuffer(buffer_target, 0); }

}  // namespace

int channel_count(TextureFormat format) {
  switch (format) {
    case TextureFormat::r32f: return 1;
    case TextureFormat::rg32f: return 2;
    case TextureFormat::rgba32f:
    case TextureFormat::rgba16f:
    case TextureFormat::rgba8:
    case TextureFormat::rgba16: return 4;
  }
  return 4;
}

const char* to_string(TextureFormat format) {
  switch (format) {
    case TextureFormat::r32f: return "r32f";
    case TextureFormat::rg32f: return "rg32f";
    case TextureFormat::rgba32f: return "rgba32f";
    case TextureFormat::rgba16f: return "rgba16f";
    case TextureFormat::rgba8: return "rgba8";
    case TextureFormat::rgba16: return "rgba16";
  }
  return "?";
}

Texture::Texture(TextureFormat format, int width, int height, int depth, int levels, bool array)
    : format_(format), width_(width), height_(height), depth_(depth), levels_(levels), array_(array) {
  const bool three_d = depth > 0;
  if (width < 1 || height < 1 || depth < 0)
    throw std::invalid_argument(fmt::format("Texture: invalid size {}x{}{}", width, height,
                                            three_d ? fmt::format("x{}", depth) : std::string()));
  check_gl_error("Texture: an earlier GL call left an error");
  glCreateTextures(array ? GL_TEXTURE_2D_ARRAY : three_d ? GL_TEXTURE_3D : GL_TEXTURE_2D, 1, &id_);
  if (three_d)
    glTextureStorage3D(id_, levels, internal_format(format), width, height, depth);
  else
    glTextureStorage2D(id_, levels, internal_format(format), width, height);
  glTextureParameteri(id_, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  glTextureParameteri(id_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(id_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id_, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  try {
    check_gl_error(fmt::format("Texture: {} storage {}x{}{}", to_string(format), width, height,
                               three_d ? fmt::format("x{}", depth) : std::string()));
  } catch (...) {
    release();
    throw;
  }
}

Texture Texture::create_2d(TextureFormat format, int width, int height, std::span<const float> data) {
  Texture t(format, width, height, 0);
  upload_or_zero(t, format, data);
  return t;
}

Texture Texture::create_2d_mipmapped(TextureFormat format, int width, int height, std::span<const float> data) {
  Texture t(format, width, height, 0, full_mip_levels(width, height));
  t.upload(data);
  glGenerateTextureMipmap(t.id_);
  check_gl_error("Texture: generating mipmaps");
  return t;
}

Texture Texture::create_2d_array_mipmapped(TextureFormat format, int width, int height, int layers,
                                           std::span<const float> data) {
  if (layers < 1) throw std::invalid_argument(fmt::format("Texture: invalid layer count {}", layers));
  Texture t(format, width, height, layers, full_mip_levels(width, height), true);
  t.upload(data);
  glGenerateTextureMipmap(t.id_);
  check_gl_error("Texture: generating mipmaps of an array texture");
  return t;
}

Texture Texture::create_2d_array(TextureFormat format, int width, int height, int layers) {
  if (layers < 1) throw std::invalid_argument(fmt::format("Texture: invalid layer count {}", layers));
  Texture t(format, width, height, layers, 1, true);
  upload_or_zero(t, format, {});
  return t;
}

void Texture::set_repeat_s(bool repeat) {
  repeat_s_ = repeat;
  glTextureParameteri(id_, GL_TEXTURE_WRAP_S, repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE);
}

Texture Texture::create_3d(TextureFormat format, int width, int height, int depth, std::span<const float> data) {
  if (depth < 1) throw std::invalid_argument(fmt::format("Texture: invalid 3D depth {}", depth));
  Texture t(format, width, height, depth);
  upload_or_zero(t, format, data);
  return t;
}

Texture::~Texture() { release(); }

Texture::Texture(Texture&& other) noexcept
    : id_(std::exchange(other.id_, 0u)),
      format_(other.format_),
      width_(std::exchange(other.width_, 0)),
      height_(std::exchange(other.height_, 0)),
      depth_(std::exchange(other.depth_, 0)),
      levels_(std::exchange(other.levels_, 1)),
      array_(std::exchange(other.array_, false)),
      repeat_s_(std::exchange(other.repeat_s_, false)) {}

Texture& Texture::operator=(Texture&& other) noexcept {
  if (this != &other) {
    release();
    id_ = std::exchange(other.id_, 0u);
    format_ = other.format_;
    width_ = std::exchange(other.width_, 0);
    height_ = std::exchange(other.height_, 0);
    depth_ = std::exchange(other.depth_, 0);
    levels_ = std::exchange(other.levels_, 1);
    array_ = std::exchange(other.array_, false);
    repeat_s_ = std::exchange(other.repeat_s_, false);
  }
  return *this;
}

void Texture::release() noexcept {
  if (id_ != 0) glDeleteTextures(1, &id_);
  id_ = 0;
}

std::size_t Texture::texel_count() const {
  return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * static_cast<std::size_t>(depth());
}

TextureShape Texture::shape() const {
  TextureShape s;
  s.kind = array_    ? TextureShape::Kind::texture_2d_array
           : is_3d() ? TextureShape::Kind::texture_3d
                     : TextureShape::Kind::texture_2d;
  s.format = format_;
  s.width = width_;
  s.height = height_;
  s.depth = depth();
  s.mipmapped = levels_ > 1;
  s.repeat_s = repeat_s_;
  return s;
}

void Texture::upload(std::span<const float> data) {
  if (id_ == 0) throw std::logic_error("Texture::upload on an empty texture");
  if (data.size() != float_count())
    throw std::invalid_argument(fmt::format("Texture::upload: {} floats given, a {} {}x{}x{} texture holds {}",
                                            data.size(), to_string(format_), width_, height_, depth(), float_count()));
  unbind_pixel_buffer(GL_PIXEL_UNPACK_BUFFER);
  if (is_3d())
    glTextureSubImage3D(id_, 0, 0, 0, 0, width_, height_, depth_, pixel_format(format_), GL_FLOAT, data.data());
  else
    glTextureSubImage2D(id_, 0, 0, 0, width_, height_, pixel_format(format_), GL_FLOAT, data.data());
  check_gl_error("Texture::upload");
}

std::vector<float> Texture::read() const {
  if (id_ == 0) throw std::logic_error("Texture::read on an empty texture");
  std::vector<float> out(float_count());
  if (out.size() * sizeof(float) > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max()))
    throw std::length_error("Texture::read: more than 2 GiB in one texture");
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  unbind_pixel_buffer(GL_PIXEL_PACK_BUFFER);
  glGetTextureImage(id_, 0, pixel_format(format_), GL_FLOAT, static_cast<GLsizei>(out.size() * sizeof(float)),
                    out.data());
  check_gl_error("Texture::read");
  return out;
}

void Texture::bind(unsigned unit) const { glBindTextureUnit(unit, id_); }

void Texture::bind_image(unsigned unit, ImageAccess access) const {
  glBindImageTexture(unit, id_, 0, is_3d() ? GL_TRUE : GL_FALSE, 0, access_enum(access), internal_format(format_));
}

}  // namespace zenith::render::gl
