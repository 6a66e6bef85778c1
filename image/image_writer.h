#pragma once
// Writing rendered frames: linear HDR OpenEXR and 8-bit sRGB PNG previews; and
// 16-bit greyscale PNG maps (write_png_grey16).
// Writers stream rows (top to bottom) so an 8192² frame never needs a second
// full copy in memory, and publish the file atomically: they write NAME.partial
// and rename it to NAME in finish(), so an interrupted render never leaves a
// truncated file under the final name.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "image/tone_mapping.h"

namespace zenith::image {

enum class ExrPixelType { half, float32 };
/// "half", "float"; parse throws std::invalid_argument naming the allowed values.
const char* to_string(ExrPixelType type);
ExrPixelType parse_exr_pixel_type(const std::string& text);

/// Key–value text stored with the image (EXR string attributes, PNG tEXt chunks),
/// e.g. {"zenith:scene", "earth-moon"}, {"zenith:units", "..."}.
using ImageAttributes = std::vector<std::pair<std::string, std::string>>;

class ImageWriter {
 public:
  virtual ~ImageWriter() = default;  ///< without finish(): removes the .partial file
  int width() const { return width_; }
  int height() const { return height_; }
  /// Appends `row_count` rows of linear RGB floats (width · row_count · 3, x
  /// fastest). Rows come in order, top first; throws std::logic_error on more
  /// rows than the image has, std::runtime_error on an I/O error (naming the file).
  virtual void write_rows(int row_count, std::span<const float> rgb) = 0;
  /// Completes the file and renames it into place; throws std::logic_error unless every
  /// row was written (or when called twice), std::runtime_error on an I/O error.
  virtual void finish() = 0;

 protected:
  ImageWriter(int width, int height) : width_(width), height_(height) {}

 private:
  int width_, height_;
};

/// Linear RGB as given (values are stored, not tone mapped; NaN/Inf are
/// rejected with std::runtime_error naming the pixel; half clamps |x| to 65504,
/// the largest finite half, and logs how many values it clamped). Scanlines, ZIP
/// compression, rows handed to OpenEXR in 16-row chunks. Sides 1..32768 px and
/// attribute names that clash with the standard EXR attributes throw std::invalid_argument.
std::unique_ptr<ImageWriter> open_exr_writer(const std::filesystem::path& path, int width, int height,
                                             ExrPixelType type, const ImageAttributes& attributes = {});
/// 8-bit sRGB: each value goes through `tone` (tone_mapping.h) then the sRGB
/// transfer function, with ordered dithering off (deterministic bytes): the byte is
/// display_byte(value, tone). Attributes become tEXt chunks (iTXt for non-ASCII
/// values); names must be PNG keywords (1–79 printable ASCII, std::invalid_argument otherwise).
std::unique_ptr<ImageWriter> open_png_writer(const std::filesystem::path& path, int width, int height, ToneMapping tone,
                                             const ImageAttributes& attributes = {});

/// Convenience: a whole image at once (rgb = width · height · 3 floats).
void write_exr(const std::filesystem::path& path, int width, int height, std::span<const float> rgb, ExrPixelType type,
               const ImageAttributes& attributes = {});
void write_png(const std::filesystem::path& path, int width, int height, std::span<const float> rgb, ToneMapping tone,
               const ImageAttributes& attributes = {});

/// A 16-bit greyscale PNG of samples already encoded (width · height values,
/// row 0 at the top, x fastest), e.g. a projector's blend mask or black-level
/// map: no tone mapping, no transfer function applied here. `gamma` states the
/// encoding in a gAMA chunk of 1 / gamma: 1 for samples proportional to linear
/// light (value = sample / 65535), 2.2 for samples holding value^(1 / 2.2);
/// in (0, 10]. Published atomically like the writers above; throws
/// std::invalid_argument for a bad size, sample count, gamma or attribute name,
/// std::runtime_error naming the file when it cannot be created or written.
void write_png_grey16(const std::filesystem::path& path, int width, int height, std::span<const std::uint16_t> grey,
                      double gamma, const ImageAttributes& attributes = {});

}  // namespace zenith::image
