#pragma once
// Offline rendering of a show (docs/shows.md, "Offline rendering"): every
// frame of a show at a fixed frame rate, whatever the wall time, into numbered
// image files, resumable through the manifest (offline/offline_manifest.h).
//
// The frame loop is independent of how a frame is rendered: `zenith show
// render` hands it a LocalFrameRenderer (offline/offline_frame_renderer.h); a
// cluster can hand it one that renders on its nodes. The loop owns the file
// layout, the manifest, the progress bar, the summary and the contact sheet:
//
//   DIR/manifest.json
//   DIR/contact-sheet.png                 (unless --contact-sheet none / another FILE)
//   DIR/<output>/<output>.<frame:06d>.png|tif|exr   (RenderJob::naming: another pattern)
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "image/tone_mapping.h"
#include "scene/frame_description.h"
#include "show/show.h"

namespace zenith::app::offline {

/// The file formats of a render (docs/shows.md, "Output formats"): PNG of 8
/// or 16 bits and 16-bit TIFF hold the display codes (tone mapped, output
/// stage, sRGB encoded: the display pass's), EXR the linear radiance.
enum class ImageFormat { png, png16, tiff, exr };
/// The file extension: "png" (png and png16), "tif", "exr".
const char* extension_of(ImageFormat format);
/// The format's name on the command line: "png", "png16", "tiff", "exr".
const char* name_of(ImageFormat format);
/// Whether the format stores display codes (png, png16, tiff) rather than linear radiance.
bool is_display_format(ImageFormat format);
/// A comma list of png, png16, tiff and exr, each at most once ("png,exr");
/// png and png16 not together (one extension). Throws std::invalid_argument
/// naming --format and the allowed values.
std::vector<ImageFormat> parse_formats(const std::string& text);

/// How frame files are named inside their output's folder: a pattern with one
/// printf-style frame number (`%d` or `%0Nd`, N in [1, 9]) and optionally
/// `{output}`, the extension appended; the file of show frame i carries the
/// number start_number + i.
struct FileNaming {
  std::string pattern = "{output}.%06d";
  std::uint64_t start_number = 0;
  bool operator==(const FileNaming&) const = default;
};
/// Checks --frame-name PATTERN (a trailing ".png", ".tif", ".tiff" or ".exr"
/// is dropped: the format gives the extension); throws std::invalid_argument
/// naming --frame-name and the rule.
FileNaming parse_file_naming(const std::string& pattern, std::uint64_t start_number);

/// An output of the render: one image per frame and format.
struct OutputSpec {
  std::string name;  ///< the folder and file stem: a viewport output's name, or the projection's ("fisheye", "planar")
  int width_px = 0, height_px = 0;
  /// Everything besides the frame state that shapes its pixels (projection,
  /// viewport file digest, warp, blend, black level): part of its settings key.
  std::string description;
  /// Where this output's top-left pixel sits in one picture shared by every
  /// output (tiles of a dome master, warp/dome_tiles.h): the contact sheet
  /// then shows each frame as that picture. Set on all outputs or none.
  std::optional<std::array<int, 2>> mosaic_origin_px;
};

/// "<output>/<output>.<frame:06d>.<ext>": a file's path relative to the render
/// folder (six digits at least; more for frames ≥ 1 000 000); with `naming`,
/// "<output>/<pattern with the number>.<ext>".
std::string frame_file_path(const std::string& output, std::uint64_t frame, ImageFormat format,
                            const FileNaming& naming = {});

/// A frame whose files are complete, with the SHA-256 (hex) of each, output-major.
struct FinishedFrame {
  std::uint64_t frame = 0;
  std::vector<std::string> file_sha256;
};

/// Renders the state of one frame into files[o][f]: output o of the job, its
/// format f, each published atomically (NAME.partial renamed to NAME).
class FrameRenderer {
 public:
  virtual ~FrameRenderer() = default;
  virtual void render_frame(const scene::FrameDescription& state,
                            const std::vector<std::vector<std::filesystem::path>>& files) = 0;
  /// A pipelined renderer queues the frame and returns (its files appear
  /// later, frames in order); this one renders it at once (render_frame) and
  /// hashes its files.
  virtual void submit_frame(const scene::FrameDescription& state,
                            const std::vector<std::vector<std::filesystem::path>>& files);
  /// The frames whose files are complete since the last call, in order.
  virtual std::vector<FinishedFrame> take_finished();
  /// Waits until every submitted frame is complete; throws the first error.
  virtual void finish_frames() {}

 private:
  std::vector<FinishedFrame> finished_;  // submit_frame's
};

struct RenderJob {
  const show::Show* show = nullptr;
  double fps = 30.0;
  std::uint64_t first_frame = 0, last_frame = 0;  ///< inclusive; last_frame < show->frame_count(fps)
  std::uint32_t render_flags = 0;                 ///< for Show::state_at
  std::vector<OutputSpec> outputs;                ///< at least one, distinct names
  std::vector<ImageFormat> formats;               ///< at least one
  /// What else shapes every file's bytes (scene file digest, table sizes,
  /// colour mapping, ...), and each format's own settings (tone mapping for
  /// PNG, pixel type for EXR): with OutputSpec::description, the settings key.
  std::string settings, png_settings, exr_settings, tiff_settings;
  std::filesystem::path out_dir;
  FileNaming naming;
  nlohmann::json run = nlohmann::json::object();  ///< stored as the manifest's "run"
  /// The contact sheet's path (nullopt: none), its number of frames and the
  /// tone mapping of EXR-only outputs in it.
  std::optional<std::filesystem::path> contact_sheet;
  std::size_t contact_sheet_frames = 24;
  image::ToneMapping tone = image::ToneMapping::exponential;
  double manifest_interval_s = 2.0;  ///< the manifest is rewritten at most this often while rendering
  /// Called once the frames to render are known, before the first renders,
  /// with their number and the table sets (hashes) their states use; not
  /// called when there are none. E.g. to precompute those tables ahead.
  std::function<void(std::uint64_t frames_to_render, const std::set<scene::TableHash>& table_hashes)> before_rendering;
  /// The fingerprint of a frame's description that the manifest stores and a
  /// resume compares (required). `zenith show render` passes
  /// cluster::state_digest, the one the cluster nodes write to presented.log.
  std::function<std::string(const scene::FrameDescription&)> frame_digest;
};

struct RenderSummary {
  std::uint64_t frames = 0, rendered = 0, skipped = 0;
  double render_s = 0.0;  ///< wall time of the rendered frames (files and hashes included)
  double total_s = 0.0;   ///< the whole job, checks and contact sheet included
  std::optional<std::filesystem::path> contact_sheet;
};

/// The settings key of `output` in `format`: the first 16 hex digits of the
/// SHA-256 of job.settings, the output's name, size and description, and the
/// format's settings.
std::string settings_key(const RenderJob& job, const OutputSpec& output, ImageFormat format);

/// Checks every frame of [first_frame, last_frame] against DIR/manifest.json,
/// renders those that are not verified (renderer.render_frame, then hashes the
/// files into the manifest), writes the contact sheet and returns the counts.
/// Throws std::invalid_argument for an inconsistent job; on an error while
/// rendering, the manifest is written (recording the frames finished) before
/// the exception propagates.
RenderSummary run_render_job(const RenderJob& job, FrameRenderer& renderer);

/// "rendered 2, skipped 4 of 6 frames in 12.3 s (2.41 s per rendered frame)".
std::string describe(const RenderSummary& summary);

}  // namespace zenith::app::offline
