// Contact sheets (image/contact_sheet.h).
#include "image/contact_sheet.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "image/image_writer.h"

namespace zenith::image {
namespace {

constexpr int kMaxSide_px = 32768;  ///< as read_image and the writers accept
constexpr int kMaxCellHeight_px = 4096;
constexpr int kMaxGap_px = 256;

/// One output sample along an axis: the source pixels [first, first + weights.size()) and their weights (sum 1).
struct Footprint {
  int first = 0;
  std::vector<double> weights;
};

/// The footprints of `target` pixels over `source` pixels: output pixel i
/// covers the source interval [i·s, (i + 1)·s), s = source / target.
std::vector<Footprint> footprints(int source, int target) {
  const double scale = static_cast<double>(source) / target;
  std::vector<Footprint> result(static_cast<std::size_t>(target));
  for (int i = 0; i < target; ++i) {
    const double begin = i * scale, end = (i + 1) * scale;
    const int first = std::min(source - 1, static_cast<int>(std::floor(begin)));
    const int last = std::clamp(static_cast<int>(std::ceil(end)) - 1, first, source - 1);
    Footprint& f = result[static_cast<std::size_t>(i)];
    f.first = first;
    double total = 0.0;
    for (int p = first; p <= last; ++p) {
      const double covered = std::min(end, p + 1.0) - std::max(begin, static_cast<double>(p));
      f.weights.push_back(std::max(covered, 0.0));
      total += f.weights.back();
    }
    for (double& w : f.weights) w /= total;
  }
  return result;
}

void check_side(const char* what, int side) {
  if (side < 1 || side > kMaxSide_px)
    throw std::invalid_argument(fmt::format("downscale_box: {} {} px outside [1, {}]", what, side, kMaxSide_px));
}

}  // namespace

LinearImage downscale_box(const LinearImage& image, int width, int height) {
  check_side("source width", image.width);
  check_side("source height", image.height);
  check_side("width", width);
  check_side("height", height);
  if (image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
    throw std::invalid_argument("downscale_box: the image holds not width · height · 3 values");
  const std::vector<Footprint> fx = footprints(image.width, width), fy = footprints(image.height, height);

  // Rows first (source height × target width), then columns.
  std::vector<double> horizontal(static_cast<std::size_t>(image.height) * width * 3, 0.0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < width; ++x) {
      const Footprint& f = fx[static_cast<std::size_t>(x)];
      for (std::size_t k = 0; k < f.weights.size(); ++k)
        for (int c = 0; c < 3; ++c)
          horizontal[(static_cast<std::size_t>(y) * width + x) * 3 + c] +=
              f.weights[k] * image.rgb[(static_cast<std::size_t>(y) * image.width + f.first + k) * 3 + c];
    }
  LinearImage result{width, height, std::vector<float>(static_cast<std::size_t>(width) * height * 3)};
  for (int y = 0; y < height; ++y) {
    const Footprint& f = fy[static_cast<std::size_t>(y)];
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (std::size_t k = 0; k < f.weights.size(); ++k)
          sum += f.weights[k] * horizontal[((f.first + k) * static_cast<std::size_t>(width) + x) * 3 + c];
        result.rgb[(static_cast<std::size_t>(y) * width + x) * 3 + c] = static_cast<float>(sum);
      }
  }
  return result;
}

namespace {

/// An image's thumbnail width at `height` px: its aspect ratio kept, at least 1 px.
int thumbnail_width(const LinearImage& image, int height) {
  const double w = std::round(static_cast<double>(image.width) * height / image.height);
  return static_cast<int>(std::clamp(w, 1.0, static_cast<double>(kMaxSide_px)));
}

void check_options(const ContactSheetOptions& o) {
  if (o.cell_height_px < 1 || o.cell_height_px > kMaxCellHeight_px)
    throw std::invalid_argument(
        fmt::format("contact sheet: cell height {} px outside [1, {}]", o.cell_height_px, kMaxCellHeight_px));
  if (o.gap_px < 0 || o.gap_px > kMaxGap_px)
    throw std::invalid_argument(fmt::format("contact sheet: gap {} px outside [0, {}]", o.gap_px, kMaxGap_px));
  if (o.columns < 0) throw std::invalid_argument(fmt::format("contact sheet: columns {} < 0", o.columns));
  if (!(o.background >= 0.0f && o.background <= 1.0f))
    throw std::invalid_argument(fmt::format("contact sheet: background {} outside [0, 1]", o.background));
}

}  // namespace

LinearImage compose_contact_sheet(const std::vector<std::vector<LinearImage>>& frames,
                                  const ContactSheetOptions& options) {
  check_options(options);
  if (frames.empty()) throw std::invalid_argument("contact sheet: no frames");
  const int h = options.cell_height_px, gap = options.gap_px;
  int cell_width = 0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (frames[k].empty()) throw std::invalid_argument(fmt::format("contact sheet: frame {} has no images", k));
    int w = -gap;
    for (const LinearImage& image : frames[k]) {
      if (image.width < 1 || image.height < 1)
        throw std::invalid_argument(fmt::format("contact sheet: frame {} has an empty image", k));
      w += thumbnail_width(image, h) + gap;
    }
    cell_width = std::max(cell_width, w);
  }
  const long long n = static_cast<long long>(frames.size());
  long long columns = options.columns;
  if (columns == 0)  // c columns, n / c rows: c · cell_width ≈ (n / c) · h
    columns = std::llround(std::sqrt(static_cast<double>(n) * h / cell_width));
  columns = std::clamp(columns, 1LL, n);
  const long long rows = (n + columns - 1) / columns;
  const long long sheet_w = columns * cell_width + (columns + 1) * gap, sheet_h = rows * h + (rows + 1) * gap;
  if (sheet_w > kMaxSide_px || sheet_h > kMaxSide_px)
    throw std::invalid_argument(fmt::format("contact sheet: {}x{} px exceeds {} px per side; use smaller cells",
                                            sheet_w, sheet_h, kMaxSide_px));

  LinearImage sheet{static_cast<int>(sheet_w), static_cast<int>(sheet_h),
                    std::vector<float>(static_cast<std::size_t>(sheet_w * sheet_h * 3), options.background)};
  for (long long k = 0; k < n; ++k) {
    const long long top = gap + (k / columns) * (h + gap);
    long long left = gap + (k % columns) * (cell_width + gap);
    for (const LinearImage& image : frames[static_cast<std::size_t>(k)]) {
      const LinearImage thumb = downscale_box(image, thumbnail_width(image, h), h);
      for (int y = 0; y < thumb.height; ++y)
        std::copy_n(thumb.rgb.begin() + static_cast<std::ptrdiff_t>(y) * thumb.width * 3, thumb.width * 3,
                    sheet.rgb.begin() + static_cast<std::ptrdiff_t>(((top + y) * sheet_w + left) * 3));
      left += thumb.width + gap;
    }
  }
  return sheet;
}

LinearImage read_display_image(const std::filesystem::path& path, ToneMapping exr_tone) {
  LinearImage image = read_image(path);
  if (path.extension() == ".exr")
    for (float& v : image.rgb) v = tone_map(v, exr_tone);
  return image;
}

std::pair<int, int> write_contact_sheet(const std::filesystem::path& sheet_path,
                                        const std::vector<std::vector<std::filesystem::path>>& frames,
                                        ToneMapping exr_tone, const ContactSheetOptions& options) {
  check_options(options);
  std::vector<std::vector<LinearImage>> thumbnails;
  for (const auto& files : frames) {
    std::vector<LinearImage>& cell = thumbnails.emplace_back();
    for (const auto& file : files) {
      const LinearImage image = read_display_image(file, exr_tone);
      cell.push_back(downscale_box(image, thumbnail_width(image, options.cell_height_px), options.cell_height_px));
    }
  }
  const LinearImage sheet = compose_contact_sheet(thumbnails, options);
  if (sheet_path.has_parent_path()) std::filesystem::create_directories(sheet_path.parent_path());
  // Values are display-linear already: the clamp operator is the identity on [0, 1].
  write_png(sheet_path, sheet.width, sheet.height, sheet.rgb, ToneMapping::clamp,
            {{"zenith:content", "contact sheet (docs/shows.md, \"Offline rendering\")"}});
  return {sheet.width, sheet.height};
}

std::pair<int, int> write_mosaic_contact_sheet(const std::filesystem::path& sheet_path,
                                               const std::vector<std::vector<MosaicTile>>& frames, ToneMapping exr_tone,
                                               const ContactSheetOptions& options) {
  check_options(options);
  std::vector<std::vector<LinearImage>> thumbnails;
  for (const auto& tiles : frames) {
    if (tiles.empty()) throw std::invalid_argument("write_mosaic_contact_sheet: a frame without tiles");
    std::vector<LinearImage> images;
    LinearImage picture;
    for (const MosaicTile& tile : tiles) {
      if (tile.x_px < 0 || tile.y_px < 0)
        throw std::invalid_argument("write_mosaic_contact_sheet: a tile at a negative offset");
      images.push_back(read_display_image(tile.file, exr_tone));
      picture.width = std::max(picture.width, tile.x_px + images.back().width);
      picture.height = std::max(picture.height, tile.y_px + images.back().height);
    }
    picture.rgb.assign(static_cast<std::size_t>(picture.width) * picture.height * 3, 0.0f);
    for (std::size_t t = 0; t < tiles.size(); ++t) {
      const LinearImage& image = images[t];
      for (int y = 0; y < image.height; ++y)
        std::copy_n(
            image.rgb.begin() + static_cast<std::ptrdiff_t>(y) * image.width * 3, image.width * 3,
            picture.rgb.begin() + (static_cast<std::ptrdiff_t>(tiles[t].y_px + y) * picture.width + tiles[t].x_px) * 3);
    }
    thumbnails.push_back(
        {downscale_box(picture, thumbnail_width(picture, options.cell_height_px), options.cell_height_px)});
  }
  const LinearImage sheet = compose_contact_sheet(thumbnails, options);
  if (sheet_path.has_parent_path()) std::filesystem::create_directories(sheet_path.parent_path());
  write_png(sheet_path, sheet.width, sheet.height, sheet.rgb, ToneMapping::clamp,
            {{"zenith:content", "contact sheet (docs/shows.md, \"Offline rendering\")"}});
  return {sheet.width, sheet.height};
}

std::vector<std::uint64_t> evenly_spaced_frames(std::uint64_t first, std::uint64_t last, std::size_t count) {
  std::vector<std::uint64_t> result;
  if (count == 0 || last < first) return result;
  const std::uint64_t span = last - first;
  if (span < count) {
    for (std::uint64_t f = first; f <= last; ++f) result.push_back(f);
    return result;
  }
  if (count == 1) return {first};
  for (std::size_t k = 0; k < count; ++k) {
    // first + round(k · span / (count − 1)) in integers without overflow:
    // span = q · (count − 1) + r, so k · span / (count − 1) = k · q + k · r / (count − 1).
    const std::uint64_t d = count - 1, q = span / d, r = span % d;
    const std::uint64_t offset = k * q + (2 * k * r + d) / (2 * d);
    if (result.empty() || result.back() != first + offset) result.push_back(first + offset);
  }
  return result;
}

}  // namespace zenith::image
