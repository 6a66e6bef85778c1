#pragma once
// What `zenith render` and `zenith show render` share: the --size and
// --projection arguments, the --viewport CONFIG[#NAME] selection, the table
// request of the --tables/--cache options, the image attributes, and the
// rendering of one frame into files (streamed to EXR/PNG writers, with the
// viewport output stage: blend mask and black level, docs/viewports.md).
#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "image/image_writer.h"
#include "render/lut/table_provider.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "warp/blending.h"
#include "warp/colour_profile.h"
#include "warp/projection.h"
#include "warp/viewport_config.h"

namespace zenith::app {

/// "WIDTHxHEIGHT" (1–5 digits each, both in [1, 16384]); throws
/// std::invalid_argument naming --size and the expected form.
std::pair<int, int> parse_size(const std::string& text);

/// A "planar" (--fov: horizontal, default 60, in (0, 179)) or "fisheye" (--fov
/// default 180, --tilt default 0) projection of width × height pixels. Throws
/// std::invalid_argument naming the option for a bad field of view or --tilt
/// on a planar projection.
std::unique_ptr<warp::Projection> make_projection(const std::string& kind, std::optional<double> fov_deg,
                                                  std::optional<double> tilt_deg, int width, int height);

/// The outputs --viewport CONFIG[#NAME] selects: output NAME, or every output
/// of CONFIG without #NAME.
struct ViewportSelection {
  std::string file;  ///< CONFIG as given
  warp::ViewportConfig config;
  std::vector<std::size_t> indices;  ///< into config.outputs
};
/// Loads CONFIG; throws std::invalid_argument for an empty CONFIG or an
/// unknown NAME (listing the names), zenith::ConfigError for a bad config and
/// for a selected output whose warp cannot be used. Another output's broken
/// warp does not stop NAME (warp::ViewportLoadOptions::keep_broken_warps).
ViewportSelection select_viewport_outputs(const std::string& spec);

/// The render::TableRequest of --tables NAME, --orders N, --cpu-precompute, --no-cache
/// and --cache DIR ("" for the default cache directory).
render::TableRequest make_table_request(const std::string& table_sizes, int orders, bool cpu_precompute, bool use_cache,
                                        const std::string& cache_dir);

/// zenith:scene, zenith:projection, zenith:exposure and zenith:units.
image::ImageAttributes image_attributes(const scene::Scene& scene, const warp::Projection& projection);
/// zenith:viewport ("FILE#NAME") and zenith:blend of output `o` of the viewport config `file`.
image::ImageAttributes viewport_attributes(const std::string& file, const warp::OutputConfig& o);

/// How rendered radiance becomes file values.
struct OutputStage {
  image::ToneMapping tone = image::ToneMapping::exponential;  ///< PNG
  image::ExrPixelType exr_type = image::ExrPixelType::half;
  const warp::BlendMask* blend = nullptr;  ///< viewport outputs: the output's mask
  double black_level = 0.0;                ///< with a blend: β
  /// The frame's fade (docs/operator.md, "Fades"; image/display_fade.h): PNG
  /// rows are faded after tone mapping, before the output stage, as on a
  /// projector; EXR keeps the radiance and names the fade in zenith:fade.
  double fade_level = 0.0;
  std::array<double, 3> fade_colour{0, 0, 0};
  /// An MPCDI region's colour profile: PNG codes are its processPixel of the
  /// sRGB signal with α and β (render/display/colour_signal.h); nullptr: none. EXR keeps the radiance.
  const warp::MpcdiColourProfile* colour = nullptr;
};

/// Called after each band of rows reaches the writers.
using RowProgress = std::function<void(int first_row, int row_count)>;

/// Renders one frame into every file of `files` (.exr: linear, else PNG),
/// each published atomically (NAME.partial, renamed by finish()). With a
/// `stage.blend` mask, each output's rows go through the output stage first
/// (docs/viewports.md): PNG: L = tone(v), L' = L·α·(1 − β) + β, then sRGB
/// (the writer is opened with the clamp operator, the identity on [0, 1]);
/// EXR: v' = v·α·(1 − β) + β, linear, 1.0 = full white. With `stage.colour`
/// the PNG's codes are render::display::apply_colour_profile's (docs/warp-meshes.md, "Colour profile").
void render_to_files(render::Renderer& renderer, const scene::Scene& scene, const warp::Projection& projection,
                     const std::vector<std::filesystem::path>& files, const OutputStage& stage,
                     const image::ImageAttributes& attributes, const RowProgress& progress = {});

}  // namespace zenith::app
