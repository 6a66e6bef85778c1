#pragma once
// Export of a viewport config's outputs for hardware that warps and blends
// itself (projector warp engines, media servers): `zenith export-calibration`.
// Per output NAME, into one folder:
//
//   NAME.warp.pfm            the warp: (2W+1) × (2H+1) nodes (u, v, 0), rows top first,
//                            absolute, v down, NaN = no data (warp/export_warp_map.h)
//   NAME.alpha-linear.png    the blend mask α (times the warp's intensity), 16-bit grey, α = value / 65535
//   NAME.alpha-gamma2.2.png  the same, display-encoded: α = (value / 65535)^2.2
//   NAME.beta-linear.png     the black-level map β (what the output stage adds), linear
//   NAME.beta-gamma2.2.png   the same, display-encoded
//   NAME.mpcdi               MPCDI 2d archive: mpcdi.xml, the warp PFM, the linear alpha and beta maps;
//                            or (CalibrationExportOptions::mpcdi_profile sl) an sl archive: the
//                            output's frustum and a coordinate frame, its warp as the lens
//                            distortion map (none without a warp), the alpha and beta maps
//
// and for the whole export:
//
//   viewport-pfm.json        a viewport config of the exported outputs reading the PFM warps,
//                            the linear alpha map as the blend file and β as black_level
//                            (where β is one number; an output whose β is a map, from an
//                            MPCDI region's beta map, has it only in the maps and the archive)
//   viewport-mpcdi.json      the same reading the MPCDI archives, with "blend": {"type": "mpcdi"}:
//                            the archive's alpha map as α, its beta map as β per pixel
//   calibration.json         the sidecar: every file, its size, encoding and conventions
//
// Loading either viewport config gives every output pixel the ray it had
// (within 1e-6) and the same blend mask and black level (within the 16-bit
// quantization, half a step 7.6e-6; viewport-pfm.json's black_level exactly),
// so the same displayed frame within ±1 code in 8 bits. docs/warp-meshes.md,
// "Exporting to warp engines and media servers".
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "warp/mpcdi.h"
#include "warp/viewport_config.h"

namespace zenith::app {

/// Options of export_calibration().
struct CalibrationExportOptions {
  /// The profile of the MPCDI archives: media_2d (any output: the warp of its
  /// source image) or shader_lamps (outputs whose projection is planar, with
  /// or without a warp: a pinhole projector, the frustum and frame exactly,
  /// the warp as the lens distortion map; warp/mpcdi_writer.h).
  warp::MpcdiProfile mpcdi_profile = warp::MpcdiProfile::media_2d;
};

/// One file an export wrote.
struct ExportedFile {
  std::filesystem::path path;
  std::string summary;  ///< what it holds, one line: "warp, PFM 97 x 55 nodes (u, v, 0), rows top first, ..."
};

/// Exports the outputs `indices` of `config` into `dir` (created with its
/// parents when missing; existing files of the same names are replaced).
/// Returns the files written, in order. Throws what require_renderable() throws
/// for an output whose warp cannot be used, std::invalid_argument from
/// warp::export_warp_map() (an output too large) and, for the sl profile,
/// naming an output whose projection is not planar (before anything is
/// written), and std::runtime_error naming the folder or file that cannot be
/// created or written.
std::vector<ExportedFile> export_calibration(const warp::ViewportConfig& config,
                                             const std::vector<std::size_t>& indices, const std::filesystem::path& dir,
                                             const CalibrationExportOptions& options = {});

/// export_calibration() of the output named `output_name`, or of every output
/// when it is empty. Throws std::invalid_argument naming the config file and
/// listing its outputs for an unknown name.
std::vector<ExportedFile> export_calibration(const warp::ViewportConfig& config, const std::string& output_name,
                                             const std::filesystem::path& dir,
                                             const CalibrationExportOptions& options = {});

}  // namespace zenith::app
