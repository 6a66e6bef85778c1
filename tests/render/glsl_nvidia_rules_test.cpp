// Every shader program the precompute and the renderer compile, checked for
// the constructs NVIDIA's GLSL compiler refuses while Mesa (this machine's
// llvmpipe) accepts them, so that CI without a GPU catches them
// (docs/gpu-precompute.md, "What NVIDIA's compiler refuses").
//
// The programs are the real ones: the test runs the GPU precompute on tiny
// tables for every shader switch (fp64 and fp32, 4, 5 and 64 wavelengths,
// absorbers or none, Mie or none, each phase model, air mass or none, both
// quadratures and both density methods, 1 to 3 orders, the series tail) and the
// renderer over a ground view, an eclipse and three atmospheres in each
// projection kind, with and without fp64, multiple scattering, eclipses, the
// sky-view table and the one-pass tiles, with ZENITH_SHADER_DUMP_DIR set (render/gl/shader_dump.h):
// each distinct final text given to glShaderSource is written out, includes
// expanded and #defines injected. glslangValidator (Debian: glslang-tools)
// parses each one and prints its syntax tree (-i); the test walks the tree.
//
// Rule 1, NVIDIA "C9999: can't find __setVectorIndex function in stdlib" (a
// link failure; driver 580.159.04, 2026-11-26): no write — =, op=, ++/--, an
// out/inout argument — to one component of a double vector (dvec2..4, the
// shaders' real2..4 in fp64) at an index that is not a constant expression.
// `sum[k] += v[k]` is refused even in a loop of constant bound; write the
// whole vector instead: `sum += mix(real4(0), v, lessThan(ivec4(0,1,2,3), ivec4(lanes)))`.
//
// Rule 2, NVIDIA "C5025: lvalue in array access too complex" (a link failure
// of the same driver): NVIDIA unrolls loops of constant bound; a storage-
// buffer element whose index depends on the counter of such a loop nested in
// another such loop (through calls too) is what the 9 programs it refused
// share — the absorber loop inside the transmittance's and the view rays'
// sample loops (wavelength_data[… + a], table_data[ABSORBER_PROFILES + 4a]),
// the l loop inside the m loop of harmonic_density.comp, the k loop inside the
// f loop of test_shader_model.comp — and what the programs it linked do not
// have (indirect_irradiance.comp reads its rule by the outer counter only,
// harmonic_projection.comp's outer bound depends on the invocation). It failed
// only where the loops were short enough to be unrolled whole (tiny tables: 4
// sphere nodes, 100 transmittance samples, and fp32), so whether a given
// program fails depends on the driver's unrolling heuristics: the shape is the
// risk, not a certainty. ShaderProgram::compute compiles a program that fails
// with C5025 again with `#pragma optionNV(unroll none)` (every one probed on
// an H200 then linked). The sites the shaders have today are listed in
// kKnownNestedBufferIndices, each on that retry; a new one fails the test.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "astro/sky_positions.h"
#include "atmosphere/lut/cpu_precompute.h"
#include "atmosphere/parameters.h"
#include "atmosphere/phase_functions.h"
#include "core/units.h"
#include "render/gl/egl_context.h"
#include "render/gl/shader_program.h"
#include "render/lut/gpu_precompute.h"
#include "render/renderer.h"
#include "render/shader_programs.h"
#include "scene/local_horizon.h"
#include "scene/scene_loader.h"
#include "scene/sky_clock.h"
#include "tests/render/glsl_ast.h"
#include "tests/render/render_test_support.h"
#include "tests/render/tiny_precompute_options.h"
#include "warp/cube_face_projection.h"
#include "warp/cylindrical_projection.h"
#include "warp/equirectangular_projection.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"

namespace zenith::render::testing {
namespace {

using atmosphere::AtmosphereModel;
using atmosphere::lut::PrecomputeOptions;
using atmosphere::lut::TableSizes;
namespace fs = std::filesystem;

/// stdout of `command` (stderr merged), and its exit status.
std::pair<std::string, int> run(const std::string& command) {
  std::string out;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return {"popen failed", -1};
  std::array<char, 65536> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), n);
  const int status = pclose(pipe);
  return {out, status};
}

std::string quoted(const fs::path& p) { return fmt::format("'{}'", p.string()); }

/// The tree glslangValidator prints for `shader` (its stage from the extension).
AstNode syntax_tree(const fs::path& shader) {
  const auto [listing, status] = run(fmt::format("{} -i {}", ZENITH_GLSLANG_VALIDATOR, quoted(shader)));
  if (status != 0)
    throw std::runtime_error(fmt::format("glslangValidator failed on {}:\n{}", shader.string(), listing));
  return parse_glslang_ast(listing);
}

/// The trees of `shaders`, from one glslangValidator process: it builds its
/// built-in symbol tables once a process, the larger part of its time on a
/// shader of ours, so a batch is several times faster than a process a file.
/// Its listing gives each file's tree under a line holding the file's path.
std::vector<AstNode> syntax_trees(const std::vector<fs::path>& shaders) {
  std::string command = ZENITH_GLSLANG_VALIDATOR + std::string(" -i");
  for (const fs::path& s : shaders) command += " " + quoted(s);
  const auto [listing, status] = run(command);
  if (status != 0) throw std::runtime_error("glslangValidator failed on a batch:\n" + listing);
  const std::string_view text = listing;
  std::vector<std::size_t> headers;  // where each file's path line starts, in the order given
  for (const fs::path& s : shaders) {
    const std::string line = s.string() + "\n";
    std::size_t at = text.find(line, headers.empty() ? 0 : headers.back() + 1);
    while (at != std::string_view::npos && at > 0 && text[at - 1] != '\n') at = text.find(line, at + 1);
    if (at == std::string_view::npos)
      throw std::runtime_error(fmt::format("glslangValidator's listing has no tree for {}", s.string()));
    headers.push_back(at);
  }
  std::vector<AstNode> trees;
  for (std::size_t i = 0; i < headers.size(); ++i) {
    const std::size_t begin = headers[i] + shaders[i].string().size() + 1;
    const std::size_t end = i + 1 < headers.size() ? headers[i + 1] : text.size();
    trees.push_back(parse_glslang_ast(text.substr(begin, end - begin)));
  }
  return trees;
}

/// A shader written to a temporary file and its tree.
AstNode syntax_tree_of(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("zenith-glsl-rules-{}", ::getpid());
  fs::create_directories(dir);
  const fs::path file = dir / name;
  std::ofstream(file) << text;
  AstNode tree = syntax_tree(file);
  fs::remove_all(dir);
  return tree;
}

/// A compute shader of one invocation: its buffer block (`members`) and a
/// uniform `g` the body indexes with on lines 1–4, then `body`, which starts
/// with a line break (a raw string's), so its first line is line 5.
std::string compute_shader(const std::string& members, const std::string& body) {
  return "#version 450 core\nlayout(local_size_x = 1) in;\nlayout(std430, binding = 0) buffer B { " + members +
         " };\nuniform int g;" + body;
}

std::vector<int> lines_of(const std::vector<Finding>& findings) {
  std::vector<int> lines;
  for (const Finding& f : findings) lines.push_back(f.line);
  return lines;
}

bool have_validator() { return std::string(ZENITH_GLSLANG_VALIDATOR).size() > 0; }

#define REQUIRE_VALIDATOR()                                                         \
  if (!have_validator())                                                            \
  GTEST_FAIL() << "glslangValidator not found when configuring (scripts/bootstrap " \
                  "installs glslang-tools)"

// ------------------------------------------------------------ the rules on shaders written for them

TEST(GlslNvidiaRules, Rule1FindsEveryKindOfWriteToADoubleVectorAtAVariableIndex) {
  REQUIRE_VALIDATOR();
  const std::string shader = compute_shader("dvec4 w[8]; double v[];", R"(
void add_one(inout dvec4 x, int k) { x[k] += 1.0; }
void set_one(out double y) { y = 1.0; }
void main() {
  dvec4 s = dvec4(0);
  for (int k = 0; k < 4; ++k) s[k] = v[k];
  s[g]++;
  --s[g];
  add_one(s, 1);
  set_one(s[g]);
  s.x = modf(v[0], s[g]);
  dvec4 a[3];
  a[g][g] = 2.0;
  w[g][g] = 3.0;
  s[1] = 2.0;
  a[g] = s;
  a[g].y = 1.0;
  vec4 f = vec4(0);
  f[g] = 1.0;
  v[g] = s[g];
}
)");
  const std::vector<Finding> found = double_vector_index_writes(syntax_tree_of("rule1.comp", shader));
  for (const Finding& f : found) std::printf("  %d:%d %s\n", f.source, f.line, f.what.c_str());
  // Lines 5 (x[k] +=, inout x), 9, 10, 11, 13 (out argument), 14 (modf's out), 16, 17;
  // not 12 (a whole vector to inout), 18 (constant index), 19, 20 (swizzle of a whole element), 22 (float), 23 (a
  // read).
  EXPECT_EQ(lines_of(found), (std::vector<int>{5, 9, 10, 11, 13, 14, 16, 17}));
}

TEST(GlslNvidiaRules, Rule2FindsBufferIndicesOfNestedConstantLoopsThroughCalls) {
  REQUIRE_VALIDATOR();
  const std::string shader = compute_shader("double result[64]; double table[];", R"(
double field(int f) { return table[g * 8 + f]; }
double absorbers(double h) {
  double e = 0.0;
  for (int a = 0; a < 2; ++a) e += field(3 + a) * h;
  return e;
}
void main() {
  double sum = 0.0;
  for (int i = 0; i <= 100; ++i) sum += absorbers(double(i));
  for (int i = 0; i < 8; ++i) sum += table[i];
  for (int m = 0; m < 8; ++m)
    for (int l = m; l <= 7; ++l) {
      const int moment = 40 + l;
      sum += table[moment];
    }
  for (int j = 0; j < int(sum); ++j)
    for (int k = 0; k < 4; ++k) sum += table[k];
  for (int f = 0; f < 4; ++f)
    for (int k = 0; k < 4; ++k) result[8 + 4 * f + k] = sum + table[f];
  const int m0 = g % 8;
  for (int l = m0; l <= 7; ++l)
    for (int k = 0; k < 4; ++k) sum += table[k];
}
)");
  const std::vector<Finding> found = nested_unrolled_buffer_indices(syntax_tree_of("rule2.comp", shader));
  for (const Finding& f : found) std::printf("  %d:%d %s\n", f.source, f.line, f.what.c_str());
  // Line 5 (field's index, from the a loop inside the i loop), 18 (l inside m), 23 (k inside f);
  // not 14 (one loop), 21 (the outer loop's bound is not a constant), table[f] on 23 (the outer counter),
  // 26 (the outer loop starts at a value known only at run time: not unrolled).
  EXPECT_EQ(lines_of(found), (std::vector<int>{5, 18, 23}));
}

// ------------------------------------------------------------ every program of the precompute and the renderer

/// Sets ZENITH_SHADER_DUMP_DIR for the lifetime of the object.
struct DumpDirectory {
  fs::path path;
  DumpDirectory() : path(fs::temp_directory_path() / fmt::format("zenith-shader-variants-{}", ::getpid())) {
    fs::remove_all(path);
    setenv("ZENITH_SHADER_DUMP_DIR", path.c_str(), 1);
  }
  ~DumpDirectory() {
    unsetenv("ZENITH_SHADER_DUMP_DIR");
    fs::remove_all(path);
  }
};

/// A tabulated aerosol phase (MIE_PHASE 3): Cornette–Shanks every 5°.
void with_tabulated_mie_phase(AtmosphereModel& m, PrecomputeOptions&) {
  std::vector<double> angles;
  std::vector<atmosphere::TabulatedPhase::Column> columns = {{550.0, {}}};
  for (int a = 0; a <= 180; a += 5) {
    angles.push_back(a);
    columns[0].values.push_back(atmosphere::cornette_shanks(std::cos(a * core::kPi / 180.0), 0.7));
  }
  m.mie_phase.model = atmosphere::MiePhase::Model::Tabulated;
  m.mie_phase.table = std::make_shared<const atmosphere::TabulatedPhase>(angles, columns, m.wavelengths_nm);
}

void precompute_every_variant(const gl::HeadlessContext& context) {
  struct Variant {
    const char* preset;
    GpuPrecision precision;
    std::vector<double> wavelengths_nm;  ///< empty: the preset's
    void (*edit)(AtmosphereModel&, PrecomputeOptions&);
  };
  std::vector<double> sixty_four;
  for (int i = 0; i < 64; ++i) sixty_four.push_back(440.0 + 4.0 * i);
  const auto none = [](AtmosphereModel&, PrecomputeOptions&) {};
  const Variant variants[] = {
      {"earth-advanced", GpuPrecision::fp64, {}, none},
      {"earth-advanced", GpuPrecision::fp32, {}, none},
      {"mars", GpuPrecision::fp64, sixty_four, none},
      {"titan", GpuPrecision::fp64, {}, none},
      {"halcyon", GpuPrecision::fp64, {}, none},
      {"halcyon", GpuPrecision::fp32, {}, none},
      {"earth-standard", GpuPrecision::fp64, {}, none},
      {"earth-advanced", GpuPrecision::fp64, {440, 500, 550, 600, 680}, none},
      {"earth-advanced",
       GpuPrecision::fp64,
       {},
       [](AtmosphereModel& m, PrecomputeOptions& o) {
         m.rayleigh_phase = atmosphere::RayleighPhaseModel::Classic;
         m.air_mass = atmosphere::AirMassStretch();
         o.scattering_quadrature = PrecomputeOptions::Quadrature::Trapezoid;
       }},
      {"earth-advanced",
       GpuPrecision::fp64,
       {},
       [](AtmosphereModel& m, PrecomputeOptions&) {
         m.rayleigh_phase = atmosphere::RayleighPhaseModel::Depolarized;
         for (std::size_t i = 0; i < m.wavelength_count(); ++i) m.mie_scattering_m1[i] = m.mie_extinction_m1[i] = 0.0;
       }},
      {"earth-advanced",
       GpuPrecision::fp64,
       {},
       [](AtmosphereModel&, PrecomputeOptions& o) {
         o.density_method = PrecomputeOptions::DensityMethod::Direct;
         o.series_tail = false;
       }},
      {"titan", GpuPrecision::fp64, {}, [](AtmosphereModel&, PrecomputeOptions& o) { o.max_orders = 1; }},
      {"earth-advanced", GpuPrecision::fp64, {}, with_tabulated_mie_phase},
      {"earth-advanced", GpuPrecision::fp32, {}, with_tabulated_mie_phase},
  };
  for (const Variant& v : variants) {
    atmosphere::LoadOptions load;
    if (!v.wavelengths_nm.empty()) load.wavelengths_nm = v.wavelengths_nm;
    AtmosphereModel model = atmosphere::load_preset(v.preset, load).model;
    PrecomputeOptions options = testing::tiny_precompute_options();
    v.edit(model, options);
    precompute_tables_gpu(model, options, nullptr, &context, v.precision);
  }
}

/// The renderer's programs: a ground view, an eclipse seen from orbit and from
/// inside the Moon's shadow, three atmospheres side by side, in a planar and a
/// fisheye view under each set of options, and the other projection kinds once.
void render_every_variant() {
  const PrecomputeOptions tables = testing::tiny_precompute_options();
  const warp::PlanarProjection planar = warp::PlanarProjection::symmetric(48, 32, 70.0);
  const warp::FisheyeProjection fisheye(48, 48);
  const warp::EquirectangularProjection equirectangular(48, 24);
  const warp::CylindricalProjection cylindrical(48, 24, warp::CylindricalParameters{});
  const warp::CubeFaceProjection cube_face(32, warp::CubeFace::positive_x);
  std::vector<RenderOptions> options(3);
  options[0].unlit_tile_zeroing = UnlitTileZeroing::compute_pass;  // a GPU's way: zero_tiles.comp built
  options[1].atmosphere.fp64 = true;
  options[1].sky_view_table = SkyViewTableUse::off;
  options[1].one_pass_tiles = false;
  options[2].atmosphere.multiple_scattering = false;
  options[2].atmosphere.eclipses = false;
  options[2].sun_disc = false;
  options[2].limb_darkening = false;
  const fs::path scenes = fs::path(ZENITH_SOURCE_DIR) / "configs/scenes";
  for (std::size_t i = 0; i < options.size(); ++i) {
    Renderer renderer(options[i], [&](const AtmosphereModel& model) {
      return atmosphere::lut::precompute_tables_cpu(model, tables);
    });
    // earth-dusk-greenwich at a night exposure: the night sky's pass (stars, floor);
    // the 2017 totality: the Moon's shadow on the sky (eclipse_sky.comp, ECLIPSE_SKY tiles);
    // the Moon in the Earth's shadow from space: the air shadows' code (AIR_SHADOWS).
    for (const char* name :
         {"earth-ground-view.json", "earth-moon.json", "three-worlds.json", "earth-dusk-greenwich.json",
          "earth-eclipse-2017-totality.json", "earth-moon-lunar-eclipse.json"}) {
      scene::Scene s = scene::load_scene(scenes / name);
      if (s.sky_clock) s.camera.exposure = scene::kMaxExposure;
      renderer.render_image(s, planar);
      renderer.render_image(s, fisheye);
      if (i == 0 && std::string_view(name) == "three-worlds.json")
        for (const warp::Projection* p :
             std::initializer_list<const warp::Projection*>{&equirectangular, &cylindrical, &cube_face})
          renderer.render_image(s, *p);
    }
    // The Moon's disc (the night sky's pass compiles its code only into the
    // tiles the disc reaches, NightSkyVariant): 2° on the full Moon of
    // 2026-01-03 from Greenwich, 57° up, at a night exposure.
    scene::Scene s = scene::load_scene(scenes / "earth-dusk-greenwich.json");
    s.sky_clock->time = astro::UtcTime{2026, 1, 3, 23, 0, 0.0};
    s.camera.exposure = scene::kMaxExposure;
    s.sun.direction =
        scene::ephemeris_sun(s, *s.sky_clock, astro::AstroTime::from_utc(s.sky_clock->time), s.camera.position_m)
            .direction;
    const std::size_t earth = s.sky_clock->body;
    const scene::LocalHorizon h = scene::local_horizon_at(s.camera.position_m, s.bodies[earth]);
    const auto moon = astro::SkyPositions(astro::AstroTime::from_utc(s.sky_clock->time), s.sky_clock->site)
                          .moon()
                          .horizontal.east_north_up();
    s.camera.orientation = testing::look_rotation(moon[0] * h.east + moon[1] * h.north + moon[2] * h.up, h.up);
    renderer.render_image(s, warp::PlanarProjection::symmetric(48, 32, 2.0));
  }
}

/// (file, line) of a finding in a dumped shader, through its ".files" list.
std::string where(const fs::path& shader, const Finding& f) {
  std::ifstream names(shader.string() + ".files");
  std::vector<std::string> files;
  for (std::string l; std::getline(names, l);) files.push_back(l);
  if (f.source >= 0 && static_cast<std::size_t>(f.source) < files.size())
    return fmt::format("{}:{}", files[static_cast<std::size_t>(f.source)], f.line);
  return fmt::format("source {}:{}", f.source, f.line);
}

/// "harmonic_density.comp" of a dumped "harmonic_density.comp.<hash>.comp".
std::string program_name(const fs::path& dumped) {
  const std::string f = dumped.filename().string();
  return f.substr(0, f.find('.', f.find('.') + 1));
}

/// The sites of rule 2 in today's shaders, each handled by the C5025 retry
/// (render/gl/shader_program.h, kNvidiaLoopUnrollOff), as "function: buffer"
/// ("main" qualified by its shader): named by function rather than line so
/// that moving code between files keeps them.
const std::set<std::string> kKnownNestedBufferIndices = {
    // extinction()'s absorber loop inside the sample loops of transmittance.comp and
    // view_transmittance.comp: the absorber's coefficients and its profile (descriptor, spline knots).
    "wavelength_field: wavelength_data",
    "profile_density: table_data",
    "spline_value: table_data",
    // harmonic_density.comp: the l loop inside the m loop (phase moments, harmonic coefficients).
    "harmonic_density.comp main: table_data",
    "harmonic_density.comp main: harmonic_coefficients",
};

TEST(GlslNvidiaRules, EveryProgramOfThePrecomputeAndTheRendererPassesOnNvidiasRules) {
  REQUIRE_VALIDATOR();
  const DumpDirectory dump;
  {
    const gl::HeadlessContext context;
    precompute_every_variant(context);
    render_every_variant();
    const gl::ShaderProgram present = load_graphics_program("render/present.vert", "render/present.frag");
    // The display pass (render/display/display_encoder.h: the output stage and
    // an MPCDI colour profile's LUTs), from a texture and from a band, and its thumbnail.
    for (const char* band : {"0", "1"}) {
      const std::vector<gl::ShaderDefine> defines = {{"FROM_BAND", band}};
      const gl::ShaderProgram display =
          load_graphics_program("render/present.vert", "render/display_encode.frag", defines);
    }
    const gl::ShaderProgram thumbnail = load_compute_program("render/display_thumbnail.comp");
  }
  std::size_t programs = 0;
  std::vector<std::string> rule1, rule2_new;
  std::map<std::string, std::set<std::string>> rule2_known;  // site → programs
  std::vector<fs::path> shaders;
  for (const auto& entry : fs::directory_iterator(dump.path))
    if (entry.path().extension() != ".files") shaders.push_back(entry.path());
  std::sort(shaders.begin(), shaders.end());
  // glslangValidator on every core, a process per batch of shaders.
  constexpr std::size_t kBatch = 16;
  std::atomic<std::size_t> next{0};
  std::vector<AstNode> parsed(shaders.size());
  std::vector<std::string> errors(shaders.size());
  std::vector<std::thread> workers;
  for (unsigned w = 0; w < std::max(1u, std::thread::hardware_concurrency()); ++w)
    workers.emplace_back([&] {
      for (std::size_t first; (first = next.fetch_add(kBatch)) < shaders.size();) {
        const std::size_t last = std::min(first + kBatch, shaders.size());
        try {
          std::vector<AstNode> trees = syntax_trees({shaders.begin() + first, shaders.begin() + last});
          std::move(trees.begin(), trees.end(), parsed.begin() + first);
        } catch (const std::exception&) {
          // A batch refused: each of its shaders alone, so that an error names its shader.
          for (std::size_t i = first; i < last; ++i) {
            try {
              parsed[i] = syntax_tree(shaders[i]);
            } catch (const std::exception& e) {
              errors[i] = e.what();
            }
          }
        }
      }
    });
  for (std::thread& t : workers) t.join();
  for (std::size_t i = 0; i < shaders.size(); ++i) {
    const fs::path& shader = shaders[i];
    ++programs;
    if (!errors[i].empty()) {
      ADD_FAILURE() << errors[i];
      continue;
    }
    const AstNode& tree = parsed[i];
    for (const Finding& f : double_vector_index_writes(tree))
      rule1.push_back(fmt::format("{}: {} ({})", where(shader, f), f.what, shader.filename().string()));
    const std::string program = program_name(shader);
    for (const Finding& f : nested_unrolled_buffer_indices(tree)) {
      const std::string site = fmt::format("{}{}: {}", f.function == "main" ? program + " " : "", f.function, f.buffer);
      if (kKnownNestedBufferIndices.contains(site))
        rule2_known[site].insert(program);
      else
        rule2_new.push_back(fmt::format("{}: {} ({})", where(shader, f), f.what, shader.filename().string()));
    }
  }
  std::printf("%zu distinct shader texts checked\n", programs);
  for (const auto& [site, in] : rule2_known) {
    std::printf("  rule 2, known (C5025 retry): %s in", site.c_str());
    for (const std::string& p : in) std::printf(" %s", p.c_str());
    std::printf("\n");
  }
  EXPECT_GT(programs, 60u) << "the variant sweep compiled fewer programs than it should";
  for (const std::string& r : rule1) ADD_FAILURE() << "rule 1 (NVIDIA C9999 __setVectorIndex): " << r;
  for (const std::string& r : rule2_new) ADD_FAILURE() << "rule 2 (NVIDIA C5025): " << r;
}

}  // namespace
}  // namespace zenith::render::testing
