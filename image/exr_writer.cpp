// Linear HDR frames as OpenEXR: R, G, B channels (half or float), scanlines,
// ZIP compression, streamed through OpenEXR's scanline API.
//
// Compression: ZIP (zlib over 16-scanline blocks, after OpenEXR's byte
// reordering and delta predictor) for both pixel types. It is lossless,
// deterministic, decodes fast, and does well on what the renderer writes —
// smooth sky gradients and flat black space; PIZ (wavelet) compresses noisy
// photographic half data better but gains little here and uses 32-line blocks.
//
// Memory: rows are validated, converted and handed to OpenEXR in chunks of
// kChunkRows = 16 rows (one ZIP block) through a staging buffer of
// width · 16 · 3 values, so the writer holds O(width) memory however many rows a
// call passes; OpenEXR itself buffers one block.
#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStdIO.h>
#include <ImfStringAttribute.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "image/image_writer.h"
#include "image/writer_support.h"

namespace zenith::image {
namespace {

constexpr int kChunkRows = 16;               ///< rows per hand-over to OpenEXR (= one ZIP block)
constexpr long long kMaxSide_px = 32768;     ///< as read_image accepts
constexpr float kHalfMax = 65504.0f;         ///< largest finite half; larger magnitudes are clamped to it
constexpr std::size_t kMaxNameLength = 255;  ///< OpenEXR's attribute-name limit (long names)

const char* channel_name(int c) { return c == 0 ? "R" : c == 1 ? "G" : "B"; }

class ExrWriter final : public ImageWriter {
 public:
  ExrWriter(const std::filesystem::path& path, int width, int height, ExrPixelType type,
            const ImageAttributes& attributes)
      : ImageWriter(width, height), path_(path), partial_(detail::partial_path_for(path)), type_(type) {
    try {
      Imf::Header header(width, height);
      header.compression() = Imf::ZIP_COMPRESSION;
      header.lineOrder() = Imf::INCREASING_Y;
      const Imf::PixelType pixel_type = type == ExrPixelType::half ? Imf::HALF : Imf::FLOAT;
      for (int c = 0; c < 3; ++c) header.channels().insert(channel_name(c), Imf::Channel(pixel_type));
      Imf::addChromaticities(header, Imf::Chromaticities());  // Rec. 709 primaries, D65: linear sRGB
      for (const auto& [name, value] : attributes) {
        if (name.empty() || name.size() > kMaxNameLength)
          throw std::invalid_argument(detail::prefix(path_) + "attribute name '" + name + "' must have 1 to " +
                                      std::to_string(kMaxNameLength) + " characters");
        if (header.find(name) != header.end())
          throw std::invalid_argument(detail::prefix(path_) + "attribute '" + name +
                                      "' is already set by the writer (standard EXR attribute or given twice)");
        header.insert(name, Imf::StringAttribute(value));
      }
      stream_.open(partial_, std::ios::binary | std::ios::trunc);
      if (!stream_) throw std::runtime_error(detail::prefix(path_) + "cannot create " + partial_.string());
      created_ = true;
      imf_stream_ = std::make_unique<Imf::StdOFStream>(stream_, partial_.c_str());
      file_ = std::make_unique<Imf::OutputFile>(*imf_stream_, header);
      if (type_ == ExrPixelType::half)
        half_rows_.resize(std::size_t(width) * kChunkRows * 3);
      else
        float_rows_.resize(std::size_t(width) * kChunkRows * 3);
    } catch (const std::logic_error&) {  // our argument checks (std::invalid_argument)
      abandon();
      throw;
    } catch (const std::runtime_error&) {  // ours, already naming the file
      abandon();
      throw;
    } catch (const std::exception& e) {  // OpenEXR's (Iex::BaseExc derives from std::exception only)
      abandon();
      throw std::runtime_error(detail::prefix(path_) + "OpenEXR: " + e.what());
    }
  }

  ~ExrWriter() override {
    if (!finished_) abandon();
  }

  void write_rows(int row_count, std::span<const float> rgb) override {
    detail::check_row_block(path_, width(), height(), rows_written_, row_count, rgb.size(), open());
    // Validate the whole block first, so a rejected call writes nothing.
    const std::size_t row_values = std::size_t(width()) * 3;
    for (std::size_t k = 0; k < rgb.size(); ++k)
      if (!std::isfinite(rgb[k])) {
        const std::size_t x = (k % row_values) / 3, y = std::size_t(rows_written_) + k / row_values;
        throw std::runtime_error(detail::prefix(path_) + "pixel (x " + std::to_string(x) + ", y " + std::to_string(y) +
                                 ") channel " + channel_name(int(k % 3)) + " is " +
                                 (std::isnan(rgb[k]) ? "NaN" : "infinite") + "; EXR frames must be finite");
      }
    try {
      for (int done = 0; done < row_count; done += kChunkRows) {
        const int rows = std::min(kChunkRows, row_count - done);
        write_chunk(rows, rgb.subspan(std::size_t(done) * row_values, std::size_t(rows) * row_values));
      }
    } catch (const std::exception& e) {
      failed_ = true;
      throw std::runtime_error(detail::prefix(path_) + "writing " + partial_.string() + ": " + e.what());
    }
  }

  void finish() override {
    detail::check_complete(path_, height(), rows_written_, open());
    // Destroying the OutputFile writes the scanline offset table; OpenEXR's
    // destructor swallows I/O errors, so they are detected on our own stream.
    file_.reset();
    imf_stream_.reset();
    stream_.close();
    if (stream_.fail()) {
      failed_ = true;
      throw std::runtime_error(detail::prefix(path_) + "error writing " + partial_.string());
    }
    detail::publish(partial_, path_);
    finished_ = true;
    if (clamped_values_ > 0)
      spdlog::warn("{}: {} values beyond the half-float range were clamped to ±{}", path_.string(), clamped_values_,
                   kHalfMax);
  }

 private:
  bool open() const { return !finished_ && !failed_; }

  /// Converts `rows` rows into the staging buffer and hands them to OpenEXR. The
  /// slices are addressed in absolute image rows, so their origin is the chunk's first row.
  void write_chunk(int rows, std::span<const float> rgb) {
    const bool half = type_ == ExrPixelType::half;
    if (half) {
      for (std::size_t k = 0; k < rgb.size(); ++k) {
        const float v = std::clamp(rgb[k], -kHalfMax, kHalfMax);
        clamped_values_ += v != rgb[k];
        half_rows_[k] = Imath::half(v);  // round to nearest even
      }
    } else {
      std::copy(rgb.begin(), rgb.end(), float_rows_.begin());
    }
    const std::size_t value_size = half ? sizeof(Imath::half) : sizeof(float);
    const char* base =
        half ? reinterpret_cast<const char*>(half_rows_.data()) : reinterpret_cast<const char*>(float_rows_.data());
    Imf::FrameBuffer frame;
    for (int c = 0; c < 3; ++c)
      frame.insert(channel_name(c), Imf::Slice::Make(half ? Imf::HALF : Imf::FLOAT, base + std::size_t(c) * value_size,
                                                     Imath::V2i(0, rows_written_), width(), rows, 3 * value_size,
                                                     3 * value_size * std::size_t(width())));
    file_->setFrameBuffer(frame);
    file_->writePixels(rows);
    rows_written_ += rows;
  }

  /// Closes everything and removes the partial file; never throws.
  void abandon() noexcept {
    try {
      file_.reset();  // OpenEXR's destructor catches its own errors
    } catch (...) {
    }
    imf_stream_.reset();
    if (stream_.is_open()) stream_.close();
    if (created_) detail::discard(partial_);  // never a NAME.partial this writer did not create
  }

  std::filesystem::path path_, partial_;
  ExrPixelType type_;
  // Destroyed in reverse order: the OutputFile, then its stream adapter, then the stream.
  std::ofstream stream_;
  std::unique_ptr<Imf::StdOFStream> imf_stream_;
  std::unique_ptr<Imf::OutputFile> file_;
  std::vector<Imath::half> half_rows_;  ///< staging for ExrPixelType::half
  std::vector<float> float_rows_;       ///< staging for ExrPixelType::float32
  int rows_written_ = 0;
  bool created_ = false, finished_ = false, failed_ = false;
  std::size_t clamped_values_ = 0;
};

}  // namespace

std::unique_ptr<ImageWriter> open_exr_writer(const std::filesystem::path& path, int width, int height,
                                             ExrPixelType type, const ImageAttributes& attributes) {
  detail::check_dimensions(path, width, height, kMaxSide_px);
  detail::check_unique_names(path, attributes);
  return std::make_unique<ExrWriter>(path, width, height, type, attributes);
}

}  // namespace zenith::image
