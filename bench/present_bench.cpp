#include "bench/present_bench.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "atmosphere/lut/precompute_options.h"
#include "atmosphere/lut/table_cache.h"
#include "bench/bench_tables.h"
#include "bench/command_line.h"
#include "bench/moving_camera.h"
#include "bench/process_cpu.h"
#include "image/image_writer.h"
#include "image/tone_mapping.h"
#include "render/display/display_encoder.h"
#include "render/gl/egl_context.h"
#include "render/gl/texture.h"
#include "render/renderer.h"
#include "render/window/frame_presenter.h"
#include "render/window/output_windows.h"
#include "scene/scene_loader.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"

namespace zenith::bench {
namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

constexpr const char* kUsage =
    "render_bench --present [--scene FILE] [--size WxH] [--fov DEG] [--frames N] [--rounds R]\n"
    "                       [--tables paper|small] [--orders N] [--cache DIR] [--csv FILE] [--headless] [--no-before]\n"
    "                       [--split] [--moving]\n"
    "  the live frame (render to a texture, display pass, window; no readback) against the path before it\n"
    "  (readback, CPU tone mapping, a PNG file, upload, draw), interleaved; bench/present_bench.h has the details.\n"
    "  --size      WIDTHxHEIGHT (default 1280x720; square: a 180 deg fisheye dome master, else planar)\n"
    "  --fov       horizontal field of a planar view in degrees (default 90)\n"
    "  --frames    timed frames per case and round (default 5); --rounds R (default 3)\n"
    "  --headless  no window even with DISPLAY set: the frame stops at the display texture\n"
    "  --no-before only the live frame\n"
    "  --split     time the live frame's steps apart (render to a texture, display pass, window; glFinish\n"
    "              between) instead of the node's fused frame (each band straight into the display texture)\n"
    "  --moving    the camera and the sun turn by 1 µrad every frame (bench/moving_camera.h): no frame\n"
    "              reuses the tile classification or sky-view tables of the one before, as in a show\n"
    "              whose camera and clock run\n";

struct Options {
  fs::path scene = fs::path(ZENITH_SOURCE_DIR) / "configs/scenes/earth-ground-view.json";
  int width = 1280, height = 720;
  double fov_deg = 90.0;
  int frames = 5, rounds = 3;
  std::string tables = "paper";
  int orders = atmosphere::lut::kDefaultScatteringOrders;
  std::optional<fs::path> cache;
  fs::path csv = fs::path(ZENITH_SOURCE_DIR) / "bench/results/present_frame_times.csv";
  bool headless = false, before = true, split = false, moving = false;
};

Options parse(int argc, char** argv) {
  Options o;
  for (CommandLine args(argc, argv); args.next();) {
    const std::string& a = args.option();
    if (a == "--present") continue;
    if (a == "--scene")
      o.scene = args.value();
    else if (a == "--size") {
      const std::string v = args.value();
      const auto x = v.find_first_of("xX");
      if (x == std::string::npos) throw std::invalid_argument("--size '" + v + "': expected WIDTHxHEIGHT");
      o.width = std::stoi(v.substr(0, x));
      o.height = std::stoi(v.substr(x + 1));
      if (o.width < 16 || o.height < 16 || o.width > 16384 || o.height > 16384)
        throw std::invalid_argument("--size '" + v + "': width and height must be in [16, 16384]");
    } else if (a == "--fov") {
      o.fov_deg = std::stod(args.value());
      if (!(o.fov_deg > 0.0 && o.fov_deg < 180.0)) throw std::invalid_argument("--fov: must be in (0, 180)");
    } else if (a == "--frames") {
      o.frames = std::stoi(args.value());
      if (o.frames < 1 || o.frames > 10000) throw std::invalid_argument("--frames: must be in [1, 10000]");
    } else if (a == "--rounds") {
      o.rounds = std::stoi(args.value());
      if (o.rounds < 1 || o.rounds > 100) throw std::invalid_argument("--rounds: must be in [1, 100]");
    } else if (a == "--tables") {
      o.tables = args.value();
      if (o.tables != "paper" && o.tables != "small") throw std::invalid_argument("--tables: use paper or small");
    } else if (a == "--orders") {
      o.orders = std::stoi(args.value());
      if (o.orders < 1 || o.orders > 50) throw std::invalid_argument("--orders: must be in [1, 50]");
    } else if (a == "--cache")
      o.cache = args.value();
    else if (a == "--csv")
      o.csv = args.value();
    else if (a == "--headless")
      o.headless = true;
    else if (a == "--no-before")
      o.before = false;
    else if (a == "--split")
      o.split = true;
    else if (a == "--moving")
      o.moving = true;
    else
      help_or_unknown_option(a, kUsage);
  }
  return o;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// One case's frames.
struct Times {
  std::vector<double> wall_ms, gpu_ms;
  std::vector<double> cpu_ms;  ///< CPU time of the process per frame (every thread: a driver's, llvmpipe's too)
  std::vector<double> render_ms, display_ms, window_ms;  ///< live frames: the wall time of each step (glFinish between)
};

}  // namespace

int run_present(int argc, char** argv) {
  const Options opt = parse(argc, argv);
  const char* display_env = std::getenv("DISPLAY");
  const bool window = !opt.headless && display_env != nullptr && *display_env != '\0';

  std::optional<render::gl::HeadlessContext> headless;
  std::optional<render::window::OutputWindows> windows;
  if (window) {
    warp::OutputWindow placed;
    placed.name = "frame";
    placed.position = std::array<int, 2>{0, 0};
    placed.size = std::array<int, 2>{opt.width, opt.height};
    placed.decorated = false;
    placed.vsync = false;  // the frame's cost, not the display's rate
    windows.emplace(std::vector<render::window::ShownOutput>{{"frame", opt.width, opt.height, placed}},
                    "render_bench --present");
  } else {
    headless.emplace();
  }
  auto make_current = [&] {
    if (windows)
      windows->primary().make_current();
    else
      headless->make_current();
  };
  const std::string device = windows ? windows->primary().renderer() : headless->renderer();
  const std::string target = windows ? "window" : "headless";

  const scene::Scene still = scene::load_scene(opt.scene);
  scene::Scene scene = still;  // with --moving, turned a little every frame
  int frame_number = 0;
  atmosphere::lut::PrecomputeOptions table_options;
  table_options.sizes = opt.tables == "small" ? atmosphere::lut::TableSizes::small() : atmosphere::lut::TableSizes{};
  table_options.max_orders = opt.orders;
  const atmosphere::lut::TableCache cache(opt.cache.value_or(atmosphere::lut::default_cache_directory()));
  const render::TableSource tables =
      cached_or_precomputed_tables(cache, table_options, opt.tables, render::gl::ContextOptions{}, make_current, [&] {
        if (windows) windows->primary().release_current();
      });
  render::RenderOptions with_options, without_options;
  without_options.atmospheres = false;
  render::Renderer with_atmosphere(with_options, tables), without_atmosphere(without_options, tables);

  std::unique_ptr<warp::Projection> projection;
  if (opt.width == opt.height) {
    warp::FisheyeParameters p;
    p.fov_deg = 180.0;
    projection = std::make_unique<warp::FisheyeProjection>(opt.width, opt.height, p);
  } else {
    projection =
        std::make_unique<warp::PlanarProjection>(warp::PlanarProjection::symmetric(opt.width, opt.height, opt.fov_deg));
  }
  fmt::print("render_bench --present: scene '{}', {}x{} {}, on {} ({})\n", scene.name, opt.width, opt.height,
             projection->describe(), device, target);

  make_current();
  render::gl::Texture radiance =
      render::gl::Texture::create_2d(render::gl::TextureFormat::rgba32f, opt.width, opt.height);
  render::gl::Texture display = render::gl::Texture::create_2d(render::gl::TextureFormat::rgba8, opt.width, opt.height);
  render::display::DisplayEncoder encoder;
  std::optional<render::window::FramePresenter> presenter;
  if (windows && opt.before) presenter.emplace();
  const fs::path frame_file = fs::temp_directory_path() / fmt::format("zenith-present-bench-{}.png", ::getpid());
  GLuint query = 0;
  glGenQueries(1, &query);

  // The live frame: nothing leaves the GPU.
  auto live_frame = [&](render::Renderer& renderer, Times& t) {
    if (opt.moving) move_camera_and_sun(scene, still, ++frame_number);
    const double cpu_start = process_cpu_s();
    const auto start = Clock::now();
    auto since = [](Clock::time_point from) {
      return std::chrono::duration<double, std::milli>(Clock::now() - from).count();
    };
    glBeginQuery(GL_TIME_ELAPSED, query);
    // The node's steady frame: each band straight into the display texture
    // (render_on_gpu + encode_band); with --split the texture path instead, to
    // time the render and the display pass apart.
    if (opt.split) {
      renderer.render_to_texture(scene, *projection, radiance);
      glFinish();
    } else {
      renderer.render_on_gpu(scene, *projection,
                             [&](const render::GpuBand& band) { encoder.encode_band(band, {}, display); });
    }
    const auto rendered = Clock::now();
    if (opt.split) {
      encoder.encode(radiance, {}, display);
      glFinish();
    }
    const auto encoded = Clock::now();
    if (windows) {
      const std::vector<const render::gl::Texture*> displays = {&display};
      windows->present(displays, start);  // blit, swap, glFinish
    }
    glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    t.wall_ms.push_back(since(start));
    t.cpu_ms.push_back((process_cpu_s() - cpu_start) * 1e3);
    if (opt.split) {
      t.render_ms.push_back(std::chrono::duration<double, std::milli>(rendered - start).count());
      t.display_ms.push_back(std::chrono::duration<double, std::milli>(encoded - rendered).count());
      t.window_ms.push_back(since(encoded));
    }
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
    t.gpu_ms.push_back(static_cast<double>(ns) * 1e-6);
  };
  // The node's --window path before: readback, CPU display values, a PNG per
  // frame, the picture uploaded and drawn (cluster/node/render_worker.cpp at f28d6b6).
  auto before_frame = [&](render::Renderer& renderer, Times& t) {
    if (opt.moving) move_camera_and_sun(scene, still, ++frame_number);
    const double cpu_start = process_cpu_s();
    const auto start = Clock::now();
    std::vector<float> rgb = renderer.render_image(scene, *projection);
    std::vector<float> shown = rgb;  // OutputWriter::display_image
    for (float& v : shown) v = image::tone_map(v, image::ToneMapping::exponential);
    fs::path partial = frame_file;
    partial += ".partial";
    image::write_png(partial, opt.width, opt.height, rgb, image::ToneMapping::exponential, {});
    fs::rename(partial, frame_file);
    if (windows) {
      std::vector<float> picture(shown.size());  // the outputs side by side (one here)
      std::copy(shown.begin(), shown.end(), picture.begin());
      const render::window::FramebufferSize fb = windows->primary().framebuffer_size();
      presenter->present(picture, opt.width, opt.height, image::ToneMapping::clamp, {0, fb.width, fb.height});
      windows->primary().swap_buffers();
    }
    glFinish();
    t.wall_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    t.cpu_ms.push_back((process_cpu_s() - cpu_start) * 1e3);
  };

  struct Case {
    std::string atmospheres, path;
    render::Renderer* renderer;
    bool live;
  };
  std::vector<Case> cases;
  for (const bool atm : {true, false}) {
    render::Renderer* r = atm ? &with_atmosphere : &without_atmosphere;
    cases.push_back({atm ? "with" : "without", "live", r, true});
    if (opt.before) cases.push_back({atm ? "with" : "without", "before", r, false});
  }
  std::map<std::size_t, Times> times;
  for (std::size_t c = 0; c < cases.size(); ++c) {  // untimed: tables, programs, tile cones
    Times warm;
    cases[c].live ? live_frame(*cases[c].renderer, warm) : before_frame(*cases[c].renderer, warm);
  }
  for (int round = 0; round < opt.rounds; ++round)
    for (int f = 0; f < opt.frames; ++f)
      for (std::size_t c = 0; c < cases.size(); ++c)  // interleaved: a slow moment hits every case alike
        cases[c].live ? live_frame(*cases[c].renderer, times[c]) : before_frame(*cases[c].renderer, times[c]);
  glDeleteQueries(1, &query);
  std::error_code ignored;
  fs::remove(frame_file, ignored);

  if (opt.csv.has_parent_path()) fs::create_directories(opt.csv.parent_path());
  std::ofstream csv(opt.csv);
  if (!csv) throw std::runtime_error("cannot write " + opt.csv.string());
  csv << "device,size,atmospheres,path,target,wall_ms,wall_ms_min,gpu_ms,frames,cpu_ms\n";
  fmt::print("\n{:<12} {:<7} {:>12} {:>12} {:>12} {:>12}  {}\n", "atmosphere", "path", "wall ms", "min ms", "GL ms",
             "CPU ms", "frames");
  std::map<std::string, double> live_ms;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const Times& t = times[c];
    const double wall = median(t.wall_ms), fastest = *std::min_element(t.wall_ms.begin(), t.wall_ms.end());
    const std::string gpu = t.gpu_ms.empty() ? std::string() : fmt::format("{:.3f}", median(t.gpu_ms));
    const double cpu = median(t.cpu_ms);
    fmt::print("{:<12} {:<7} {:>12.2f} {:>12.2f} {:>12} {:>12.2f}  {}\n", cases[c].atmospheres, cases[c].path, wall,
               fastest, gpu.empty() ? "-" : gpu, cpu, t.wall_ms.size());
    csv << '"' << device << "\"," << opt.width << 'x' << opt.height << ',' << cases[c].atmospheres << ','
        << cases[c].path << ',' << target << ',' << fmt::format("{:.3f},{:.3f},", wall, fastest) << gpu << ','
        << t.wall_ms.size() << ',' << fmt::format("{:.3f}", cpu) << '\n';
    if (!t.render_ms.empty())
      fmt::print("{:<12} split: render to texture {:.2f} ms, display pass {:.2f} ms, window {:.2f} ms (medians)\n", "",
                 median(t.render_ms), median(t.display_ms), median(t.window_ms));
    if (cases[c].live)
      live_ms[cases[c].atmospheres] = wall;
    else if (live_ms.count(cases[c].atmospheres) != 0)
      fmt::print("{:<12} before / live: {:.2f}x\n", "", wall / live_ms[cases[c].atmospheres]);
  }
  fmt::print("csv: {}\n", opt.csv.string());
  return 0;
}

}  // namespace zenith::bench
