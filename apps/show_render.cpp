// `zenith show render` and `zenith show plan` (docs/shows.md, "Offline
// rendering"): every frame of a show at a fixed frame rate into numbered image
// files per output, resumable; and the table plan a show needs.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli_options.h"
#include "apps/commands.h"
#include "atmosphere/lut/table_cache.h"
#include "cluster/link/cluster_config.h"
#include "core/json_reader.h"
#include "core/strings.h"
#include "image/colour.h"
#include "image/display_image_writer.h"
#include "offline/offline_cluster_renderer.h"
#include "offline/offline_frame_renderer.h"
#include "offline/offline_manifest.h"
#include "offline/offline_render.h"
#include "offline/output_rendering.h"
#include "offline/video_proxy.h"
#include "render/lut/table_provider.h"
#include "render/render_flags.h"
#include "scene/frame_digest.h"
#include "show/eclipse_plan.h"
#include "show/show.h"
#include "show/table_plan.h"
#include "warp/dome_tiles.h"

namespace zenith::app {
namespace {

using core::cat;

/// The options `show render` and `show plan` share.
struct TableArgs {
  std::string tables = "paper", cache_dir;
  int orders = atmosphere::lut::kDefaultScatteringOrders;
  bool cpu_precompute = false;
};

struct ShowRenderArgs {
  std::string show, out, viewport, projection, size, format = "png", contact_sheet, cluster;
  std::string tone = "exponential", exr_type = "half", colour = "auto", device = "auto";
  std::string png_compression = "fast", tiff_compression = "deflate", frame_name = "{output}.%06d", video;
  std::uint64_t start_number = 0;
  std::optional<int> threads, frames_in_flight;
  bool serial_compile = false;
  std::optional<double> fps, fov_deg, tilt_deg;
  std::optional<std::uint64_t> from, to;
  TableArgs tables;
  std::size_t max_keys = show::ShowLimits::kDefaultMaxKeysPerTrack;
  std::size_t max_table_sets = show::ShowLimits::kDefaultMaxTableSets;
  double table_budget_gib = show::kDefaultTableBudgetGiB;

  /// --max-keys, --max-table-sets and --table-budget-gib (docs/shows.md, "Limits").
  void add_limits(CLI::App* cmd) {
    cmd->add_option("--max-keys", max_keys, "Refuse a show with more keys in one track (default 100000)")
        ->check(CLI::Range(std::size_t{1}, show::ShowLimits::kMaxKeysPerTrackCeiling));
    cmd->add_option("--max-table-sets", max_table_sets,
                    "Refuse a show whose atmosphere tracks step through more lookup-table sets (default 256)")
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--table-budget-gib", table_budget_gib,
                    "Warn before precomputing when the show's table sets together exceed this (default 4 GiB)")
        ->check(CLI::Range(0.001, 1e6));
  }
  show::ShowLimits limits() const {
    show::ShowLimits l;
    l.max_keys_per_track = max_keys;
    l.max_table_sets = max_table_sets;
    return l;
  }
};

render::TableRequest table_request(const TableArgs& t) {
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

show::TablePlan plan_for(const show::Show& show, double fps, const render::TableRequest& request) {
  const atmosphere::lut::TableCache cache(request.cache_directory.value_or(atmosphere::lut::default_cache_directory()));
  return show::plan_tables(show, fps, request.options, cache);
}

/// The outputs of --viewport or --projection/--size: what the frame loop
/// names and keys (specs) and what this process renders (local).
struct Outputs {
  std::vector<offline::OutputSpec> specs;
  std::vector<offline::LocalOutput> local;
};

/// Tiles of one dome master show as the whole picture on the contact sheet.
void set_dome_mosaic(std::vector<offline::OutputSpec>& specs, const std::vector<const warp::OutputConfig*>& outputs) {
  if (specs.size() < 2) return;
  if (const auto origins = warp::dome_tile_origins(outputs))
    for (std::size_t i = 0; i < specs.size(); ++i) specs[i].mosaic_origin_px = (*origins)[i];
}

/// The specs of every output of a cluster's nodes (they render; this process does not).
Outputs cluster_outputs(const cluster::ClusterConfig& config) {
  Outputs result;
  const warp::ViewportConfig viewports = warp::load_viewport_config(config.viewports);
  const std::string file_name = std::filesystem::path(config.viewports).filename().string();
  const std::string digest = offline::file_sha256(config.viewports).substr(0, 16);
  std::vector<const warp::OutputConfig*> configs;
  for (const cluster::ClusterNodeConfig& node : config.nodes)
    for (const std::string& name : node.outputs) {
      const warp::OutputConfig& o = viewports.outputs[viewports.index_of(name)];
      configs.push_back(&o);
      result.specs.push_back({o.name, o.width_px, o.height_px,
                              cat(o.projection->describe(), "; viewport ", file_name, " sha256 ", digest, " #", o.name,
                                  "; blend ", warp::describe_blend(o), "; node ", node.name),
                              std::nullopt});
    }
  set_dome_mosaic(result.specs, configs);
  return result;
}

Outputs outputs_of(const ShowRenderArgs& a) {
  Outputs result;
  if (!a.viewport.empty()) {
    const ViewportSelection selection = select_viewport_outputs(a.viewport);
    // Files carry the config's file name, not the path as typed: the bytes do not depend on the working folder.
    const std::string file_name = std::filesystem::path(selection.file).filename().string();
    const std::string digest = offline::file_sha256(selection.file).substr(0, 16);
    std::vector<const warp::OutputConfig*> configs;
    for (const std::size_t i : selection.indices) {
      const warp::OutputConfig& o = selection.config.outputs[i];
      configs.push_back(&o);
      result.specs.push_back({o.name, o.width_px, o.height_px,
                              cat(o.projection->describe(), "; viewport ", file_name, " sha256 ", digest, " #", o.name,
                                  "; blend ", warp::describe_blend(o)),
                              std::nullopt});
      result.local.push_back({o.projection, warp::output_blend_mask(selection.config, i), o.black_level,
                              viewport_attributes(file_name, o), o.colour});
    }
    set_dome_mosaic(result.specs, configs);
    return result;
  }
  const auto [width, height] = parse_size(a.size);
  std::shared_ptr<const warp::Projection> projection =
      make_projection(a.projection, a.fov_deg, a.tilt_deg, width, height);
  result.specs.push_back({a.projection, width, height, projection->describe(), std::nullopt});
  result.local.push_back({std::move(projection), std::nullopt, 0.0, {}, nullptr});
  return result;
}

void check_arguments(const ShowRenderArgs& a, bool size_given) {
  if (int(!a.viewport.empty()) + int(!a.projection.empty()) + int(!a.cluster.empty()) != 1)
    throw std::invalid_argument(
        "give one of --cluster FILE (the nodes of a cluster render their outputs), --viewport CONFIG[#NAME] (the "
        "outputs of a viewport config) or --projection fisheye|planar with --size WxH");
  if (!a.cluster.empty() && (size_given || a.fov_deg || a.tilt_deg))
    throw std::invalid_argument(
        "--cluster: the cluster's viewport config gives each output's projection and size; drop --size, --fov and "
        "--tilt");
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

void run_show_render(const ShowRenderArgs& a, bool size_given, bool format_given) {
  check_arguments(a, size_given);
  const offline::FileNaming naming = offline::parse_file_naming(a.frame_name, a.start_number);
  const int png_compression = image::parse_png_compression(a.png_compression);
  const image::TiffCompression tiff_compression = image::parse_tiff_compression(a.tiff_compression);
  if (a.threads && (*a.threads < 0 || *a.threads > 256))
    throw std::invalid_argument(
        fmt::format("--threads {}: must be in [0, 256] (0: the simple path, no pipeline)", *a.threads));
  if (a.frames_in_flight && (*a.frames_in_flight < 1 || *a.frames_in_flight > 64))
    throw std::invalid_argument(fmt::format("--frames-in-flight {}: must be in [1, 64]", *a.frames_in_flight));
  if (!a.video.empty() && !offline::find_ffmpeg())
    throw std::invalid_argument(fmt::format(
        "--video {}: ffmpeg is not installed (no ffmpeg on PATH); install it (scripts/bootstrap installs the Debian "
        "package ffmpeg) or drop --video",
        a.video));
  std::optional<cluster::ClusterConfig> cluster_config;
  if (!a.cluster.empty()) {
    cluster_config = cluster::load_cluster_config(a.cluster);
    if (format_given && a.format != cluster_config->output_format)
      throw std::invalid_argument(fmt::format("--format {}: the nodes of {} write {} (its \"output\": \"format\")",
                                              a.format, a.cluster, cluster_config->output_format));
    if (!(naming == offline::FileNaming{}) || !a.video.empty() || a.threads || a.frames_in_flight || a.serial_compile)
      throw std::invalid_argument(
          "--cluster: the nodes name and write their own files; --frame-name, --start-number, --video, --threads, "
          "--frames-in-flight and --serial-compile apply to a render in this process");
  }
  const std::vector<offline::ImageFormat> formats =
      offline::parse_formats(cluster_config ? cluster_config->output_format : a.format);
  const image::ToneMapping tone = image::parse_tone_mapping(a.tone);
  const image::ExrPixelType exr_type = image::parse_exr_pixel_type(a.exr_type);
  const image::ColourMapping colour = image::parse_colour_mapping(a.colour);
  Outputs outputs = cluster_config ? cluster_outputs(*cluster_config) : outputs_of(a);

  const show::Show show = show::load_show(a.show, a.limits());
  const double fps = frame_rate(show, a.fps);
  const std::uint64_t frame_count = show.frame_count(fps);
  if (frame_count == 0) throw std::invalid_argument(fmt::format("{}: the show has no frames", a.show));
  const std::uint64_t first = a.from.value_or(0), last = a.to.value_or(frame_count - 1);
  if (first >= frame_count || last >= frame_count || first > last)
    throw std::invalid_argument(
        fmt::format("--from {} --to {}: must satisfy 0 ≤ from ≤ to ≤ {} (the show's last "
                    "frame at {} fps)",
                    first, last, frame_count - 1, fps));

  TableArgs table_args = a.tables;
  if (cluster_config) {  // the nodes render with the cluster's tables
    table_args.tables = cluster_config->table_sizes;
    table_args.orders = cluster_config->table_orders;
  }
  render::TableRequest request = table_request(table_args);
  if (a.serial_compile) request.compile = render::gl::CompileMode::serial;
  const show::TablePlan plan = plan_for(show, fps, request);
  if (const std::string warning = show::budget_warning(plan, a.table_budget_gib); !warning.empty())
    fmt::print(stderr, "{}", warning);
  fmt::print("{}", show::describe(plan));
  std::fflush(stdout);

  std::map<scene::TableHash, show::AtmosphereVersion> versions;
  for (const show::TablePlanEntry& entry : plan.sets) versions.emplace(entry.version.table_hash, entry.version);

  offline::RenderJob job;
  job.show = &show;
  job.fps = fps;
  job.first_frame = first;
  job.last_frame = last;
  job.render_flags = render::render_flags_of(render::RenderOptions{});
  job.frame_digest = scene::frame_digest;
  job.outputs = outputs.specs;
  job.formats = formats;
  job.settings = cat("scene sha256 ", offline::file_sha256(show.scene_path()), "; tables ", table_args.tables,
                     " orders ", table_args.orders, "; colour ", image::to_string(colour));
  if (cluster_config)  // the nodes' own output stage (the defaults of `zenith node`)
    job.settings = cat(job.settings, "; cluster ", cluster_config->name, " nodes");
  // The pipeline's PNGs carry the display pass's codes at the chosen compression (the bytes depend on it).
  job.png_settings = cat("tone ", image::to_string(tone), "; display pass; zlib ", png_compression);
  job.tiff_settings = cat("tone ", image::to_string(tone), "; display pass; ", image::to_string(tiff_compression));
  if (cluster_config) job.png_settings = cat("tone ", image::to_string(tone));
  job.exr_settings = cat("pixels ", image::to_string(exr_type));
  job.out_dir = a.out;
  job.naming = naming;
  job.tone = tone;
  if (a.contact_sheet != "none")
    job.contact_sheet =
        a.contact_sheet.empty() ? job.out_dir / "contact-sheet.png" : std::filesystem::path(a.contact_sheet);

  nlohmann::json run_outputs = nlohmann::json::array();
  for (const offline::OutputSpec& o : job.outputs) {
    nlohmann::json keys = nlohmann::json::object();
    for (const offline::ImageFormat f : formats) keys[offline::name_of(f)] = offline::settings_key(job, o, f);
    run_outputs.push_back({{"name", o.name},
                           {"width_px", o.width_px},
                           {"height_px", o.height_px},
                           {"description", o.description},
                           {"settings_keys", std::move(keys)}});
  }
  nlohmann::json run_formats = nlohmann::json::array();
  for (const offline::ImageFormat f : formats) run_formats.push_back(offline::name_of(f));
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
             {"tiff_settings", job.tiff_settings},
             {"exr_settings", job.exr_settings},
             {"frame_name", naming.pattern},
             {"start_number", naming.start_number}};

  if (cluster_config) {
    offline::ClusterRenderSettings settings;
    settings.cluster_file = a.cluster;
    settings.show_file = a.show;
    settings.fps = fps;
    settings.out_dir = a.out;
    if (!a.tables.cache_dir.empty()) settings.cache_directory = std::filesystem::path(a.tables.cache_dir);
    settings.cpu_precompute = a.tables.cpu_precompute;
    std::optional<offline::ClusterFrameRenderer> cluster_renderer;
    job.before_rendering = [&](std::uint64_t frames, const std::set<scene::TableHash>&) {
      spdlog::info("rendering {} frame{} of '{}' at {} fps on the nodes of {} into {}/<output>/<output>.NNNNNN.{}",
                   frames, frames == 1 ? "" : "s", show.name(), fps, a.cluster, a.out, cluster_config->output_format);
      cluster_renderer.emplace(settings);
    };
    /// Starts the cluster only when there is something to render (before_rendering).
    struct Deferred final : offline::FrameRenderer {
      std::optional<offline::ClusterFrameRenderer>& renderer;
      explicit Deferred(std::optional<offline::ClusterFrameRenderer>& r) : renderer(r) {}
      void render_frame(const scene::FrameDescription& state,
                        const std::vector<std::vector<std::filesystem::path>>& files) override {
        renderer->render_frame(state, files);
      }
    } deferred(cluster_renderer);
    const offline::RenderSummary summary = offline::run_render_job(job, deferred);
    cluster_renderer.reset();  // Goodbye to the nodes before the summary
    fmt::print("{}\n", offline::describe(summary));
    return;
  }

  render::gl::ContextOptions context_options;
  context_options.prefer = render::gl::parse_device_preference(a.device);
  offline::PipelineSettings pipeline;
  pipeline.formats = formats;
  pipeline.tone = tone;
  pipeline.exr_type = exr_type;
  pipeline.png_compression = png_compression;
  pipeline.tiff_compression = tiff_compression;
  pipeline.threads = a.threads.value_or(-1);
  pipeline.frames_in_flight = a.frames_in_flight.value_or(0);
  pipeline.serial_compile = a.serial_compile;
  std::optional<offline::VideoProxy> video;
  if (!a.video.empty()) {
    if (std::none_of(formats.begin(), formats.end(), offline::is_display_format))
      throw std::invalid_argument(fmt::format(
          "--video {}: needs a display format among --format (png, png16 or tiff); exr is linear", a.video));
    const offline::LocalOutput& first_output = outputs.local.front();
    const bool eight = std::find(formats.begin(), formats.end(), offline::ImageFormat::png) != formats.end();
    video.emplace(a.video, first_output.projection->width(), first_output.projection->height(), eight ? 8 : 16, fps);
    pipeline.published = [&video](const offline::DisplayFrame& frame) { video->write(frame.rgba); };
  }
  offline::LocalFrameRenderer renderer(show, std::move(versions), std::move(outputs.local), std::move(pipeline), colour,
                                       request, context_options);
  job.before_rendering = [&](std::uint64_t frames, const std::set<scene::TableHash>& table_hashes) {
    spdlog::info("rendering {} frame{} of '{}' at {} fps into {}/<output>/{}.{} on {}", frames, frames == 1 ? "" : "s",
                 show.name(), fps, a.out, naming.pattern, a.format, renderer.device());
    if (video && frames != last - first + 1)
      spdlog::warn("--video {}: covers the {} frames rendered by this run, not the {} already on disk", a.video, frames,
                   last - first + 1 - frames);
    renderer.precompute_missing(plan, table_hashes);
  };
  const offline::RenderSummary summary = offline::run_render_job(job, renderer);
  if (video) {
    video->finish();
    spdlog::info("--video {}: {} frames encoded by ffmpeg", a.video, video->frames());
  }
  fmt::print("{}\n", offline::describe(summary));
}

}  // namespace

void register_show_render(CLI::App& show_command) {
  auto a = std::make_shared<ShowRenderArgs>();
  CLI::App* cmd = show_command.add_subcommand(
      "render",
      "Render every frame of a show at a fixed frame rate to numbered PNG/TIFF/EXR files per output, resumable "
      "(docs/shows.md, \"Offline rendering\")");
  cmd->add_option("--show", a->show, "Show file (configs/shows/)")->required();
  cmd->add_option("--out", a->out, "Output folder: DIR/<output>/<output>.<frame:06d>.png|tif|exr, DIR/manifest.json")
      ->required();
  cmd->add_option("--cluster", a->cluster,
                  "Render on the nodes of this cluster config (all on this machine; its viewports, tables and format)");
  cmd->add_option("--viewport", a->viewport,
                  "Render output NAME of a viewport config (CONFIG.json#NAME), or every output (CONFIG.json)");
  add_view_options(cmd, a->projection, "fisheye or planar (with --size), instead of --viewport", a->fov_deg,
                   a->tilt_deg, a->size, "WIDTHxHEIGHT in pixels (with --projection)");
  cmd->add_option("--fps", a->fps, "Frame rate [Hz] in (0, 1000] (default: the show's)");
  cmd->add_option("--from", a->from, "First frame to render (default 0)");
  cmd->add_option("--to", a->to, "Last frame to render, inclusive (default: the show's last)");
  cmd->add_option("--format", a->format,
                  "Comma list of png (8-bit, default), png16, tiff (16-bit) and exr (linear), e.g. png,exr");
  cmd->add_option("--png-compression", a->png_compression,
                  "fast (default: zlib 1, Sub filter), default (zlib 6, adaptive filters), best (9) or a level 0-9");
  cmd->add_option("--tiff-compression", a->tiff_compression, "deflate (default), lzw or none");
  cmd->add_option("--frame-name", a->frame_name,
                  "File name pattern in each output's folder: one %d or %0Nd, optionally {output}; the extension "
                  "is the format's (default {output}.%06d)");
  cmd->add_option("--start-number", a->start_number, "The number of frame 0 in file names (default 0)");
  cmd->add_option("--threads", a->threads,
                  "Encoding and writing threads (default: the CPUs; 1 on a CPU rasterizer); 0: the simple path, "
                  "one frame at a time");
  cmd->add_option("--frames-in-flight", a->frames_in_flight,
                  "Frames whose pixels may be held at once, in [1, 64] (default threads + 2): bounds the memory");
  cmd->add_flag("--serial-compile", a->serial_compile,
                "Build the renderer's and the precompute's programs one at a time where first used, instead of "
                "starting each frame's together on the driver's compiler threads (to compare; the start-up line "
                "says what they took)");
  cmd->add_option("--video", a->video, "Also pipe the frames to ffmpeg for an H.264 review proxy FILE (.mp4)");
  cmd->add_option("--contact-sheet", a->contact_sheet,
                  "Contact sheet PNG of 24 evenly spaced frames (default DIR/contact-sheet.png; none: no sheet)");
  add_image_options(cmd, a->exr_type, a->tone, a->colour);
  add_table_options(cmd, a->tables.tables, a->tables.orders, a->tables.cache_dir);
  add_cpu_precompute_flag(cmd, a->tables.cpu_precompute);
  add_gl_device_option(cmd, a->device);
  a->add_limits(cmd);
  cmd->callback([a, cmd] { run_show_render(*a, cmd->count("--size") > 0, cmd->count("--format") > 0); });
}

void register_show_plan(CLI::App& show_command) {
  auto a = std::make_shared<ShowRenderArgs>();
  CLI::App* cmd = show_command.add_subcommand(
      "plan",
      "Print the lookup-table sets a show needs at a frame rate, their size and which are cached, and for a show by "
      "date and place the solar eclipse its sky holds or the next one its site sees");
  cmd->add_option("--show", a->show, "Show file (configs/shows/)")->required();
  cmd->add_option("--fps", a->fps, "Frame rate [Hz] in (0, 1000] (default: the show's)");
  add_table_options(cmd, a->tables.tables, a->tables.orders, a->tables.cache_dir);
  a->add_limits(cmd);
  cmd->callback([a] {
    const show::Show loaded = show::load_show(a->show, a->limits());
    const double fps = frame_rate(loaded, a->fps);
    const show::TablePlan plan = plan_for(loaded, fps, table_request(a->tables));
    fmt::print(stderr, "{}", show::budget_warning(plan, a->table_budget_gib));
    fmt::print("{}", show::describe(plan));
    if (const std::optional<show::EclipsePlan> eclipses = show::plan_eclipses(loaded))
      fmt::print("{}", show::describe(*eclipses));
  });
}

}  // namespace zenith::app
