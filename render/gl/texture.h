#pragma once
// Float textures for lookup tables: 2D or 3D, one mip level, linear filtering,
// clamp-to-edge. Needs a current GL 4.5 context (direct state access).
#include <cstddef>
#include <span>
#include <vector>

namespace zenith::render::gl {

/// The *32f/*16f formats are float; rgba8 and rgba16 are unsigned normalized
/// (display values in [0, 1] as 8- or 16-bit integers: what a display shows and
/// a PNG stores). Every format is read and written as floats here.
enum class TextureFormat { r32f, rg32f, rgba32f, rgba16f, rgba8, rgba16 };
/// 1, 2 or 4.
int channel_count(TextureFormat format);
/// "r32f", "rg32f", "rgba32f", "rgba16f", "rgba8", "rgba16" (the GLSL image format qualifier).
const char* to_string(TextureFormat format);
/// GL's sized internal format of `format` (GL_R32F, …, GL_RGBA16).
unsigned internal_format(TextureFormat format);

/// How a compute shader accesses a texture bound as an image.
enum class ImageAccess { read_only, write_only, read_write };

/// What a driver's machine code for a program can depend on in a texture
/// bound to one of its units: the kind, format, filtering and wrap, and
/// whether each size is a power of two (Mesa's llvmpipe keys a program's
/// code by these; render/gl/first_dispatch_warmup.h makes stand-ins so shaped).
struct TextureShape {
  enum class Kind { texture_2d, texture_2d_array, texture_3d };
  Kind kind = Kind::texture_2d;
  TextureFormat format = TextureFormat::rgba32f;
  int width = 1, height = 1;
  int depth = 1;           ///< a 3D texture's depth, an array's layers
  bool mipmapped = false;  ///< a full mipmap chain, trilinear filtering
  bool repeat_s = false;   ///< GL_REPEAT in s, else clamped to the edge
  bool operator==(const TextureShape&) const = default;
};

class Texture {
 public:
  /// `data`: empty (the texture is zero-filled) or width·height·channels floats,
  /// x fastest, then y. Throws std::invalid_argument on a bad size and
  /// std::runtime_error when GL refuses the storage (too large, out of memory).
  static Texture create_2d(TextureFormat format, int width, int height, std::span<const float> data = {});
  /// A 2D texture with a full mipmap chain (trilinear filtering), built from
  /// level 0 `data` (width·height·channels floats): albedo maps seen from far away.
  static Texture create_2d_mipmapped(TextureFormat format, int width, int height, std::span<const float> data);
  /// A 2D array texture of `layers` layers (width·height·layers·channels floats,
  /// layer after layer), with a full mipmap chain per layer (sampler2DArray).
  static Texture create_2d_array_mipmapped(TextureFormat format, int width, int height, int layers,
                                           std::span<const float> data);
  /// A 2D array texture of `layers` layers, one level, bilinear filtering,
  /// zero-filled: tables a shader fills (image2DArray) and others sample.
  static Texture create_2d_array(TextureFormat format, int width, int height, int layers);
  /// Same for 3D: width·height·depth·channels floats, x fastest, then y, then z.
  static Texture create_3d(TextureFormat format, int width, int height, int depth, std::span<const float> data = {});

  Texture() = default;  ///< no texture (id 0)
  ~Texture();
  Texture(Texture&& other) noexcept;
  Texture& operator=(Texture&& other) noexcept;
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;

  /// Replaces the whole contents; `data.size()` must equal float_count().
  void upload(std::span<const float> data);
  /// The whole contents (layout as in create_2d/create_3d). Issues
  /// glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT) first, so image stores of
  /// earlier dispatches are visible.
  std::vector<float> read() const;

  /// Binds for sampling (sampler2D / sampler3D) on texture unit `unit`.
  void bind(unsigned unit) const;
  /// Binds level 0 as an image (image2D / image3D, all layers) on image unit `unit`
  /// with this texture's format.
  void bind_image(unsigned unit, ImageAccess access) const;

  /// Wrap mode of the s (x) coordinate: repeat (longitude of an equirectangular
  /// map) or clamp to edge (the default).
  void set_repeat_s(bool repeat);

  unsigned id() const { return id_; }
  TextureFormat format() const { return format_; }
  bool is_3d() const { return depth_ > 0; }
  int width() const { return width_; }
  int height() const { return height_; }
  int depth() const { return depth_ > 0 ? depth_ : 1; }
  std::size_t texel_count() const;
  TextureShape shape() const;
  std::size_t float_count() const { return texel_count() * static_cast<std::size_t>(channel_count(format_)); }

 private:
  Texture(TextureFormat format, int width, int height, int depth, int levels = 1, bool array = false);
  void release() noexcept;

  unsigned id_ = 0;
  TextureFormat format_ = TextureFormat::rgba32f;
  int width_ = 0, height_ = 0, depth_ = 0;  // depth_ == 0: a 2D texture
  int levels_ = 1;
  bool array_ = false;
  bool repeat_s_ = false;
};

}  // namespace zenith::render::gl
