// Where a show's start goes, cold and warm (docs/shows.md, "Where the start goes").
//
//   build/bench/startup_bench [--show FILE] [--size WxH] [--tables paper|small] [--rounds N]
//                             [--cases warm,cold-mesa,cold-programs,cold-maps,cold-unwarmed] [--csv FILE] [--passes-csv
//                             FILE]
//                             [--cache DIR] [--zenith PATH] [--spirv-csv FILE] [--parts starts,passes,spirv]
//                             [--spirv-no-dispatch]
//
// 1. The process: `zenith show render --show FILE --projection fisheye --size WxH --to 0`, run as a
//    user runs it, in four cases, each --rounds times, interleaved:
//      warm           Mesa's shader cache and zenith's caches (tables, albedo maps, program binaries) as a
//                     second run leaves them;
//      cold-mesa      Mesa's shader cache empty (evicted, or turned off), zenith's caches warm: the programs
//                     from zenith's stored binaries, their machine code generated again;
//      cold-programs  Mesa's cache and zenith's program binaries empty (a new machine, a new driver): every
//                     program compiled again; tables and maps from the cache;
//      cold-maps      that, and a cache holding the tables only: the albedo maps generated again;
//      cold-unwarmed  cold-mesa with --serial-compile: every first dispatch's machine code generated on the
//                     renderer's thread, none on the warm-up thread (render/gl/first_dispatch_warmup.h).
//    Wall time of the whole process and the phases of its start-up line (offline/offline_frame_renderer.h),
//    the median per case; every run to --csv.
// 2. The programs: a child process with an empty Mesa cache renders the show's scene twice in process, every
//    pass timed (RenderOptions::time_passes: glFinish-bracketed); each pass's first-frame time less its
//    second's is its programs' first-use cost (on llvmpipe, generating their machine code at the first
//    dispatch); to --passes-csv, with the warm cache's figures beside them.
// 3. SPIR-V against GLSL (GL_ARB_gl_spirv), and each program's build time: the show's compute programs as
//    the renderer gives them to the driver (a run with empty caches and ZENITH_SHADER_DUMP_DIR) and the
//    precompute's (`zenith precompute` of earth-advanced, 2 orders, no cache), each made into SPIR-V for
//    OpenGL by glslangValidator (-G, locations and bindings mapped automatically), then built from either in
//    a child with the driver's disk cache off and dispatched once, --rounds times (bench/spirv_compile.h):
//    the medians, the first round's builds, and glslangValidator's own time, to --spirv-csv. Skipped where
//    glslangValidator (Debian glslang-tools) or the extension is missing. --spirv-no-dispatch builds without
//    the dispatch: a program run with nothing bound is safe on llvmpipe only, and a GPU driver generates
//    its code at the link, which the build already times.
//
// The driver's shader cache is Mesa's or NVIDIA's: each case points both at its own folder
// (MESA_SHADER_CACHE_DIR, __GL_SHADER_DISK_CACHE_PATH) or turns both off. --parts runs some of the three.
//
// The tables come from --cache (default: zenith's own cache); the first, unrecorded run precomputes
// what it lacks.
#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "atmosphere/lut/table_cache.h"
#include "bench/bench_tables.h"
#include "bench/command_line.h"
#include "bench/spirv_compile.h"
#include "render/gl/egl_context.h"
#include "render/render_flags.h"
#include "render/renderer.h"
#include "show/show.h"
#include "warp/fisheye_projection.h"

extern char** environ;

namespace zenith::bench {
namespace {

namespace fs = std::filesystem;

struct Options {
  fs::path show = fs::path(ZENITH_SOURCE_DIR) / "bench/shows/three-worlds-dome.json";
  fs::path zenith = ZENITH_BINARY;
  int width = 512, height = 512;
  std::string tables = "paper";
  int rounds = 3;
  std::vector<std::string> cases = {"warm", "cold-mesa", "cold-programs", "cold-maps", "cold-unwarmed"};
  fs::path csv = fs::path(ZENITH_SOURCE_DIR) / "bench/results/startup_times.csv";
  fs::path passes_csv = fs::path(ZENITH_SOURCE_DIR) / "bench/results/startup_pass_compile.csv";
  fs::path spirv_csv = fs::path(ZENITH_SOURCE_DIR) / "bench/results/startup_spirv.csv";
  fs::path cache = atmosphere::lut::default_cache_directory();
  fs::path work = fs::temp_directory_path() / fmt::format("zenith-startup-bench-{}", ::getpid());
  std::vector<std::string> parts = {"starts", "passes", "spirv"};
  bool spirv_dispatch = true;
  bool pass_child = false;  // internal: the in-process pass split, run by the parent with its own Mesa cache
  fs::path spirv_child;     // internal: time the GLSL and SPIR-V builds of the programs in this folder
};

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> out;
  std::stringstream s(text);
  for (std::string item; std::getline(s, item, separator);)
    if (!item.empty()) out.push_back(item);
  return out;
}

Options parse(int argc, char** argv) {
  Options o;
  for (CommandLine args(argc, argv); args.next();) {
    const std::string& a = args.option();
    if (a == "--show") {
      o.show = args.value();
    } else if (a == "--size") {
      const std::string v = args.value();
      if (std::sscanf(v.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 16 || o.height < 16)
        throw std::invalid_argument("--size '" + v + "': WIDTHxHEIGHT, each at least 16");
    } else if (a == "--tables") {
      o.tables = args.value();
      if (o.tables != "paper" && o.tables != "small")
        throw std::invalid_argument("--tables '" + o.tables + "': use paper or small");
    } else if (a == "--rounds") {
      o.rounds = std::stoi(args.value());
      if (o.rounds < 1 || o.rounds > 50) throw std::invalid_argument("--rounds: in [1, 50]");
    } else if (a == "--cases") {
      o.cases = split(args.value(), ',');
      for (const std::string& c : o.cases)
        if (c != "warm" && c != "cold-mesa" && c != "cold-programs" && c != "cold-maps" && c != "cold-unwarmed")
          throw std::invalid_argument("--cases: '" + c +
                                      "' is not warm, cold-mesa, cold-programs, cold-maps or cold-unwarmed");
    } else if (a == "--csv") {
      o.csv = args.value();
    } else if (a == "--passes-csv") {
      o.passes_csv = args.value();
    } else if (a == "--spirv-csv") {
      o.spirv_csv = args.value();
    } else if (a == "--spirv-child") {
      o.spirv_child = args.value();
    } else if (a == "--spirv-no-dispatch") {
      o.spirv_dispatch = false;
    } else if (a == "--parts") {
      o.parts = split(args.value(), ',');
      for (const std::string& p : o.parts)
        if (p != "starts" && p != "passes" && p != "spirv")
          throw std::invalid_argument("--parts: '" + p + "' is not starts, passes or spirv");
    } else if (a == "--cache") {
      o.cache = args.value();
    } else if (a == "--zenith") {
      o.zenith = args.value();
    } else if (a == "--work") {
      o.work = args.value();
    } else if (a == "--pass-child") {
      o.pass_child = true;
    } else {
      throw std::invalid_argument("unknown option " + a + " (see the comment at the top of bench/startup_bench.cpp)");
    }
  }
  return o;
}

/// Runs `argv` with `environment` added to this process's, its output to `log`; the exit status.
int run(const std::vector<std::string>& argv, const std::map<std::string, std::string>& environment,
        const fs::path& log) {
  std::vector<std::string> env_strings;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry = *e;
    if (!environment.contains(entry.substr(0, entry.find('=')))) env_strings.push_back(entry);
  }
  for (const auto& [name, value] : environment) env_strings.push_back(name + "=" + value);
  std::vector<char*> args, env;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  for (const std::string& e : env_strings) env.push_back(const_cast<char*>(e.c_str()));
  env.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), env.data());
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw std::runtime_error(fmt::format("cannot start {}: {}", argv[0], std::strerror(spawned)));
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

using Environment = std::map<std::string, std::string>;

/// The driver's shader cache in `directory`: Mesa's and NVIDIA's (which wants the folder to exist).
Environment driver_cache_in(const fs::path& directory) {
  fs::create_directories(directory);
  return {{"MESA_SHADER_CACHE_DIR", directory.string()}, {"__GL_SHADER_DISK_CACHE_PATH", directory.string()}};
}

/// The driver's shader cache off: every build compiles.
Environment driver_cache_off() { return {{"MESA_SHADER_CACHE_DISABLE", "true"}, {"__GL_SHADER_DISK_CACHE", "0"}}; }

/// The phases of a start-up line, by name, in seconds.
struct Startup {
  double wall_s = 0.0;
  std::map<std::string, double> phases;
};

const std::vector<std::string> kPhases = {
    "total",       "GL context", "tables precomputed",         "tables loaded and uploaded", "programs",
    "albedo maps", "buffers",    "the first frame's rendering"};

Startup parse_startup(const fs::path& log) {
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find("start-up ");
  if (at == std::string::npos) throw std::runtime_error(log.string() + ": no start-up line (see the log)");
  const std::string line = text.substr(at, text.find('\n', at) - at);
  Startup s;
  std::smatch m;
  if (std::regex_search(line, m, std::regex(R"(start-up ([0-9.]+) s)"))) s.phases["total"] = std::stod(m[1]);
  for (const std::string& phase : kPhases) {
    if (phase == "total") continue;
    if (std::regex_search(line, m, std::regex(phase + R"( ([0-9.]+) s)"))) s.phases[phase] = std::stod(m[1]);
  }
  return s;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// A cache directory with `cache`'s tables linked in, and its albedo maps
/// with `maps`; no program binaries.
fs::path linked_cache(const fs::path& cache, const fs::path& directory, bool maps) {
  fs::create_directories(directory);
  for (const auto& entry : fs::directory_iterator(cache)) {
    const std::string name = entry.path().filename().string();
    if ((name.starts_with("tables-") && entry.path().extension() == ".exr") ||
        (maps && name.starts_with("albedo-") && entry.path().extension() == ".bin"))
      fs::create_symlink(entry.path(), directory / entry.path().filename());
  }
  return directory;
}

std::vector<std::string> show_command(const Options& o, const fs::path& out, const fs::path& cache,
                                      bool serial_compile = false) {
  std::vector<std::string> argv = {o.zenith.string(),
                                   "show",
                                   "render",
                                   "--show",
                                   o.show.string(),
                                   "--projection",
                                   "fisheye",
                                   "--size",
                                   fmt::format("{}x{}", o.width, o.height),
                                   "--to",
                                   "0",
                                   "--tables",
                                   o.tables,
                                   "--out",
                                   out.string()};
  argv.insert(argv.end(), {"--cache", cache.string()});
  if (serial_compile) argv.push_back("--serial-compile");
  return argv;
}

void process_starts(const Options& o) {
  fs::create_directories(o.work);
  const fs::path warm_mesa = o.work / "mesa-warm";
  fmt::print("startup_bench: {} at {}x{}, {} tables, {} round(s) of {}\n", o.show.filename().string(), o.width,
             o.height, o.tables, o.rounds, fmt::join(o.cases, ", "));
  // One run unrecorded: the tables, the maps and Mesa's warm cache in place.
  if (run(show_command(o, o.work / "prime", o.cache), driver_cache_in(warm_mesa), o.work / "prime.log") != 0)
    throw std::runtime_error("the priming run failed: " + (o.work / "prime.log").string());

  std::map<std::string, std::vector<Startup>> runs;
  fs::create_directories(o.csv.parent_path());
  std::ofstream csv(o.csv);
  csv << "case,round,wall_s";
  for (const std::string& p : kPhases) csv << ",\"" << p << "_s\"";
  csv << "\n";
  for (int r = 0; r < o.rounds; ++r)
    for (const std::string& c : o.cases) {
      const fs::path run_dir = o.work / fmt::format("{}-{}", c, r);
      const fs::path mesa = c == "warm" ? warm_mesa : run_dir / "mesa";
      fs::create_directories(run_dir);
      const bool own_cache = c == "cold-programs" || c == "cold-maps";
      const fs::path cache = own_cache ? linked_cache(o.cache, run_dir / "cache", c == "cold-programs") : o.cache;
      const fs::path log = run_dir / "zenith.log";
      const auto start = std::chrono::steady_clock::now();
      const int status = run(show_command(o, run_dir / "out", cache, c == "cold-unwarmed"), driver_cache_in(mesa), log);
      if (status != 0) throw std::runtime_error(fmt::format("{} exited with {}: {}", c, status, log.string()));
      Startup s = parse_startup(log);
      s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      csv << c << ',' << r << ',' << fmt::format("{:.3f}", s.wall_s);
      for (const std::string& p : kPhases) csv << ',' << fmt::format("{:.3f}", s.phases[p]);
      csv << "\n";
      fmt::print("  {:<14} round {}: {:.2f} s wall, start-up {:.2f} s\n", c, r, s.wall_s, s.phases["total"]);
      runs[c].push_back(std::move(s));
      fs::remove_all(run_dir);  // Mesa's cold cache and the frames: tens of MiB a run
    }
  fmt::print("\nmedian of {} round(s), seconds:\n{:<30}", o.rounds, "");
  for (const std::string& c : o.cases) fmt::print("{:>15}", c);
  fmt::print("\n{:<30}", "whole process (wall)");
  for (const std::string& c : o.cases) {
    std::vector<double> v;
    for (const Startup& s : runs[c]) v.push_back(s.wall_s);
    fmt::print("{:>15.2f}", median(v));
  }
  for (const std::string& p : kPhases) {
    fmt::print("\n{:<30}", p);
    for (const std::string& c : o.cases) {
      std::vector<double> v;
      for (const Startup& s : runs[c]) v.push_back(s.phases.at(p));
      fmt::print("{:>15.2f}", median(v));
    }
  }
  fmt::print("\nevery run: {}\n", o.csv.string());
}

/// The child: the show's first frame twice, every pass timed; "pass,first_ms,second_ms" to stdout.
int pass_child(const Options& o) {
  const show::Show show = show::load_show(o.show);
  std::map<scene::TableHash, show::AtmosphereVersion> versions;
  for (const show::AtmosphereVersion& v : show.atmosphere_versions(show.frame_rate_hz()))
    versions.emplace(v.table_hash, v);
  scene::Scene scene = show.scene();
  show::apply_state(show.state_at(0.0, 0, render::render_flags_of(render::RenderOptions{})), versions, scene);
  const render::gl::HeadlessContext context;
  atmosphere::lut::PrecomputeOptions table_options;
  table_options.sizes = o.tables == "small" ? atmosphere::lut::TableSizes::small() : atmosphere::lut::TableSizes{};
  const atmosphere::lut::TableCache cache(o.cache);
  render::RenderOptions options;
  options.time_passes = true;
  options.albedo_cache_directory = o.cache;
  render::Renderer renderer(
      options, cached_or_precomputed_tables(cache, table_options, o.tables, {}, [&] { context.make_current(); }));
  warp::FisheyeParameters fisheye;
  fisheye.fov_deg = 180.0;
  const warp::FisheyeProjection projection(o.width, o.height, fisheye);
  renderer.render_image(scene, projection);
  const std::map<std::string, double> first = renderer.last_frame().pass_ms;
  renderer.render_image(scene, projection);
  const std::map<std::string, double> second = renderer.last_frame().pass_ms;
  for (const auto& [pass, ms] : first) {
    const auto it = second.find(pass);
    fmt::print("PASS\t{}\t{:.2f}\t{:.2f}\n", pass, ms, it == second.end() ? 0.0 : it->second);
  }
  return 0;
}

void pass_compile(const Options& o) {
  fs::create_directories(o.work);
  std::map<std::string, std::map<std::string, std::pair<double, double>>> by_case;  // case → pass → (first, second)
  const fs::path mesa = o.work / "passes-mesa";  // empty for the first run, warm for the second
  fs::remove_all(mesa);
  for (const std::string& c : {std::string("cold"), std::string("warm")}) {
    const fs::path log = o.work / ("passes-" + c + ".log");
    const int status = run({fs::read_symlink("/proc/self/exe").string(), "--pass-child", "--show", o.show.string(),
                            "--size", fmt::format("{}x{}", o.width, o.height), "--tables", o.tables},
                           driver_cache_in(mesa), log);
    if (status != 0)
      throw std::runtime_error(fmt::format("the pass split ({}) exited with {}: {}", c, status, log.string()));
    std::ifstream in(log);
    for (std::string line; std::getline(in, line);) {
      const std::vector<std::string> f = split(line, '\t');
      if (f.size() == 4 && f[0] == "PASS") by_case[c][f[1]] = {std::stod(f[2]), std::stod(f[3])};
    }
  }
  fs::create_directories(o.passes_csv.parent_path());
  std::ofstream csv(o.passes_csv);
  csv << "pass,cold_first_ms,cold_second_ms,cold_first_use_ms,warm_first_ms,warm_second_ms,warm_first_use_ms\n";
  fmt::print("\neach pass's first use (first frame less second, ms), Mesa's cache empty and warm:\n");
  double cold_sum = 0.0, warm_sum = 0.0;
  for (const auto& [pass, cold] : by_case["cold"]) {
    const auto warm = by_case["warm"][pass];
    const double cold_use = cold.first - cold.second, warm_use = warm.first - warm.second;
    cold_sum += cold_use;
    warm_sum += warm_use;
    csv << fmt::format("\"{}\",{:.2f},{:.2f},{:.2f},{:.2f},{:.2f},{:.2f}\n", pass, cold.first, cold.second, cold_use,
                       warm.first, warm.second, warm_use);
    fmt::print("  {:<60} {:8.1f} {:8.1f}\n", pass, cold_use, warm_use);
  }
  fmt::print("  {:<60} {:8.1f} {:8.1f}\nevery pass: {}\n", "all passes", cold_sum, warm_sum, o.passes_csv.string());
}

/// The path of `program` on PATH, or empty.
fs::path on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  for (const std::string& dir : split(path == nullptr ? "" : path, ':'))
    if (const fs::path p = fs::path(dir) / program; ::access(p.c_str(), X_OK) == 0) return p;
  return {};
}

/// The compute programs' dumped texts under `dir` that have their SPIR-V beside them, sorted.
std::vector<fs::path> dumped_programs(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".comp" && fs::exists(entry.path().string() + ".spv")) out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

/// The two sets of programs part 3 times: the show's renderer and the precompute.
const std::array<std::string, 2> kProgramSets = {"show", "precompute"};

int spirv_child(const Options& o) {
  const render::gl::HeadlessContext context;
  if (!has_gl_spirv()) {
    fmt::print("NO-SPIRV\n");
    return 0;
  }
  for (const std::string& set : kProgramSets) {
    if (!fs::is_directory(o.spirv_child / set)) continue;
    for (const fs::path& glsl : dumped_programs(o.spirv_child / set)) {
      try {
        const CompileTimes t = time_glsl_and_spirv(glsl, glsl.string() + ".spv", o.rounds, o.spirv_dispatch);
        fmt::print("SPIRV\t{}\t{}\t{:.2f}\t{:.2f}\t{:.2f}\t{:.2f}\t{:.2f}\t{:.2f}\n", set, glsl.filename().string(),
                   t.glsl_build_ms, t.spirv_build_ms, t.glsl_dispatch_ms, t.spirv_dispatch_ms, t.glsl_first_build_ms,
                   t.spirv_first_build_ms);
      } catch (const std::exception& e) {  // the others are still timed; the parent reads no row for this one
        fmt::print("REFUSED\t{}\t{}\t{}\n", set, glsl.filename().string(), e.what());
      }
      std::fflush(stdout);
    }
  }
  return 0;
}

/// Each .comp under `dump` made into SPIR-V beside it; glslangValidator's time by file name. A program
/// glslangValidator refuses is left out, said so.
std::map<std::string, double> make_spirv(const fs::path& glslang, const fs::path& dump) {
  std::map<std::string, double> glslang_ms;
  for (const auto& entry : fs::directory_iterator(dump)) {
    if (entry.path().extension() != ".comp") continue;
    const auto start = std::chrono::steady_clock::now();
    const int status = run({glslang.string(), "-G", "--aml", "--amb", "-S", "comp", "-o",
                            entry.path().string() + ".spv", entry.path().string()},
                           {}, entry.path().string() + ".glslang.log");
    if (status != 0) {
      fmt::print("  {}: glslangValidator refused it ({}), left out\n", entry.path().filename().string(),
                 entry.path().string() + ".glslang.log");
      fs::remove(entry.path().string() + ".spv");
      continue;
    }
    glslang_ms[entry.path().filename().string()] =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  return glslang_ms;
}

void spirv_against_glsl(const Options& o) {
  const fs::path glslang = on_path("glslangValidator");
  if (glslang.empty()) {
    fmt::print("\nSPIR-V against GLSL: skipped, no glslangValidator on PATH (Debian glslang-tools)\n");
    return;
  }
  const fs::path dump = o.work / "spirv-dump";
  fs::remove_all(dump);
  // The show's programs, as its first frame builds them with no program binary to load.
  const fs::path cache =
      linked_cache(o.cache, o.work / "spirv-cache", true);  // no program binaries: every program compiled
  Environment environment = driver_cache_in(o.work / "spirv-driver-cache");
  environment["ZENITH_SHADER_DUMP_DIR"] = (dump / "show").string();
  fs::create_directories(dump / "show");
  if (run(show_command(o, o.work / "spirv-out", cache), environment, o.work / "spirv-dump.log") != 0)
    throw std::runtime_error("the run that dumps the show's programs failed: " + (o.work / "spirv-dump.log").string());
  // The precompute's: every program of every stage (two orders run the same programs as eight).
  environment["ZENITH_SHADER_DUMP_DIR"] = (dump / "precompute").string();
  fs::create_directories(dump / "precompute");
  if (run({o.zenith.string(), "precompute", "--atmosphere", "earth-advanced", "--tables", o.tables, "--orders", "2",
           "--no-cache"},
          environment, o.work / "spirv-precompute.log") != 0)
    throw std::runtime_error("the precompute that dumps its programs failed: " +
                             (o.work / "spirv-precompute.log").string());
  std::map<std::string, std::map<std::string, double>> glslang_ms;
  for (const std::string& set : kProgramSets) glslang_ms[set] = make_spirv(glslang, dump / set);

  const fs::path log = o.work / "spirv-child.log";
  std::vector<std::string> child = {fs::read_symlink("/proc/self/exe").string(), "--spirv-child", dump.string(),
                                    "--rounds", std::to_string(o.rounds)};
  if (!o.spirv_dispatch) child.push_back("--spirv-no-dispatch");
  if (run(child, driver_cache_off(), log) != 0)
    throw std::runtime_error("the SPIR-V timing child failed: " + log.string());
  std::ifstream in(log);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line == "NO-SPIRV") {
      fmt::print("\nSPIR-V against GLSL: skipped, the driver has no GL_ARB_gl_spirv\n");
      return;
    }
    if (std::vector<std::string> f = split(line, '\t'); f.size() == 9 && f[0] == "SPIRV") rows.push_back(f);
  }
  fs::create_directories(o.spirv_csv.parent_path());
  std::ofstream csv(o.spirv_csv);
  csv << "set,program,glslang_ms,glsl_build_ms,spirv_build_ms,glsl_first_dispatch_ms,spirv_first_dispatch_ms,"
         "glsl_first_build_ms,spirv_first_build_ms\n";
  fmt::print(
      "\nSPIR-V against GLSL, ms (median of {}; the driver's disk cache off): glslangValidator, the driver's build "
      "from GLSL and from SPIR-V, {}the first round's builds\n",
      o.rounds, o.spirv_dispatch ? "the first dispatch of each, " : "");
  for (const std::string& set : kProgramSets) {
    std::array<double, 7> sums{};
    int programs = 0;
    for (const auto& f : rows) {
      if (f[1] != set) continue;
      const std::array<double, 7> v = {glslang_ms[set][f[2]], std::stod(f[3]), std::stod(f[4]), std::stod(f[5]),
                                       std::stod(f[6]),       std::stod(f[7]), std::stod(f[8])};
      for (std::size_t k = 0; k < v.size(); ++k) sums[k] += v[k];
      ++programs;
      csv << fmt::format("{},\"{}\",{:.2f},{:.2f},{:.2f},{:.2f},{:.2f},{:.2f},{:.2f}\n", set, f[2], v[0], v[1], v[2],
                         v[3], v[4], v[5], v[6]);
      fmt::print("  {:<11} {:<56} {:7.1f} {:7.1f} {:7.1f} {:7.1f} {:7.1f} {:7.1f} {:7.1f}\n", set, f[2], v[0], v[1],
                 v[2], v[3], v[4], v[5], v[6]);
    }
    fmt::print("  {:<11} {:<56} {:7.1f} {:7.1f} {:7.1f} {:7.1f} {:7.1f} {:7.1f} {:7.1f}\n", set,
               fmt::format("all {} programs", programs), sums[0], sums[1], sums[2], sums[3], sums[4], sums[5], sums[6]);
  }
  fmt::print("every program: {}\n", o.spirv_csv.string());
}

}  // namespace
}  // namespace zenith::bench

int main(int argc, char** argv) {
  using namespace zenith::bench;
  try {
    const Options o = parse(argc, argv);
    if (o.pass_child) return pass_child(o);
    if (!o.spirv_child.empty()) return spirv_child(o);
    const auto wanted = [&](const char* part) { return std::ranges::find(o.parts, part) != o.parts.end(); };
    if (wanted("starts")) process_starts(o);
    if (wanted("passes")) pass_compile(o);
    if (wanted("spirv")) spirv_against_glsl(o);
    std::filesystem::remove_all(o.work);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "startup_bench: %s\n", e.what());
    return 1;
  }
}
