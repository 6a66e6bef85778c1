#pragma once
// Contact sheets: a grid of thumbnails of the frames of a sequence, for a
// glance at an offline render (`zenith show render`, docs/shows.md). Each cell
// is one frame: the images of its outputs side by side, each scaled to the
// cell height with an area-weighted box filter. Pixels only, no text.
//
// Everything here works on display-linear values (what the sRGB transfer
// function encodes: 0 black, 1 full white), so thumbnails average light, not
// sRGB codes, and the sheet is written as an 8-bit sRGB PNG.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "image/image_io.h"
#include "image/tone_mapping.h"

namespace zenith::image {

/// Resamples `image` to width × height pixels: each output pixel is the mean
/// of the source area it covers (pixels partly covered weigh by their covered
/// fraction). Meant for shrinking; enlarging repeats pixels. Throws
/// std::invalid_argument for an empty image or a side outside [1, 32768].
LinearImage downscale_box(const LinearImage& image, int width, int height);

struct ContactSheetOptions {
  int cell_height_px = 135;  ///< every thumbnail's height, [1, 4096]
  int columns = 0;           ///< cells per row; 0: about as many rows as columns of pixels (a squarish sheet)
  int gap_px = 4;            ///< between and around cells and between a frame's images, [0, 256]
  float background = 0.0f;   ///< display-linear grey of the gaps, [0, 1]
};

/// The grid: `frames[k]` is cell k (left to right, then top to bottom) and
/// holds its images, placed side by side, each scaled to options.cell_height_px
/// keeping its aspect ratio (width rounded, at least 1 px). Cells are as wide
/// as the widest. Throws std::invalid_argument for no frames, a frame without
/// images, an empty image or options out of range.
LinearImage compose_contact_sheet(const std::vector<std::vector<LinearImage>>& frames,
                                  const ContactSheetOptions& options = {});

/// A rendered file as display-linear values: a PNG decoded from sRGB (exactly
/// what it shows), an OpenEXR's radiance through `exr_tone`. Throws
/// std::runtime_error naming the file (read_image).
LinearImage read_display_image(const std::filesystem::path& path, ToneMapping exr_tone);

/// Reads the files of every frame (read_display_image, shrunk to the cell
/// height as it goes, so only one full image is in memory at a time), composes
/// the sheet and writes it as an 8-bit sRGB PNG (atomically, deterministic
/// bytes). Returns the sheet's size {width, height}.
std::pair<int, int> write_contact_sheet(const std::filesystem::path& sheet_path,
                                        const std::vector<std::vector<std::filesystem::path>>& frames,
                                        ToneMapping exr_tone, const ContactSheetOptions& options = {});

/// One tile of a frame that is a mosaic — the quadrants of a dome master
/// rendered by four cluster nodes: the file and where its top-left pixel goes
/// in the frame's picture.
struct MosaicTile {
  std::filesystem::path file;
  int x_px = 0, y_px = 0;  ///< ≥ 0
};

/// As write_contact_sheet, each cell being one picture put together from its
/// tiles (pixels no tile covers are black; a later tile overwrites an earlier).
std::pair<int, int> write_mosaic_contact_sheet(const std::filesystem::path& sheet_path,
                                               const std::vector<std::vector<MosaicTile>>& frames, ToneMapping exr_tone,
                                               const ContactSheetOptions& options = {});

/// Up to `count` distinct frame numbers evenly spaced over [first, last],
/// both ends included when count ≥ 2, ascending; all of them when the range
/// holds no more than `count`. Empty when count = 0 or last < first.
std::vector<std::uint64_t> evenly_spaced_frames(std::uint64_t first, std::uint64_t last, std::size_t count);

}  // namespace zenith::image
