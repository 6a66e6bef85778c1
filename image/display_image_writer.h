#pragma once
// Frame files from pixels already display-encoded — the codes of the GPU's
// display pass (render/display/display_encoder.h: tone mapping, output stage,
// sRGB encoding, quantization), read back as RGBA: 8- or 16-bit PNG and 16-bit
// TIFF, the formats planetarium studios deliver fulldome masters in
// (docs/shows.md, "Output formats"). Nothing is converted here but the byte
// order and the dropped alpha: the stored codes are the display pass's.
//
// Each file is published atomically as image_writer.h's are (NAME.partial,
// renamed to NAME when complete); an I/O error (a full disk, a folder that
// cannot be written) throws std::runtime_error naming the file and the reason.
#include <cstddef>
#include <filesystem>
#include <span>
#include <string>

#include "image/image_writer.h"

namespace zenith::image {

/// zlib level of the "fast" PNG setting: level 1 with the Sub filter alone
/// (about 3× less CPU than libpng's default level 6 with adaptive filters, for
/// files 10–30 % larger on skies).
inline constexpr int kFastPngCompression = 1;
inline constexpr int kDefaultPngCompression = 6;  ///< libpng's default level (adaptive filters from 4 up)
/// "fast" (1), "default" (6), "best" (9) or a level 0–9; throws
/// std::invalid_argument naming --png-compression and the allowed values.
int parse_png_compression(const std::string& text);

/// An RGB PNG of `bits` (8 or 16) bits a sample with an sRGB chunk and the
/// attributes as text chunks, from `rgba`: width · height pixels of 4 samples
/// (alpha ignored), rows top first, 16-bit samples in this machine's byte
/// order. `compression_level` 0–9 (kFastPngCompression: the Sub filter only;
/// from 4 up libpng's adaptive filters). Throws std::invalid_argument for bad
/// sizes, bit depths, levels or attribute names.
void write_png_display(const std::filesystem::path& path, int width, int height, int bits,
                       std::span<const std::byte> rgba, int compression_level, const ImageAttributes& attributes = {});

enum class TiffCompression { none, deflate, lzw };
/// "none", "deflate", "lzw"; parse throws std::invalid_argument naming --tiff-compression.
const char* to_string(TiffCompression compression);
TiffCompression parse_tiff_compression(const std::string& text);

/// A 16-bit RGB TIFF (libtiff: strips of 8 rows, contiguous RGB, the horizontal
/// predictor with deflate and LZW, deflate at zlib level 1) from `rgba`:
/// width · height pixels of 4 16-bit samples in this machine's byte order,
/// alpha ignored, rows top first. The attributes go into the ImageDescription
/// tag as "name=value" lines; Software is "zenith". The samples are the
/// display codes (sRGB encoded), as the PNGs'.
void write_tiff16_display(const std::filesystem::path& path, int width, int height, std::span<const std::uint16_t> rgba,
                          TiffCompression compression, const ImageAttributes& attributes = {});

}  // namespace zenith::image
