// Shared by `zenith render` and `zenith show render` (offline/output_rendering.h).
#include "offline/output_rendering.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <string_view>

#include "atmosphere/named_inputs.h"
#include "image/display_fade.h"
#include "image/tone_mapping.h"
#include "render/display/colour_signal.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"

namespace zenith::app {
namespace {

/// 1 to 5 decimal digits, the whole of `text`.
bool is_short_number(std::string_view text) {
  return !text.empty() && text.size() <= 5 &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

std::pair<int, int> parse_size(const std::string& text) {
  // WIDTHxHEIGHT, 1–5 digits each (parsed by hand: GCC 12 warns inside
  // std::regex under the sanitizer build's -O2, which -Werror turns fatal).
  const std::size_t x = text.find_first_of("xX");
  if (x == std::string::npos || !is_short_number(std::string_view(text).substr(0, x)) ||
      !is_short_number(std::string_view(text).substr(x + 1)))
    throw std::invalid_argument(fmt::format("--size '{}': expected WIDTHxHEIGHT, e.g. 1920x1080", text));
  const int w = std::stoi(text.substr(0, x)), h = std::stoi(text.substr(x + 1));
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw std::invalid_argument(fmt::format("--size '{}': width and height must be in [1, 16384]", text));
  return {w, h};
}

std::unique_ptr<warp::Projection> make_projection(const std::string& kind, std::optional<double> fov_deg,
                                                  std::optional<double> tilt_deg, int width, int height) {
  if (kind == "planar") {
    const double fov = fov_deg.value_or(60.0);
    if (!(fov > 0.0 && fov < 179.0))
      throw std::invalid_argument(
          fmt::format("--fov {}: a planar projection's horizontal field of view must be in (0, 179) degrees", fov));
    if (tilt_deg) throw std::invalid_argument("--tilt applies to the fisheye projection only");
    return std::make_unique<warp::PlanarProjection>(warp::PlanarProjection::symmetric(width, height, fov));
  }
  warp::FisheyeParameters p;
  p.fov_deg = fov_deg.value_or(180.0);
  p.tilt_deg = tilt_deg.value_or(0.0);
  return std::make_unique<warp::FisheyeProjection>(width, height, p);
}

ViewportSelection select_viewport_outputs(const std::string& spec) {
  const std::size_t hash = spec.rfind('#');
  ViewportSelection s;
  s.file = spec.substr(0, hash);
  if (s.file.empty()) throw std::invalid_argument(fmt::format("--viewport '{}': expected CONFIG.json[#NAME]", spec));
  // One broken output must not stop another: warps that cannot be used fail
  // only the outputs that need them.
  s.config = warp::load_viewport_config(s.file, {.keep_broken_warps = true});
  if (hash != std::string::npos) {
    s.indices.push_back(s.config.index_of(spec.substr(hash + 1)));
  } else {
    for (std::size_t i = 0; i < s.config.outputs.size(); ++i) s.indices.push_back(i);
  }
  for (const std::size_t i : s.indices) s.config.require_renderable(i);
  return s;
}

render::TableRequest make_table_request(const std::string& table_sizes, int orders, bool cpu_precompute, bool use_cache,
                                        const std::string& cache_dir) {
  render::TableRequest request;
  atmosphere::apply_table_set(table_sizes, request.options);
  request.options.max_orders = orders;
  request.backend = cpu_precompute ? render::PrecomputeBackend::Cpu : render::PrecomputeBackend::Gpu;
  request.use_cache = use_cache;
  if (!cache_dir.empty()) request.cache_directory = cache_dir;
  return request;
}

image::ImageAttributes image_attributes(const scene::Scene& scene, const warp::Projection& projection) {
  return {
      {"zenith:scene", scene.name},
      {"zenith:projection", projection.describe()},
      {"zenith:exposure", fmt::format("{}", scene.camera.exposure)},
      {"zenith:units", "linear sRGB radiance [W m^-2 sr^-1 nm^-1] x exposure"},
  };
}

image::ImageAttributes viewport_attributes(const std::string& file, const warp::OutputConfig& o) {
  image::ImageAttributes attributes;
  attributes.emplace_back("zenith:viewport", fmt::format("{}#{}", file, o.name));
  attributes.emplace_back("zenith:blend", fmt::format("{}; output stage P*alpha*(1-beta)+beta (docs/viewports.md)",
                                                      warp::describe_blend(o)));
  if (o.colour)
    attributes.emplace_back("zenith:colour", fmt::format("MPCDI region \"{}\": {} (docs/warp-meshes.md)",
                                                         o.warp ? o.warp->region : "", warp::describe(*o.colour)));
  return attributes;
}

void render_to_files(render::Renderer& renderer, const scene::Scene& scene, const warp::Projection& projection,
                     const std::vector<std::filesystem::path>& files, const OutputStage& stage,
                     const image::ImageAttributes& attributes, const RowProgress& progress) {
  const int width = projection.width(), height = projection.height();
  struct Target {
    std::unique_ptr<image::ImageWriter> writer;
    bool png;
  };
  std::vector<Target> targets;
  const bool faded = stage.fade_level > 0.0;
  for (const auto& path : files) {
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    const bool png = path.extension() != ".exr";
    // With a blend, a fade or a colour profile the PNG rows arrive tone mapped: the writer only encodes sRGB.
    const image::ToneMapping writer_tone =
        png && (stage.blend != nullptr || faded || stage.colour != nullptr) ? image::ToneMapping::clamp : stage.tone;
    targets.push_back({png ? image::open_png_writer(path, width, height, writer_tone, attributes)
                           : image::open_exr_writer(path, width, height, stage.exr_type, attributes),
                       png});
  }
  std::vector<float> rows;
  renderer.render(scene, projection, [&](int first_row, int row_count, std::span<const float> rgb) {
    for (auto& t : targets) {
      if (t.png && stage.colour != nullptr) {
        rows.assign(rgb.begin(), rgb.end());
        for (float& v : rows) v = image::tone_map(v, stage.tone);
        image::apply_fade(rows, stage.fade_level, stage.fade_colour);
        render::display::apply_colour_profile(rows, first_row, row_count, width, *stage.colour, stage.blend,
                                              stage.black_level);
        render::display::to_srgb_code_centres(rows);  // the writer encodes sRGB: it stores V's codes
        t.writer->write_rows(row_count, rows);
        continue;
      }
      if (stage.blend == nullptr && !(faded && t.png)) {
        t.writer->write_rows(row_count, rgb);
        continue;
      }
      rows.assign(rgb.begin(), rgb.end());
      if (t.png) {
        for (float& v : rows) v = image::tone_map(v, stage.tone);
        image::apply_fade(rows, stage.fade_level, stage.fade_colour);
      }
      if (stage.blend != nullptr) warp::apply_blend(rows, first_row, row_count, *stage.blend, stage.black_level);
      t.writer->write_rows(row_count, rows);
    }
    if (progress) progress(first_row, row_count);
  });
  for (auto& t : targets) t.writer->finish();
}

}  // namespace zenith::app
