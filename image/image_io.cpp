// Reading images: the format is told by the file's magic bytes, not its name.
//
// PNG (libpng): every colour type and bit depth is expanded to 8- or 16-bit RGB
// (palette → RGB, 1/2/4-bit grey → 8-bit, grey → RGB), alpha and tRNS are
// dropped, interlaced files are de-interlaced. The values are taken as sRGB
// (whatever gAMA/iCCP chunks say: albedo maps are authored in sRGB) and decoded
// with the exact IEC 61966-2-1 curve (srgb_decode) from v / 255 or v / 65535.
//
// OpenEXR: the first part's data window; R, G and B channels (all three), or
// else a Y channel (grey); half, float or uint, converted to float by OpenEXR;
// values as stored (linear).
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "image/image_io.h"
#include "image/png_support.h"
#include "image/tone_mapping.h"

namespace zenith::image {
namespace {

constexpr long long kMaxSide_px = 32768;
constexpr png_alloc_size_t kMaxChunkBytes = 16u << 20;  ///< largest ancillary PNG chunk read
constexpr double kMaxDeflateRatio = 1100.0;             ///< above deflate's ~1032:1 limit

/// An error this reader diagnosed itself; its message already names the file.
struct ReadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

ReadError error(const std::filesystem::path& path, const std::string& reason) {
  return ReadError(path.string() + ": " + reason);
}

void check_size(const std::filesystem::path& path, long long width, long long height) {
  if (width < 1 || height < 1)
    throw error(path, "empty image (" + std::to_string(width) + "x" + std::to_string(height) + " px)");
  if (width > kMaxSide_px || height > kMaxSide_px)
    throw error(path, "image of " + std::to_string(width) + "x" + std::to_string(height) + " px is larger than the " +
                          std::to_string(kMaxSide_px) + " px per side this reader accepts");
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// ---------------------------------------------------------------- PNG

/// png_rw_ptr reading from the FILE*; a short read is a libpng error.
void read_from_file(png_structp png, png_bytep data, std::size_t length) {
  auto* file = static_cast<std::FILE*>(png_get_io_ptr(png));
  if (std::fread(data, 1, length, file) != length)
    png_error(png, std::ferror(file) ? "read error" : "truncated (unexpected end of file)");
}

/// Walks the PNG chunk list (PNG specification, section 5.3: length (4 bytes, big
/// endian, ≤ 2³¹ − 1), type, data, CRC) up to IEND before libpng reads it: libpng
/// allocates an ancillary chunk whole from its length field, and treats an
/// oversized length only as a warning, so a corrupt length could make it
/// allocate gigabytes. Every chunk must lie within the file.
void check_png_chunk_bounds(const std::filesystem::path& path, std::FILE* file) {
  std::error_code ec;
  const auto file_size = static_cast<long long>(std::filesystem::file_size(path, ec));
  if (ec) throw error(path, "cannot read its size: " + ec.message());
  long long position = 8;  // after the signature
  while (true) {
    std::array<unsigned char, 8> header{};
    if (std::fseek(file, long(position), SEEK_SET) != 0 || std::fread(header.data(), 1, 8, file) != 8)
      throw error(path, "PNG: truncated (no IEND chunk)");
    const long long length = (long long)header[0] << 24 | header[1] << 16 | header[2] << 8 | header[3];
    const std::string type(header.begin() + 4, header.end());
    if (length > 0x7fffffffLL || position + 12 + length > file_size)
      throw error(path, "PNG: truncated (chunk at byte " + std::to_string(position) + " claims " +
                            std::to_string(length) + " bytes, " + std::to_string(file_size - position - 12) +
                            " remain in the file)");
    if (type == "IEND") break;
    position += 12 + length;
  }
  if (std::fseek(file, 8, SEEK_SET) != 0) throw error(path, "cannot seek");
}

/// Owns libpng's read state.
struct PngReadState {
  png_structp png = nullptr;
  png_infop info = nullptr;
  detail::PngErrorState errors;
  ~PngReadState() {
    if (png) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
  }
};

/// Decoding table: code value → linear, for 8-bit (256 entries) or 16-bit (65536) samples.
std::vector<float> srgb_decode_table(int bit_depth) {
  const int codes = 1 << bit_depth;
  std::vector<float> table(std::size_t(codes), 0.0f);
  for (int v = 0; v < codes; ++v) table[std::size_t(v)] = srgb_decode(float(double(v) / double(codes - 1)));
  return table;
}

LinearImage read_png(const std::filesystem::path& path, std::FILE* file_in, std::size_t signature_bytes) {
  PngReadState s;
  s.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &s.errors, detail::png_error_callback,
                                 detail::png_warning_callback);
  if (s.png) s.info = png_create_info_struct(s.png);
  if (!s.png || !s.info) throw error(path, "libpng cannot allocate its state");
  png_structp png = s.png;
  png_infop info = s.info;
  std::FILE* file = file_in;
  const auto fail = [&]() { return error(path, std::string("PNG: ") + s.errors.message); };

  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, colour_type = 0, interlace = 0;
  png_uint_32* width_p = &width;
  png_uint_32* height_p = &height;
  int* bit_depth_p = &bit_depth;
  int* colour_type_p = &colour_type;
  int* interlace_p = &interlace;
  const int signature = static_cast<int>(signature_bytes);
  if (!detail::png_guarded(png, [=] {
        // Cap what libpng allocates for one ancillary chunk, decompressed zTXt, iTXt
        // and iCCP included (a small compressed chunk can inflate to gigabytes);
        // libpng drops a chunk over the cap with a warning.
        png_set_chunk_malloc_max(png, kMaxChunkBytes);
        png_set_read_fn(png, file, read_from_file);
        png_set_sig_bytes(png, signature);
        png_read_info(png, info);
        png_get_IHDR(png, info, width_p, height_p, bit_depth_p, colour_type_p, interlace_p, nullptr, nullptr);
      }))
    throw fail();
  check_size(path, width, height);
  // Deflate compresses at most ~1032:1, so a file too small for the image its
  // header claims is truncated — said before allocating for the claimed size.
  {
    const int channels = png_get_channels(png, info);
    const double raw_bytes = double(height) * (1.0 + std::ceil(double(width) * channels * bit_depth / 8.0));
    std::error_code ec;
    const double file_bytes = double(std::filesystem::file_size(path, ec));
    if (!ec && raw_bytes > kMaxDeflateRatio * file_bytes)
      throw error(path, "PNG: truncated (" + std::to_string(std::uintmax_t(file_bytes)) + " bytes cannot hold a " +
                            std::to_string(width) + "x" + std::to_string(height) + " image)");
  }

  int passes = 1;
  int* passes_p = &passes;
  std::size_t row_bytes = 0;
  std::size_t* row_bytes_p = &row_bytes;
  if (!detail::png_guarded(png, [=] {
        if (colour_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
        if (colour_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
        if (colour_type == PNG_COLOR_TYPE_GRAY || colour_type == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
        if (colour_type & PNG_COLOR_MASK_ALPHA) png_set_strip_alpha(png);
        *passes_p = png_set_interlace_handling(png);
        png_read_update_info(png, info);
        *row_bytes_p = png_get_rowbytes(png, info);
      }))
    throw fail();
  const int sample_bytes = bit_depth == 16 ? 2 : 1;  // palette and low-bit grey are now 8-bit
  const std::size_t row_samples = std::size_t(width) * 3;
  if (row_bytes != row_samples * std::size_t(sample_bytes))
    throw error(path, "PNG: unexpected row layout after expansion to RGB (" + std::to_string(row_bytes) + " bytes)");

  LinearImage image;
  image.width = int(width);
  image.height = int(height);
  image.rgb.resize(row_samples * height);
  const std::vector<float> decode = srgb_decode_table(8 * sample_bytes);
  // Non-interlaced files are converted row by row; interlaced ones need the whole
  // image in bytes while libpng fills in the passes.
  std::vector<png_byte> bytes(row_bytes * (passes > 1 ? std::size_t(height) : 1));
  std::vector<png_bytep> row_pointers(passes > 1 ? std::size_t(height) : 0);
  for (std::size_t y = 0; y < row_pointers.size(); ++y) row_pointers[y] = bytes.data() + y * row_bytes;

  png_bytep byte_data = bytes.data();
  png_bytepp rows = row_pointers.data();
  float* out = image.rgb.data();
  const float* table = decode.data();
  const auto convert_row = [=](const png_byte* in, float* row_out) {
    for (std::size_t k = 0; k < row_samples; ++k) {
      const unsigned code =
          sample_bytes == 2 ? (unsigned(in[2 * k]) << 8) | unsigned(in[2 * k + 1]) : unsigned(in[k]);  // big endian
      row_out[k] = table[code];
    }
  };
  if (!detail::png_guarded(png, [=] {
        if (passes > 1) {
          png_read_image(png, rows);
          for (png_uint_32 y = 0; y < height; ++y) convert_row(rows[y], out + std::size_t(y) * row_samples);
        } else {
          for (png_uint_32 y = 0; y < height; ++y) {
            png_read_row(png, byte_data, nullptr);
            convert_row(byte_data, out + std::size_t(y) * row_samples);
          }
        }
        png_read_end(png, nullptr);  // checks the rest of the file up to IEND
      }))
    throw fail();
  return image;
}

// ---------------------------------------------------------------- OpenEXR

/// Scanlines per chunk for each OpenEXR compression (ImfCompression.h order:
/// NONE, RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A, DWAA, DWAB); 0 if unknown.
int exr_lines_per_chunk(int compression) {
  constexpr std::array<int, 10> lines{1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
  return compression >= 0 && compression < int(lines.size()) ? lines[std::size_t(compression)] : 0;
}

/// The value size of OpenEXR's fixed-size attribute types (ImfStandardAttributes.h,
/// ImfTypedAttribute.h); 0 for variable-size or unknown types.
int exr_fixed_attribute_size(const std::string& type) {
  static constexpr std::pair<std::string_view, int> kSizes[] = {{"box2i", 16},
                                                                {"box2f", 16},
                                                                {"chromaticities", 32},
                                                                {"compression", 1},
                                                                {"deepImageState", 1},
                                                                {"double", 8},
                                                                {"envmap", 1},
                                                                {"float", 4},
                                                                {"int", 4},
                                                                {"keycode", 28},
                                                                {"lineOrder", 1},
                                                                {"m33f", 36},
                                                                {"m33d", 72},
                                                                {"m44f", 64},
                                                                {"m44d", 128},
                                                                {"rational", 8},
                                                                {"tiledesc", 9},
                                                                {"timecode", 8},
                                                                {"v2i", 8},
                                                                {"v2f", 8},
                                                                {"v2d", 16},
                                                                {"v3i", 12},
                                                                {"v3f", 12},
                                                                {"v3d", 24}};
  for (const auto& [name, size] : kSizes)
    if (type == name) return size;
  return 0;
}

/// Walks an EXR file's structure before OpenEXR reads it. OpenEXR allocates an
/// attribute's value, and a chunk's buffer, from size fields in the file before
/// it notices the file is too short, so one corrupt size field could make it
/// allocate gigabytes. Layout (OpenEXR, "OpenEXR File Layout"): magic, version
/// (flags: 0x200 tiled, 0x800 deep, 0x1000 multi-part), header(s) of attributes
/// `name\0 type\0 int32 size, value` each ended by `\0` (multi-part: ended by
/// an empty header), the chunk offset table (uint64 per chunk), the chunks
/// (scanline: int32 y, int32 data size, data). Checked here: every attribute
/// size lies within the file and agrees with the attribute's type (fixed-size
/// types, channel lists and previews are parsed by content, as OpenEXR does, so
/// both walk the header alike), every data window fits the size limit, and, for
/// single-part scanline files (what the writers produce, and most albedo maps),
/// every chunk a valid offset points at lies within the file. Offsets that do
/// not point into the file are left to OpenEXR (it reports the file incomplete).
void check_exr_structure(const std::filesystem::path& path, std::FILE* file) {
  std::error_code ec;
  const auto file_size = static_cast<long long>(std::filesystem::file_size(path, ec));
  if (ec) throw error(path, "cannot read its size: " + ec.message());
  const auto fail = [&](const std::string& what) { return error(path, "OpenEXR: corrupt file: " + what); };
  std::array<unsigned char, 8> start{};
  if (std::fseek(file, 0, SEEK_SET) != 0 || std::fread(start.data(), 1, 8, file) != 8) throw fail("truncated header");
  const bool tiled = (start[5] & 0x02) != 0, deep = (start[5] & 0x08) != 0, multi_part = (start[5] & 0x10) != 0;
  const auto read_string = [&](const char* what) {
    std::string text;
    for (int c = std::fgetc(file); c != 0; c = std::fgetc(file)) {
      if (c == EOF) throw fail(std::string("truncated in ") + what);
      if (text.size() >= 255) throw fail(std::string(what) + " longer than 255 characters");
      text.push_back(static_cast<char>(c));
    }
    return text;
  };
  const auto read_le = [&](int bytes) {
    std::array<unsigned char, 8> b{};
    if (std::fread(b.data(), 1, std::size_t(bytes), file) != std::size_t(bytes)) throw fail("truncated");
    std::uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = v << 8 | b[std::size_t(i)];
    return v;
  };
  const auto read_int32 = [&] { return static_cast<std::int32_t>(static_cast<std::uint32_t>(read_le(4))); };

  long long first_y = 0, last_y = -1;  // of the first part's data window
  int compression = -1;
  for (int part = 0;; ++part) {
    int attributes = 0;
    for (std::string name = read_string("an attribute name"); !name.empty(); name = read_string("an attribute name")) {
      ++attributes;
      const std::string type = read_string("an attribute type");
      const std::int32_t size = read_int32();
      const long long remaining = file_size - static_cast<long long>(std::ftell(file));
      if (size < 0 || size > remaining)
        throw fail("attribute '" + name + "' claims " + std::to_string(size) + " bytes, " + std::to_string(remaining) +
                   " remain in the file");
      // OpenEXR reads known types by their content, not by the size field: a size
      // that disagrees with the content would make it parse differently from here.
      if (const int expected = exr_fixed_attribute_size(type); expected > 0 && size != expected)
        throw fail("attribute '" + name + "' of type " + type + " has " + std::to_string(size) + " bytes, not " +
                   std::to_string(expected));
      if (type == "chlist") {  // per channel: name\0, int32 type, uint8 linear, 3 reserved, int32 × 2 sampling
        const long long value_start = std::ftell(file);
        while (!read_string("a channel name").empty())
          if (std::fseek(file, 16, SEEK_CUR) != 0) throw fail("truncated");
        if (std::ftell(file) - value_start != size) throw fail("channel list '" + name + "' disagrees with its size");
      } else if (type == "preview") {  // uint32 width, uint32 height, RGBA8 pixels
        const std::uint64_t w = read_le(4), h = read_le(4);
        if (8 + 4 * w * h != std::uint64_t(size)) throw fail("preview image disagrees with its size");
        if (std::fseek(file, size - 8, SEEK_CUR) != 0) throw fail("truncated");
      } else if (name == "dataWindow" && type == "box2i" && size == 16) {
        const long long x0 = read_int32(), y0 = read_int32(), x1 = read_int32(), y1 = read_int32();
        check_size(path, x1 - x0 + 1, y1 - y0 + 1);
        if (part == 0) first_y = y0, last_y = y1;
      } else if (name == "compression" && type == "compression" && size == 1) {
        const int value = std::fgetc(file);
        if (part == 0) compression = value;
      } else if (std::fseek(file, size, SEEK_CUR) != 0) {
        throw fail("truncated");
      }
    }
    if (!multi_part || attributes == 0) break;
  }
  const int lines = exr_lines_per_chunk(compression);
  if (multi_part || tiled || deep || lines == 0 || last_y < first_y) return;  // OpenEXR checks the rest

  const long long chunks = (last_y - first_y + lines) / lines;
  const long long table_start = std::ftell(file), table_end = table_start + 8 * chunks;
  if (table_end > file_size) throw fail("truncated in the offset table");
  std::vector<std::uint64_t> offsets(static_cast<std::size_t>(chunks));
  for (auto& offset : offsets) offset = read_le(8);
  for (const std::uint64_t offset : offsets) {
    if (offset < std::uint64_t(table_end) || offset + 8 > std::uint64_t(file_size)) continue;  // left to OpenEXR
    if (std::fseek(file, long(offset) + 4, SEEK_SET) != 0) throw fail("cannot seek");
    const std::int32_t size = read_int32();
    if (size < 0 || std::uint64_t(size) > std::uint64_t(file_size) - offset - 8)
      throw fail("truncated (chunk at byte " + std::to_string(offset) + " claims " + std::to_string(size) + " bytes, " +
                 std::to_string(std::uint64_t(file_size) - offset - 8) + " remain in the file)");
  }
}

std::string channel_names(const Imf::ChannelList& channels) {
  std::string names;
  for (auto it = channels.begin(); it != channels.end(); ++it)
    names += (names.empty() ? "" : ", ") + std::string(it.name());
  return names.empty() ? "none" : names;
}

LinearImage read_exr(const std::filesystem::path& path) {
  LinearImage image;
  bool grey = false;
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i window = header.dataWindow();
    const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
    check_size(path, width, height);
    const Imf::ChannelList& channels = header.channels();
    const bool has_rgb = channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
    const std::array<const char*, 3> wanted =
        has_rgb ? std::array<const char*, 3>{"R", "G", "B"} : std::array<const char*, 3>{"Y", nullptr, nullptr};
    grey = !has_rgb;
    if (grey && !channels.findChannel("Y"))
      throw error(path, "OpenEXR: no R, G, B or Y channel (channels: " + channel_names(channels) + ")");
    for (const char* name : wanted) {
      if (!name) continue;
      const Imf::Channel* channel = channels.findChannel(name);
      if (!channel)
        throw error(
            path, std::string("OpenEXR: channel ") + name + " is missing (channels: " + channel_names(channels) + ")");
      if (channel->xSampling != 1 || channel->ySampling != 1)
        throw error(path, std::string("OpenEXR: channel ") + name + " is subsampled, which is not supported");
    }
    if (!file.isComplete()) throw error(path, "OpenEXR: truncated (pixel data incomplete)");

    image.width = int(width);
    image.height = int(height);
    image.rgb.assign(std::size_t(width) * std::size_t(height) * 3, 0.0f);
    Imf::FrameBuffer frame;
    const std::size_t x_stride = 3 * sizeof(float), y_stride = x_stride * std::size_t(width);
    for (int c = 0; c < 3; ++c)
      if (wanted[std::size_t(c)])
        frame.insert(wanted[std::size_t(c)],
                     Imf::Slice::Make(Imf::FLOAT, image.rgb.data() + c, window, x_stride, y_stride));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
  } catch (const ReadError&) {
    throw;
  } catch (const std::exception& e) {  // Iex::BaseExc (derives from std::exception only), std::bad_alloc
    throw error(path, std::string("OpenEXR: ") + e.what());
  }
  if (grey)  // Y was read into R
    for (std::size_t k = 0; k < image.rgb.size(); k += 3) image.rgb[k + 1] = image.rgb[k + 2] = image.rgb[k];
  return image;
}

}  // namespace

LinearImage read_image(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw error(path, "is a directory, not an image file");
  File file(std::fopen(path.c_str(), "rb"));
  if (!file)
    throw error(path,
                errno == ENOENT ? std::string("no such file") : std::string("cannot open: ") + std::strerror(errno));
  std::array<unsigned char, 8> magic{};
  const std::size_t got = std::fread(magic.data(), 1, magic.size(), file.get());
  if (got == 0) throw error(path, "empty file, not an image");
  static constexpr std::array<unsigned char, 8> kPngSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static constexpr std::array<unsigned char, 4> kExrMagic{0x76, 0x2f, 0x31, 0x01};  // 20000630, little endian
  if (got == 8 && magic == kPngSignature) {
    check_png_chunk_bounds(path, file.get());
    return read_png(path, file.get(), got);
  }
  if (got >= 4 && std::equal(kExrMagic.begin(), kExrMagic.end(), magic.begin())) {
    check_exr_structure(path, file.get());
    file.reset();
    return read_exr(path);
  }
  if (got < 8 && std::equal(magic.begin(), magic.begin() + long(got), kPngSignature.begin()))
    throw error(path, "PNG: truncated (" + std::to_string(got) + " bytes)");
  throw error(path, "not a PNG or OpenEXR file (unrecognised magic bytes)");
}

}  // namespace zenith::image
