// What the C++ side and the shaders share, checked on the GPU
// (render/shader_bindings.h, render/lut/shader_model.h, render/frame/gpu_body.h):
//  * the std430 layout of render/body.glsl's Body against GpuBody, field by
//    field: a distinct value in every float of a GpuBody array, each Body field
//    read back by the shader and located in that array, so a field moved on
//    either side fails naming it, with both byte offsets;
//  * the constants of the shader model as atmosphere_common.glsl sees them
//    (PI, INV_4PI, PENNDORF_A/B, SERIES_LIMIT), exactly the C++ values (rounded
//    to float in fp32; in fp64 they come as doubles in the Fp64Constants
//    uniform block, so equal on any driver);
//  * the WavelengthData fields by name (FIELD_*): each the model's spectrum;
//  * the tile words of the render passes' tile lists (render/frame/tile_culling.h's
//    pack_tile): frame.glsl's tile_pixel() finds the pixels of the tile the C++
//    side packed, at both ends of the column's and the row's bits.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include "atmosphere/lut/parameterization.h"
#include "atmosphere/lut/quadrature.h"
#include "atmosphere/parameters.h"
#include "atmosphere/phase_functions.h"
#include "core/units.h"
#include "render/frame/gpu_body.h"
#include "render/frame/tile_culling.h"
#include "render/gl/buffer.h"
#include "render/gl/shader_program.h"
#include "render/lut/shader_model.h"
#include "render/shader_bindings.h"
#include "tests/render/render_test_support.h"
#include "tests/render/test_shaders.h"

namespace zenith::render {
namespace {

constexpr unsigned kTestOutputBinding = 3;  ///< not one of atmosphere_common.glsl's storage buffers (1, 2)

/// A buffer of reals (double in fp64, float otherwise) read back as doubles.
std::vector<double> read_reals(const gl::Buffer& buffer, bool fp64) {
  if (fp64) return buffer.read<double>();
  const std::vector<float> f = buffer.read<float>();
  return std::vector<double>(f.begin(), f.end());
}

/// `value` as the shader holds it: a double, or rounded to float.
double as_real(double value, bool fp64) { return fp64 ? value : static_cast<double>(static_cast<float>(value)); }

TEST(ShaderInterface, BodyLayoutMatchesGpuBodyFieldByField) {
  testing::context();
  constexpr std::size_t kBodies = 3, kFloatsPerBody = sizeof(GpuBody) / sizeof(float);
  // Float j of the array holds j + 1 (exact in float): a value names its byte offset.
  std::vector<float> raw(kBodies * kFloatsPerBody);
  std::iota(raw.begin(), raw.end(), 1.0f);
  const gl::Buffer bodies = gl::Buffer::from(std::span<const float>(raw));
  bodies.bind_storage(binding::kBodies);
  const gl::Buffer fields(kBodies * 6 * 4 * sizeof(float));
  fields.bind_storage(kTestOutputBinding);
  const gl::ShaderProgram program = testing::load_test_compute_program(
      "test_body_layout.comp", std::vector<gl::ShaderDefine>{{"FIELDS_BINDING", std::to_string(kTestOutputBinding)}});
  ASSERT_TRUE(program.set_uniform("body_count", static_cast<int>(kBodies)));
  program.dispatch_covering(1);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  const std::vector<float> out = fields.read<float>();

  struct Field {
    const char* glsl_name;
    std::size_t cpp_offset;  ///< bytes from the start of GpuBody
  };
  const std::size_t vec4_bytes = sizeof(GpuBody::Vec4);
  const Field declared[6] = {{"centre", offsetof(GpuBody, centre)},
                             {"shape", offsetof(GpuBody, shape)},
                             {"albedo_map", offsetof(GpuBody, albedo_map)},
                             {"world_to_body0", offsetof(GpuBody, world_to_body)},
                             {"world_to_body1", offsetof(GpuBody, world_to_body) + vec4_bytes},
                             {"world_to_body2", offsetof(GpuBody, world_to_body) + 2 * vec4_bytes}};
  for (std::size_t b = 0; b < kBodies; ++b)
    for (std::size_t k = 0; k < 6; ++k)
      for (std::size_t c = 0; c < 4; ++c) {
        // The byte offset in the buffer that GLSL read Body.<field>[c] of body b from.
        const double read = out[(b * 6 + k) * 4 + c];
        const double glsl_offset = (read - 1.0) * sizeof(float);
        const double cpp_offset = double(b * sizeof(GpuBody) + declared[k].cpp_offset + c * sizeof(float));
        EXPECT_EQ(glsl_offset, cpp_offset)
            << "Body." << declared[k].glsl_name << "[" << c << "] of body " << b << ": the shader reads byte "
            << glsl_offset << " of the Bodies buffer, GpuBody puts it at byte " << cpp_offset;
      }
}

void expect_shader_model_constants(const std::string& preset, bool fp64) {
  SCOPED_TRACE(preset + (fp64 ? " fp64" : " fp32"));
  testing::context();
  const atmosphere::AtmosphereModel model = atmosphere::load_preset(preset).model;
  atmosphere::lut::PrecomputeOptions options;
  options.sizes = atmosphere::lut::TableSizes::small();
  const ShaderModel m = shader_model(model, options, fp64);
  const ModelBuffers buffers(m);
  buffers.bind();
  const std::size_t real_size = fp64 ? sizeof(double) : sizeof(float);
  const gl::Buffer texel_values(m.texel_layout.count * real_size);
  texel_values.bind_storage(binding::kTexelCoordinates);
  const gl::Buffer values((8 + 4 * 8) * real_size);
  values.bind_storage(kTestOutputBinding);
  std::vector<gl::ShaderDefine> defines = m.defines;
  defines.push_back({"VALUES_BINDING", std::to_string(kTestOutputBinding)});
  const gl::ShaderProgram program = testing::load_test_compute_program("test_shader_model.comp", defines);
  program.set_uniform("wavelength_group", 0);
  program.dispatch_covering(1);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  const std::vector<double> v = read_reals(values, fp64);

  EXPECT_EQ(v[0], as_real(core::kPi, fp64)) << "PI";
  EXPECT_EQ(v[1], as_real(atmosphere::kInv4Pi, fp64)) << "INV_4PI";
  EXPECT_EQ(v[2], as_real(atmosphere::kPenndorfA, fp64)) << "PENNDORF_A";
  EXPECT_EQ(v[3], as_real(atmosphere::kPenndorfB, fp64)) << "PENNDORF_B";
  EXPECT_EQ(v[4], as_real(atmosphere::lut::kLogLinearSeriesLimit, fp64)) << "SERIES_LIMIT";

  struct Field {
    const char* name;
    const atmosphere::Spectrum* spectrum;
  };
  std::vector<Field> named = {{"FIELD_RAYLEIGH_SCATTERING", &model.rayleigh_scattering_m1},
                              {"FIELD_MIE_SCATTERING", &model.mie_scattering_m1},
                              {"FIELD_MIE_EXTINCTION", &model.mie_extinction_m1},
                              {"FIELD_MIE_G1", &model.mie_phase.g1},
                              {"FIELD_MIE_G2", &model.mie_phase.g2},
                              {"FIELD_MIE_ALPHA", &model.mie_phase.alpha},
                              {"FIELD_GROUND_ALBEDO", &model.ground_albedo}};
  if (!model.absorbers.empty()) named.push_back({"FIELD_ABSORBERS", &model.absorbers[0].absorption_m1});
  std::size_t nonzero = 0;
  for (std::size_t f = 0; f < named.size(); ++f)
    for (std::size_t k = 0; k < kWavelengthLanes && k < named[f].spectrum->size(); ++k) {
      const double expected = as_real((*named[f].spectrum)[k], fp64);
      nonzero += expected != 0.0;
      EXPECT_EQ(v[8 + 4 * f + k], expected) << named[f].name << ", wavelength " << k;
    }
  EXPECT_GT(nonzero, 4 * 4u) << "the model's fields should not all be zero";
}

TEST(ShaderInterface, ShaderModelConstantsAndFieldsAreTheCppOnesInFp64) {
  expect_shader_model_constants("earth-advanced", true);
  expect_shader_model_constants("mars", true);
}

TEST(ShaderInterface, ShaderModelConstantsAndFieldsAreTheCppOnesInFp32) {
  expect_shader_model_constants("earth-advanced", false);
  expect_shader_model_constants("mars", false);
}

/// The render passes build one program for every atmosphere of the same table
/// sizes and precision (ShaderModel::shared_defines): no define of theirs
/// holds a model's own value, and the model reaches them in WavelengthData's header.
TEST(ShaderInterface, EveryPresetSharesTheRenderProgramsAndHeadsItsWavelengthData) {
  atmosphere::lut::PrecomputeOptions options;
  options.sizes = atmosphere::lut::TableSizes::small();
  const std::set<std::string> precompute_only = {
      "RAYLEIGH_PHASE", "MIE_PHASE",   "ABSORBER_COUNT", "AIR_MASS",        "SPHERE_RULE",
      "HARMONIC_RULE",  "MIE_MOMENTS", "AIR_MASS_TABLE", "HEMISPHERE_RULE", "RAYLEIGH_MOMENTS"};
  for (bool fp64 : {false, true}) {
    std::map<bool, std::vector<gl::ShaderDefine>> by_mie;  // has Mie → the shared defines
    for (const std::string& preset : atmosphere::preset_names()) {
      SCOPED_TRACE(preset + (fp64 ? " fp64" : " fp32"));
      const atmosphere::AtmosphereModel model = atmosphere::load_preset(preset).model;
      const ShaderModel m = shader_model(model, options, fp64);
      const auto value_of = [](const std::vector<gl::ShaderDefine>& defines, const std::string& name) {
        for (const gl::ShaderDefine& d : defines)
          if (d.name == name) return d.value;
        return std::string("(absent)");
      };
      EXPECT_EQ(value_of(m.defines, "MODEL_AT_RUN_TIME"), "0");
      EXPECT_EQ(value_of(m.shared_defines, "MODEL_AT_RUN_TIME"), "1");
      for (const gl::ShaderDefine& d : m.shared_defines) EXPECT_FALSE(precompute_only.contains(d.name)) << d.name;
      const auto [it, first] = by_mie.try_emplace(model.has_mie(), m.shared_defines);
      if (!first) {
        ASSERT_EQ(it->second.size(), m.shared_defines.size());
        for (std::size_t i = 0; i < m.shared_defines.size(); ++i)
          EXPECT_EQ(it->second[i].value, m.shared_defines[i].value) << m.shared_defines[i].name << " differs";
      }
      // The header (shader_model.h): the radii, δ, H; the phase models, the fields, Mie; A.
      const std::vector<double>& w = m.wavelength_data;
      ASSERT_GE(w.size(), kModelHeaderVectors * kWavelengthLanes);
      EXPECT_EQ(w[0], model.ground_radius_m);
      EXPECT_EQ(w[1], model.top_radius_m);
      EXPECT_EQ(w[2], model.rayleigh_depolarization);
      const atmosphere::lut::ShellGeometry g{model.ground_radius_m, model.top_radius_m};
      const double H = g.horizon_distance_at_top_m();
      EXPECT_NEAR(w[3], H, (fp64 ? 1e-15 : 1e-7) * H) << "H in the shaders' precision";
      EXPECT_EQ(w[6], std::stod(value_of(m.defines, "FIELD_ABSORBERS")) + double(model.absorbers.size()));
      EXPECT_EQ(w[7], model.has_mie() ? 1.0 : 0.0);
      // A: the μs distance mapping's (d_top(rb, μs_min) − d_min) / (d_max − d_min), in double here.
      const double d_min = model.top_radius_m - model.ground_radius_m;
      const double A = (g.distance_to_top_m(model.ground_radius_m, g.min_sun_cosine()) - d_min) / (H - d_min);
      EXPECT_NEAR(w[8], A, (fp64 ? 1e-12 : 1e-4) * A) << "A in the shaders' precision";
    }
  }
}

TEST(ShaderInterface, TileWordsReachTheShadersAsTheCppPacksThem) {
  testing::context();
  struct Tile {
    std::uint32_t column, band_row;
  };
  // Inside the band, straddling its corner, and at both ends of the column's and the row's bits.
  const std::vector<Tile> tiles = {
      {0, 0}, {3, 2}, {4, 3}, {kTileColumnMask, 1}, {1, 0xfffe}, {kTileColumnMask, 0xffff}};
  const std::array<int, 2> band_size = {4 * kTileSize + 5, 3 * kTileSize + 7};
  // Word 0 is not the pass's: tile_offset skips it.
  std::vector<std::uint32_t> words = {pack_tile(9, 9)};
  for (const Tile& t : tiles) {
    words.push_back(pack_tile(t.column, t.band_row));
    ASSERT_EQ(tile_column(words.back()), t.column);
    ASSERT_EQ(tile_band_row(words.back()), t.band_row);
  }
  const gl::Buffer tile_words = gl::Buffer::from(std::span<const std::uint32_t>(words));
  tile_words.bind_storage(binding::kTiles);
  constexpr std::size_t kPixelsPerTile = std::size_t{kTileSize} * kTileSize;
  const gl::Buffer pixels(tiles.size() * kPixelsPerTile * 4 * sizeof(std::int32_t));
  pixels.bind_storage(kTestOutputBinding);
  const gl::ShaderProgram program = testing::load_test_compute_program(
      "test_tile_words.comp", std::vector<gl::ShaderDefine>{{"PIXELS_BINDING", std::to_string(kTestOutputBinding)}});
  ASSERT_TRUE(program.set_uniform("band_size", band_size));
  ASSERT_TRUE(program.set_uniform("tile_offset", 1));
  ASSERT_TRUE(program.set_uniform("tile_count", static_cast<int>(tiles.size())));
  program.dispatch(static_cast<unsigned>(tiles.size()));
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  const std::vector<std::int32_t> out = pixels.read<std::int32_t>();
  ASSERT_EQ(out.size(), tiles.size() * kPixelsPerTile * 4);

  std::size_t inside = 0;
  for (std::size_t t = 0; t < tiles.size(); ++t)
    for (std::size_t i = 0; i < kPixelsPerTile; ++i) {
      const std::int32_t* p = &out[(t * kPixelsPerTile + i) * 4];
      const auto x = static_cast<std::int64_t>(tiles[t].column) * kTileSize + static_cast<std::int64_t>(i % kTileSize);
      const auto y =
          static_cast<std::int64_t>(tiles[t].band_row) * kTileSize + static_cast<std::int64_t>(i / kTileSize);
      ASSERT_EQ(p[0], x) << "tile " << tiles[t].column << ", " << tiles[t].band_row << ", invocation " << i;
      ASSERT_EQ(p[1], y) << "tile " << tiles[t].column << ", " << tiles[t].band_row << ", invocation " << i;
      const bool in_band = x < band_size[0] && y < band_size[1];
      ASSERT_EQ(p[2], in_band ? 1 : 0) << "tile " << tiles[t].column << ", " << tiles[t].band_row << ", invocation "
                                       << i;
      inside += in_band;
    }
  EXPECT_EQ(inside, 2 * kPixelsPerTile + 5u * 7u) << "tiles (0, 0) and (3, 2) whole, 5 × 7 pixels of (4, 3)";
}

}  // namespace
}  // namespace zenith::render
