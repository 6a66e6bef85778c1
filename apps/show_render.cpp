// `zenith show render` and `zenith show plan` (docs/shows.md, "Offline
// rendering"): every frame of a show at a fixed frame rate into numbered image
// files per output, resumable; and the table plan a show needs.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "apps/offline_frame_renderer.h"
#include "apps/offline_manifest.h"
#include "apps/offline_render.h"
#include "apps/output_rendering.h"
#include "apps/table_provider.h"
#include "atmosphere/json_reader.h"
#include "atmosphere/lut/table_cache.h"
#include "cluster/frame_scene.h"
#include "cluster/show/show.h"
#include "cluster/show/table_plan.h"
#include "render/image/colour.h"

namespace zenith::app {
namespace {

using config::cat;

/// The options `show render` and `show plan` share.
struct TableArgs {
  std::string tables = "paper", cache_dir;
  int orders = 4;
  bool cpu_precompute = false;
};

struct ShowRenderArgs {
  std::string show, out, viewport, projection, size, format = "png", contact_sheet;
  std::string tone = "exponential", exr_type = "half", colour = "auto", device = "auto";
  std::optional<double> fps, fov_deg, tilt_deg;
  std::optional<std::uint64_t> from, to;
  TableArgs tables;
};

void add_table_options(CLI::App* cmd, TableArgs& t) {
  cmd->add_option("--tables", t.tables, "Table sizes: paper (default), small, large")
      ->check(CLI::IsMember({"paper", "small", "large"}));
  cmd->add_option("--orders", t.orders, "Scattering orders of the tables (default 4)")->check(CLI::Range(1, 50));
  cmd->add_option("--cache", t.cache_dir, "Table cache directory (default $XDG_CACHE_HOME/zenith)");
}

TableRequest table_request(const TableArgs& t) {
  return make_table_request(t.tables, t.orders, t.cpu_precompute, true, t.cache_dir);
}

/// --fps, else the show's own rate; checked against (0, 1000].
double frame_rate(const show::Show& show, const std::optional<double>& fps) {
  const double rate = fps.value_or(show.frame_rate_hz());
  if (!(rate > 0.0 && rate <= 1000.0))
    throw std::invalid_argument(fmt::format("--fps {}: must be in (0, 1000] frames per second", rate));
  if (fps && show.kind() == show::Show::Kind::recording && *fps != show.frame_rate_hz())
    spdlog::warn("--fps {}: '{}' is a recording; its {} recorded frames are rendered as recorded ({} fps)", *fps,
                 show.source().string(), show.frame_count(rate), show.frame_rate_hz());
  return rate;
}

show::TablePlan plan_for(const show::Show& show, double fps, const TableRequest& request) {
  const atmosphere::lut::TableCache cache(request.cache_directory.value_or(atmosphere::lut::default_cache_directory()));
  return show::plan_tables(show, fps, request.options, cache);
}

/// The outputs of --viewport or --projection/--size: what the frame loop
/// names and keys (specs) and what this process renders (local).
struct Outputs {
  std::vector<offline::OutputSpec> specs;
  std::vector<offline::LocalOutput> local;
};

Outputs outputs_of(const ShowRenderArgs& a) {
  Outputs result;
  if (!a.viewport.empty()) {
    const ViewportSelection selection = select_viewport_outputs(a.viewport);
    // Files carry the config's file name, not the path as typed: the bytes do not depend on the working folder.
    const std::string file_name = std::filesystem::path(selection.file).filename().string();
    const std::string digest = offline::file_sha256(selection.file).substr(0, 16);
    for (const std::size_t i : selection.indices) {
      const warp::OutputConfig& o = selection.config.outputs[i];
      result.specs.push_back({o.name, o.width_px, o.height_px,
                              cat(o.projection->describe(), "; viewport ", file_name, " sha256 ", digest, " #",
                                  o.name, "; blend ", warp::to_string(o.blend.mode), "; black level ",
                                  o.black_level)});
      result.local.push_back({o.projection, warp::output_blend_mask(selection.config, i), o.black_level,
                              viewport_attributes(file_name, o)});
    }
    return result;
  }
  const auto [width, height] = parse_size(a.size);
  std::shared_ptr<const warp::Projection> projection = make_projection(a.projection, a.fov_deg, a.tilt_deg, width, height);
  result.specs.push_back({a.projection, width, height, projection->describe()});
  result.local.push_back({std::move(projection), std::nullopt, 0.0, {}});
  return result;
}

void check_arguments(const ShowRenderArgs& a, bool size_given) {
  if (a.viewport.empty() == a.projection.empty())
    throw std::invalid_argument(
        "give either --viewport CONFIG[#NAME] (the outputs of a viewport config) or --projection fisheye|planar "
        "with --size WxH");
  if (!a.viewport.empty() && (size_given || a.fov_deg || a.tilt_deg))
    throw std::invalid_argument(
        "--viewport: the viewport config gives each output's projection and size; drop --size, --fov and --tilt");
  if (!a.projection.empty() && !size_given)
    throw std::invalid_argument("--projection: give the frame size with --size WxH (e.g. --size 1024x1024)");
  if (a.fps && !(*a.fps > 0.0 && *a.fps <= 1000.0))
    throw std::invalid_argument(fmt::format("--fps {}: must be in (0, 1000] frames per second", *a.fps));
  std::error_code ec;
  if (std::filesystem::exists(a.out, ec) && !std::filesystem::is_directory(a.out, ec))
    throw std::invalid_argument(fmt::format("--out '{}': exists and is not a folder", a.out));
}

void run_show_render(const ShowRenderArgs& a, bool size_given) {
  check_arguments(a, size_given);
  const std::vector<offline::ImageFormat> formats = offline::parse_formats(a.format);
  const image::ToneMapping tone = image::parse_tone_mapping(a.tone);
  const image::ExrPixelType exr_type = image::parse_exr_pixel_type(a.exr_type);
  const image::ColourMapping colour = image::parse_colour_mapping(a.colour);
  Outputs outputs = outputs_of(a);

  const show::Show show = show::load_show(a.show);
  const double fps = frame_rate(show, a.fps);
  const std::uint64_t frame_count = show.frame_count(fps);
  if (frame_count == 0) throw std::invalid_argument(fmt::format("{}: the show has no frames", a.show));
  const std::uint64_t first = a.from.value_or(0), last = a.to.value_or(frame_count - 1);
  if (first >= frame_count || last >= frame_count || first > last)
    throw std::invalid_argument(fmt::format("--from {} --to {}: must satisfy 0 ≤ from ≤ to ≤ {} (the show's last "
                                            "frame at {} fps)",
                                            first, last, frame_count - 1, fps));

  const TableRequest request = table_request(a.tables);
  const show::TablePlan plan = plan_for(show, fps, request);
  fmt::print("{}", show::describe(plan));
  std::fflush(stdout);

  std::map<cluster::Digest, show::AtmosphereVersion> versions;
  for (const show::TablePlanEntry& entry : plan.sets) versions.emplace(entry.version.table_hash, entry.version);

  offline::RenderJob job;
  job.show = &show;
  job.fps = fps;
  job.first_frame = first;
  job.last_frame = last;
  job.render_flags = cluster::render_flags_of(render::RenderOptions{});
  job.outputs = outputs.specs;
  job.formats = formats;
  job.settings = cat("scene sha256 ", offline::file_sha256(show.scene_path()), "; tables ", a.tables.tables,
                     " orders ", a.tables.orders, "; colour ", image::to_string(colour));
  job.png_settings = cat("tone ", image::to_string(tone));
  job.exr_settings = cat("pixels ", image::to_string(exr_type));
  job.out_dir = a.out;
  job.tone = tone;
  if (a.contact_sheet != "none")
    job.contact_sheet = a.contact_sheet.empty() ? job.out_dir / "contact-sheet.png"
                                                : std::filesystem::path(a.contact_sheet);

  nlohmann::json run_outputs = nlohmann::json::array();
  for (const offline::OutputSpec& o : job.outputs) {
    nlohmann::json keys = nlohmann::json::object();
    for (const offline::ImageFormat f : formats) keys[offline::extension_of(f)] = offline::settings_key(job, o, f);
    run_outputs.push_back({{"name", o.name},
                           {"width_px", o.width_px},
                           {"height_px", o.height_px},
                           {"description", o.description},
                           {"settings_keys", std::move(keys)}});
  }
  nlohmann::json run_formats = nlohmann::json::array();
  for (const offline::ImageFormat f : formats) run_formats.push_back(offline::extension_of(f));
  job.run = {{"show",
              {{"file", std::filesystem::absolute(show.source()).string()},
               {"name", show.name()},
               {"sha256", offline::file_sha256(show.source())}}},
             {"scene", std::filesystem::absolute(show.scene_path()).string()},
             {"fps", fps},
             {"frame_count", frame_count},
             {"from", first},
             {"to", last},
             {"outputs", std::move(run_outputs)},
             {"formats", std::move(run_formats)},
             {"settings", job.settings},
             {"png_settings", job.png_settings},
             {"exr_settings", job.exr_settings}};

  render::gl::ContextOptions context_options;
  context_options.prefer = render::gl::parse_device_preference(a.device);
  offline::LocalFrameRenderer renderer(show, std::move(versions), std::move(outputs.local), OutputStage{tone, exr_type},
                                       colour, request, context_options);
  job.before_rendering = [&](std::uint64_t frames, const std::set<cluster::Digest>& table_hashes) {
    spdlog::info("rendering {} frame{} of '{}' at {} fps into {}/<output>/<output>.NNNNNN.{} on {}", frames,
                 frames == 1 ? "" : "s", show.name(), fps, a.out, a.format, renderer.device());
    renderer.precompute_missing(plan, table_hashes);
  };
  const offline::RenderSummary summary = offline::run_render_job(job, renderer);
  fmt::print("{}\n", offline::describe(summary));
}

}  // namespace

void register_show_render(CLI::App& show_command) {
  auto a = std::make_shared<ShowRenderArgs>();
  CLI::App* cmd = show_command.add_subcommand(
      "render", "Render every frame of a show at a fixed frame rate to numbered PNG/EXR files per output, resumable "
                "(docs/shows.md, \"Offline rendering\")");
  cmd->add_option("--show", a->show, "Show file (configs/shows/)")->required();
  cmd->add_option("--out", a->out, "Output folder: DIR/<output>/<output>.<frame:06d>.png|exr, DIR/manifest.json")
      ->required();
  cmd->add_option("--viewport", a->viewport,
                  "Render output NAME of a viewport config (CONFIG.json#NAME), or every output (CONFIG.json)");
  cmd->add_option("--projection", a->projection, "fisheye or planar (with --size), instead of --viewport")
      ->check(CLI::IsMember({"planar", "fisheye"}));
  cmd->add_option("--fov", a->fov_deg, "Field of view [deg]: planar horizontal (default 60), fisheye (default 180)");
  cmd->add_option("--tilt", a->tilt_deg, "Fisheye: axis tilted from the zenith toward forward [deg]");
  cmd->add_option("--size", a->size, "WIDTHxHEIGHT in pixels (with --projection)");
  cmd->add_option("--fps", a->fps, "Frame rate [Hz] in (0, 1000] (default: the show's)");
  cmd->add_option("--from", a->from, "First frame to render (default 0)");
  cmd->add_option("--to", a->to, "Last frame to render, inclusive (default: the show's last)");
  cmd->add_option("--format", a->format, "png (default), exr or png,exr");
  cmd->add_option("--contact-sheet", a->contact_sheet,
                  "Contact sheet PNG of 24 evenly spaced frames (default DIR/contact-sheet.png; none: no sheet)");
  cmd->add_option("--exr-type", a->exr_type, "EXR pixels: half (default) or float")
      ->check(CLI::IsMember({"half", "float"}));
  cmd->add_option("--tone", a->tone, "PNG tone mapping: exponential (paper, default) or clamp")
      ->check(CLI::IsMember({"exponential", "clamp"}));
  cmd->add_option("--colour", a->colour, "Spectral to RGB: auto, direct, cie1931")
      ->check(CLI::IsMember({"auto", "direct", "cie1931"}));
  add_table_options(cmd, a->tables);
  cmd->add_flag("--cpu-precompute", a->tables.cpu_precompute, "Precompute missing tables on the CPU");
  cmd->add_option("--device", a->device, "GL device: auto, software (llvmpipe), hardware")
      ->check(CLI::IsMember({"auto", "software", "hardware"}));
  cmd->callback([a, cmd] { run_show_render(*a, cmd->count("--size") > 0); });
}

void register_show_plan(CLI::App& show_command) {
  auto a = std::make_shared<ShowRenderArgs>();
  CLI::App* cmd = show_command.add_subcommand(
      "plan", "Print the lookup-table sets a show needs at a frame rate, their size and which are cached");
  cmd->add_option("--show", a->show, "Show file (configs/shows/)")->required();
  cmd->add_option("--fps", a->fps, "Frame rate [Hz] in (0, 1000] (default: the show's)");
  add_table_options(cmd, a->tables);
  cmd->callback([a] {
    const show::Show loaded = show::load_show(a->show);
    const double fps = frame_rate(loaded, a->fps);
    fmt::print("{}", show::describe(plan_for(loaded, fps, table_request(a->tables))));
  });
}

}  // namespace zenith::app
