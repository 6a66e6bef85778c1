// `zenith render`: one frame of a scene through a planar or fisheye projection,
// written as a linear OpenEXR and/or an 8-bit sRGB PNG preview; with --window,
// the same renderer on a window's GL context, explored with the keyboard
// (docs/window.md); with --viewport CONFIG#NAME, one output of a viewport
// config (its projection, warp, size, blend mask and black level;
// docs/viewports.md), or every output of the config without #NAME.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "apps/cli_options.h"
#include "apps/commands.h"
#include "core/progress_bar.h"
#include "core/units.h"
#include "image/image_writer.h"
#include "offline/output_rendering.h"
#include "render/gl/egl_context.h"
#include "render/lut/table_provider.h"
#include "render/renderer.h"
#include "render/window/frame_presenter.h"
#include "render/window/window_context.h"
#include "scene/scene_loader.h"
#include "warp/blending.h"
#include "warp/viewport_config.h"

namespace zenith::app {
namespace {

struct RenderArgs {
  std::string scene, projection = "fisheye", size = "1024x1024", tables = "paper", cache_dir, device = "auto";
  std::string exr_type = "half", tone = "exponential", colour = "auto";
  std::vector<std::string> outputs;
  std::optional<double> fov_deg, tilt_deg, exposure;
  bool no_cache = false, cpu_precompute = false, no_sun_disc = false, no_limb_darkening = false;
  bool single_scattering = false, bodies_only = false, no_eclipses = false, fp64 = false;
  int orders = atmosphere::lut::kDefaultScatteringOrders;
  bool window = false;        ///< show the frame in a window and explore the scene
  std::optional<int> frames;  ///< --window: close after this many presented frames
  std::string viewport;       ///< --viewport CONFIG[#NAME]
  /// Which of the options a viewport replaces were given on the command line.
  bool projection_given = false, size_given = false;
};

std::unique_ptr<warp::Projection> make_projection(const RenderArgs& a, int width, int height) {
  return app::make_projection(a.projection, a.fov_deg, a.tilt_deg, width, height);
}

render::TableRequest make_table_request(const RenderArgs& a) {
  return app::make_table_request(a.tables, a.orders, a.cpu_precompute, !a.no_cache, a.cache_dir);
}

render::RenderOptions make_render_options(const RenderArgs& a) {
  render::RenderOptions options;
  options.atmospheres = !a.bodies_only;
  options.sun_disc = !a.no_sun_disc;
  options.limb_darkening = !a.no_limb_darkening;
  options.atmosphere.multiple_scattering = !a.single_scattering;
  options.atmosphere.eclipses = !a.no_eclipses;
  options.atmosphere.fp64 = a.fp64;
  options.colour = image::parse_colour_mapping(a.colour);
  // A window's frames are live: they never wait for the Moon's shadow nor for a new program variant.
  options.background_shadow_builds = a.window;
  options.background_variant_builds = a.window;
  // A cold start builds one tile program per shell, not one per tile kind (the same pixels).
  options.tile_programs = render::TilePrograms::own_once_built;
  options.albedo_cache_directory = render::cache_directory_of(make_table_request(a));
  options.program_cache_directory = render::program_cache_directory_of(make_table_request(a));
  return options;
}

void log_frame_stats(const render::FrameStats& s) {
  for (const auto& atm : s.atmospheres)
    spdlog::info("atmosphere of '{}': {} of {} tiles", atm.body, atm.tiles, atm.tiles_total);
  spdlog::info("frame rendered in {:.3f} s ({} band{})", s.seconds, s.bands, s.bands == 1 ? "" : "s");
}

/// `text` with every "{name}" replaced by `name`.
std::string substitute_name(std::string text, const std::string& name) {
  for (std::size_t at = text.find("{name}"); at != std::string::npos; at = text.find("{name}", at + name.size()))
    text.replace(at, 6, name);
  return text;
}

/// Renders one frame into every file of `outputs` (render_to_files in
/// offline/output_rendering.h) with a progress bar over the rows.
void render_to_files(render::Renderer& renderer, const scene::Scene& scene, const warp::Projection& projection,
                     const std::vector<std::string>& outputs, const RenderArgs& a,
                     const image::ImageAttributes& attributes, const warp::BlendMask* blend, double black_level,
                     const warp::MpcdiColourProfile* colour = nullptr) {
  OutputStage stage;
  stage.colour = colour;
  stage.tone = image::parse_tone_mapping(a.tone);
  stage.exr_type = image::parse_exr_pixel_type(a.exr_type);
  stage.blend = blend;
  stage.black_level = black_level;
  const int height = projection.height();
  core::ProgressBar bar("render");
  app::render_to_files(renderer, scene, projection, std::vector<std::filesystem::path>(outputs.begin(), outputs.end()),
                       stage, attributes, [&](int first_row, int row_count) {
                         bar.update(fmt::format("rows {}–{}", first_row, first_row + row_count - 1),
                                    static_cast<double>(first_row + row_count) / height);
                       });
  bar.finish();
  log_frame_stats(renderer.last_frame());
  for (const auto& out : outputs) fmt::print("written {}\n", out);
}

// ---------------------------------------------------------------------------
// The window's view controls: how keys move the camera and the sun.

constexpr double kTurnStepRad = 2.0 * core::kPi / 180.0;  ///< arrows, ',' and '.'
constexpr double kFastTurnFactor = 5.0;                   ///< with Shift
constexpr double kMoveFraction = 0.1;                     ///< PageUp/PageDown: of the altitude
constexpr double kMinAltitudeM = 1.0;                     ///< the camera stays this high above every body
constexpr double kExposureStep = 1.25;                    ///< '[' and ']'

/// The body whose surface is nearest to `point` (scene::nearest_body), or null in an empty scene.
const scene::Body* nearest_body(const scene::Scene& scene, const glm::dvec3& point) {
  return scene.bodies.empty() ? nullptr : &scene.bodies[scene::nearest_body(scene.bodies, point)];
}

/// The camera's local up: away from the nearest body's centre, else world +z.
glm::dvec3 local_up(const scene::Scene& scene) {
  const scene::Body* body = nearest_body(scene, scene.camera.position_m);
  if (body == nullptr) return {0.0, 0.0, 1.0};
  const glm::dvec3 away = scene.camera.position_m - body->position_m;
  const double length = glm::length(away);
  return length > 0.0 ? away / length : glm::dvec3(0.0, 0.0, 1.0);
}

/// Turns the camera about its position: `yaw_rad` about the local up (positive
/// turns left, counter-clockwise seen from above), then `pitch_rad` about its
/// right axis (positive looks up).
void turn_camera(scene::Scene& scene, double yaw_rad, double pitch_rad) {
  glm::dquat& q = scene.camera.orientation;
  if (yaw_rad != 0.0) q = glm::angleAxis(yaw_rad, local_up(scene)) * q;
  if (pitch_rad != 0.0) q = glm::angleAxis(pitch_rad, q * glm::dvec3(1.0, 0.0, 0.0)) * q;
  q = glm::normalize(q);
}

/// Moves the camera along its forward axis by `fraction` of its altitude above
/// the nearest body (negative: backward), keeping it kMinAltitudeM above every
/// body's surface.
void move_camera(scene::Scene& scene, double fraction) {
  glm::dvec3& p = scene.camera.position_m;
  const scene::Body* body = nearest_body(scene, p);
  const double altitude = body != nullptr ? glm::length(p - body->position_m) - body->radius_m : glm::length(p);
  const glm::dvec3 forward = scene.camera.orientation * glm::dvec3(0.0, 0.0, -1.0);
  p += forward * (fraction * std::max(altitude, kMinAltitudeM));
  for (const scene::Body& b : scene.bodies) {
    const glm::dvec3 away = p - b.position_m;
    const double distance = glm::length(away);
    const double floor = b.radius_m + kMinAltitudeM;
    if (distance < floor) p = b.position_m + (distance > 0.0 ? away / distance : local_up(scene)) * floor;
  }
}

/// Rotates the sun's direction by `angle_rad` about the nearest body's polar
/// axis (world +z without bodies): the time of day. Negative moves the sun
/// westward, as the day advances on a prograde-rotating body.
void rotate_sun(scene::Scene& scene, double angle_rad) {
  const scene::Body* body = nearest_body(scene, scene.camera.position_m);
  const glm::dvec3 axis = body != nullptr ? body->orientation * glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(0.0, 0.0, 1.0);
  scene.sun.direction = glm::normalize(glm::angleAxis(angle_rad, glm::normalize(axis)) * scene.sun.direction);
}

void log_key_help() {
  spdlog::info("window keys: arrows turn the camera (yaw about the local up, pitch about its right axis; Shift: 5x)");
  spdlog::info("window keys: PageUp/PageDown move forward/backward by 10% of the altitude");
  spdlog::info("window keys: [ / ] exposure /1.25 and x1.25; , / . turn the sun -2/+2 deg about the body's axis");
  spdlog::info("window keys: P saves a PNG screenshot; Escape (or closing the window) quits");
}

/// A path for the next screenshot: next to the first --out (its stem, "-<n>.png")
/// or zenith-window-<n>.png in the working directory; n counts up past existing files.
std::filesystem::path next_screenshot_path(const RenderArgs& a, int& counter) {
  for (;;) {
    ++counter;
    std::filesystem::path path;
    if (!a.outputs.empty()) {
      const std::filesystem::path first(a.outputs.front());
      path = first.parent_path() / fmt::format("{}-{}.png", first.stem().string(), counter);
    } else {
      path = fmt::format("zenith-window-{}.png", counter);
    }
    if (!std::filesystem::exists(path)) return path;
  }
}

/// What one key press did to the view.
enum class KeyEffect { none, scene_changed, screenshot, quit };

KeyEffect apply_key(const render::window::KeyEvent& e, scene::Scene& scene) {
  using render::window::Key;
  const double turn = kTurnStepRad * (e.shift ? kFastTurnFactor : 1.0);
  switch (e.key) {
    case Key::left: turn_camera(scene, turn, 0.0); return KeyEffect::scene_changed;
    case Key::right: turn_camera(scene, -turn, 0.0); return KeyEffect::scene_changed;
    case Key::up: turn_camera(scene, 0.0, turn); return KeyEffect::scene_changed;
    case Key::down: turn_camera(scene, 0.0, -turn); return KeyEffect::scene_changed;
    case Key::page_up: move_camera(scene, kMoveFraction); return KeyEffect::scene_changed;
    case Key::page_down: move_camera(scene, -kMoveFraction); return KeyEffect::scene_changed;
    case Key::left_bracket:
    case Key::right_bracket: {
      const double e_new =
          e.key == Key::left_bracket ? scene.camera.exposure / kExposureStep : scene.camera.exposure * kExposureStep;
      scene.camera.exposure = std::clamp(e_new, 1e-9, 1e6);
      spdlog::info("exposure {:.4g}", scene.camera.exposure);
      return KeyEffect::scene_changed;
    }
    case Key::comma: rotate_sun(scene, -turn); return KeyEffect::scene_changed;
    case Key::period: rotate_sun(scene, turn); return KeyEffect::scene_changed;
    case Key::p: return KeyEffect::screenshot;
    case Key::escape: return KeyEffect::quit;
    default: return KeyEffect::none;
  }
}

/// `zenith render --window`: the renderer on the window's GL context, one
/// render per change of the view, presented until the window closes (or after
/// --frames presented frames). --out files receive the last frame on exit.
void run_window(const RenderArgs& a, scene::Scene scene, const warp::Projection& projection, int width, int height) {
  if (a.device != "auto")
    spdlog::warn("--device {}: applies to the headless path; the window system picks the GL device", a.device);
  render::window::WindowOptions window_options;
  window_options.title = fmt::format("zenith: {}", scene.name);
  window_options.width = width;
  window_options.height = height;
  render::window::WindowContext window(window_options);
  spdlog::info("rendering '{}' {} in a window on {}", scene.name, projection.describe(), window.renderer());

  // Destroyed before the window: they hold GL objects of its context.
  const render::TableRequest request = make_table_request(a);
  render::Renderer renderer(make_render_options(a), [&](const atmosphere::AtmosphereModel& model) {
    // The GPU precompute runs on a headless EGL context of its own, which
    // cannot become current on this thread while the window's (GLX) one is.
    window.release_current();
    render::ObtainedTables t = render::obtain_tables(model, request);
    window.make_current();
    return std::move(t.tables);
  });
  render::window::FramePresenter presenter;
  const image::ToneMapping tone = image::parse_tone_mapping(a.tone);
  log_key_help();

  std::vector<float> frame;
  bool stale = true, uploaded = false, screenshot_pending = false;
  int presented = 0, screenshots = 0;
  while (!window.should_close()) {
    if (stale) {
      frame = renderer.render_image(scene, projection);
      presenter.upload(frame, width, height);
      stale = false;
      uploaded = true;
      spdlog::debug("frame rendered in {:.3f} s", renderer.last_frame().seconds);
      window.set_title(fmt::format("zenith: {} (exposure {:.4g}, {:.2f} s)", scene.name, scene.camera.exposure,
                                   renderer.last_frame().seconds));
    }
    if (screenshot_pending) {  // after the re-render, so it shows every key pressed before P
      const std::filesystem::path path = next_screenshot_path(a, screenshots);
      if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
      image::write_png(path, width, height, frame, tone, image_attributes(scene, projection));
      spdlog::info("screenshot written to {}", path.string());
      screenshot_pending = false;
    }
    // Draw when the frame or the window changed; --frames draws every pass.
    const bool redraw = window.take_redraw_request() || uploaded || a.frames.has_value();
    const render::window::FramebufferSize fb = window.framebuffer_size();
    if (redraw && fb.width > 0 && fb.height > 0) {  // zero while minimised
      presenter.draw(tone, {0, fb.width, fb.height});
      window.swap_buffers();
      uploaded = false;
      ++presented;
      if (a.frames && presented >= *a.frames) break;
    }
    if (a.frames && fb.width > 0 && fb.height > 0)
      window.poll_events();
    else
      window.wait_events(0.5);
    for (const render::window::KeyEvent& e : window.take_key_events()) {
      if (e.action == render::window::KeyAction::release) continue;
      switch (apply_key(e, scene)) {
        case KeyEffect::scene_changed: stale = true; break;
        case KeyEffect::screenshot:
          screenshot_pending = screenshot_pending || e.action == render::window::KeyAction::press;
          break;
        case KeyEffect::quit: window.request_close(); break;
        case KeyEffect::none: break;
      }
    }
  }
  spdlog::info("window closed after {} presented frame{}", presented, presented == 1 ? "" : "s");

  if (a.outputs.empty() || frame.empty()) return;
  const image::ImageAttributes attributes = image_attributes(scene, projection);
  const image::ExrPixelType exr_type = image::parse_exr_pixel_type(a.exr_type);
  for (const auto& out : a.outputs) {
    const std::filesystem::path path(out);
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    if (path.extension() == ".exr")
      image::write_exr(path, width, height, frame, exr_type, attributes);
    else
      image::write_png(path, width, height, frame, tone, attributes);
    fmt::print("written {}\n", out);
  }
}

/// The viewport part of `zenith render`: CONFIG#NAME renders output NAME,
/// CONFIG alone every output; "{name}" in --out becomes the output's name, and
/// an --out ending in '/' means DIR/{name}.png.
void run_viewport_render(const RenderArgs& a, const scene::Scene& scene) {
  if (a.projection_given || a.size_given || a.fov_deg || a.tilt_deg)
    throw std::invalid_argument(
        "--viewport: the viewport config gives each output's projection and size; drop --projection, --size, "
        "--fov and --tilt");
  if (a.window) throw std::invalid_argument("--viewport renders to files; --window shows a plain projection");
  const ViewportSelection selection = select_viewport_outputs(a.viewport);
  const warp::ViewportConfig& config = selection.config;
  const std::vector<std::size_t>& indices = selection.indices;
  // Each output's files: {name} substituted, DIR/ → DIR/{name}.png.
  auto files_of = [&](const warp::OutputConfig& o) {
    std::vector<std::string> files;
    for (const auto& out : a.outputs) {
      const std::string pattern = !out.empty() && out.back() == '/' ? out + "{name}.png" : out;
      files.push_back(substitute_name(pattern, o.name));
    }
    return files;
  };
  if (indices.size() > 1)
    for (const auto& out : a.outputs)
      if (out.find("{name}") == std::string::npos && (out.empty() || out.back() != '/'))
        throw std::invalid_argument(fmt::format(
            "--out '{}': --viewport without #NAME renders {} outputs: give a folder (DIR/) or a pattern with "
            "{{name}} (out/{{name}}.exr)",
            out, indices.size()));
  for (const auto& out : a.outputs) {
    const std::string pattern = !out.empty() && out.back() == '/' ? out + "x.png" : out;
    const auto ext = std::filesystem::path(pattern).extension().string();
    if (ext != ".exr" && ext != ".png")
      throw std::invalid_argument(
          fmt::format("--out '{}': the file name must end in .exr or .png (or the folder in /)", out));
  }

  render::gl::ContextOptions context_options;
  context_options.prefer = render::gl::parse_device_preference(a.device);
  render::gl::HeadlessContext context(context_options);
  const render::TableRequest request = make_table_request(a);
  render::RenderOptions options = make_render_options(a);
  // The outputs take the sky-view table's path alike, whatever their sizes (no seam between them).
  options.sky_view_table = render::sky_view_use_for_outputs(config.largest_output_pixels());
  render::Renderer renderer(options, [&](const atmosphere::AtmosphereModel& model) {
    render::ObtainedTables t = render::obtain_tables(model, request);
    context.make_current();
    return std::move(t.tables);
  });
  for (const std::size_t i : indices) {
    const warp::OutputConfig& o = config.outputs[i];
    spdlog::info("rendering '{}' output '{}' of viewport '{}': {} on {}", scene.name, o.name, config.name,
                 o.projection->describe(), context.renderer());
    const warp::BlendMask mask = warp::output_blend_mask(config, i);
    image::ImageAttributes attributes = image_attributes(scene, *o.projection);
    for (auto& attribute : viewport_attributes(selection.file, o)) attributes.push_back(std::move(attribute));
    render_to_files(renderer, scene, *o.projection, files_of(o), a, attributes, &mask, o.black_level, o.colour.get());
  }
}

void run_render(const RenderArgs& a) {
  if (a.outputs.empty() && !a.window) throw std::invalid_argument("--out: give at least one FILE.exr or FILE.png");
  if (a.frames && !a.window) throw std::invalid_argument("--frames applies to --window only");
  scene::Scene scene = scene::load_scene(a.scene);
  if (a.exposure) {
    if (!(*a.exposure > 0.0 && *a.exposure <= 1e6))
      throw std::invalid_argument(fmt::format("--exposure {}: must be in (0, 1e6]", *a.exposure));
    scene.camera.exposure = *a.exposure;
  }
  if (!a.viewport.empty()) {
    run_viewport_render(a, scene);
    return;
  }
  for (const auto& out : a.outputs) {
    const auto ext = std::filesystem::path(out).extension().string();
    if (ext != ".exr" && ext != ".png")
      throw std::invalid_argument(fmt::format("--out '{}': the file name must end in .exr or .png", out));
  }
  const auto [width, height] = parse_size(a.size);
  const auto projection = make_projection(a, width, height);
  if (a.window) {
    run_window(a, std::move(scene), *projection, width, height);
    return;
  }

  render::gl::ContextOptions context_options;
  context_options.prefer = render::gl::parse_device_preference(a.device);
  render::gl::HeadlessContext context(context_options);
  spdlog::info("rendering '{}' {} on {}", scene.name, projection->describe(), context.renderer());

  const render::TableRequest request = make_table_request(a);
  render::Renderer renderer(make_render_options(a), [&](const atmosphere::AtmosphereModel& model) {
    render::ObtainedTables t = render::obtain_tables(model, request);
    context.make_current();  // the GPU precompute may have used a context of its own
    return std::move(t.tables);
  });
  render_to_files(renderer, scene, *projection, a.outputs, a, image_attributes(scene, *projection), nullptr, 0.0);
}

}  // namespace

void register_render_command(CLI::App& app) {
  auto a = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render one frame of a scene to EXR (linear) and/or PNG (sRGB)");
  cmd->add_option("--scene", a->scene, "Scene JSON file (configs/scenes/)")->required();
  cmd->add_option("--viewport", a->viewport,
                  "Render output NAME of a viewport config (CONFIG.json#NAME: its projection, warp, size, blend and "
                  "black level), or every output (CONFIG.json, with --out DIR/ or --out out/{name}.exr); "
                  "docs/viewports.md");
  add_view_options(cmd, a->projection, "planar or fisheye (default: fisheye, a dome master)", a->fov_deg, a->tilt_deg,
                   a->size, "WIDTHxHEIGHT in pixels (default 1024x1024)");
  cmd->add_option("--out", a->outputs,
                  "Output FILE.exr and/or FILE.png (repeatable; with --window optional: the last frame shown)");
  add_image_options(cmd, a->exr_type, a->tone, a->colour);
  cmd->add_option("--exposure", a->exposure, "Override the scene camera's exposure");
  add_table_options(cmd, a->tables, a->orders, a->cache_dir);
  cmd->add_flag("--no-cache", a->no_cache, "Neither read nor write the table cache");
  add_cpu_precompute_flag(cmd, a->cpu_precompute);
  add_gl_device_option(cmd, a->device);
  cmd->add_flag("--no-sun-disc", a->no_sun_disc, "Do not draw the sun's disc");
  cmd->add_flag("--no-limb-darkening", a->no_limb_darkening, "Draw the sun as a uniform disc");
  cmd->add_flag("--single-scattering", a->single_scattering, "Drop multiple scattering at render time");
  cmd->add_flag("--no-eclipses", a->no_eclipses, "Ignore shadows of bodies on other bodies");
  cmd->add_flag("--bodies-only", a->bodies_only, "No atmospheres: bodies lit by the sun only");
  cmd->add_flag("--fp64", a->fp64, "Atmosphere pass in double precision");
  cmd->add_flag("--window", a->window,
                "Show the frame in a window and explore the scene with the keys (docs/window.md)");
  cmd->add_option("--frames", a->frames, "--window: close after N presented frames (tests, scripts)")
      ->check(CLI::Range(1, 100000000));
  cmd->callback([a, cmd] {
    // --out is required without --window: the same error CLI11 gives for a required option.
    if (a->outputs.empty() && !a->window) throw CLI::RequiredError("--out");
    a->projection_given = cmd->count("--projection") > 0;
    a->size_given = cmd->count("--size") > 0;
    run_render(*a);
  });
}

}  // namespace zenith::app
