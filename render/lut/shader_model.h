#pragma once
// What a shader that includes shaders/atmosphere_common.glsl needs to know about
// an atmosphere model: the #defines that specialise it (radii, table sizes, phase
// models, which terms exist) and the contents of its two model storage buffers
// (per-wavelength-group coefficients in the WavelengthData uniform block,
// profiles, quadrature rules and the air-mass table in the TableData storage
// buffer). Shared by the GPU precompute and the renderer.
#include <cstddef>
#include <string>
#include <vector>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/precompute_options.h"
#include "atmosphere/lut/table_sizes.h"
#include "render/gl/buffer.h"
#include "render/gl/shader_program.h"

namespace zenith::render {

/// Wavelengths per group: one RGBA32F texel, one real4 in the shaders.
inline constexpr std::size_t kWavelengthLanes = 4;
/// real4s of WavelengthData before the first group's fields: the model values
/// the shared render programs read at run time (ShaderModel::wavelength_data).
inline constexpr std::size_t kModelHeaderVectors = 3;
/// The largest WavelengthData block shader_model makes (bytes): the uniform
/// block size every GL 4.5 implementation supports (GL_MAX_UNIFORM_BLOCK_SIZE).
inline constexpr std::size_t kMaxWavelengthDataBytes = 16384;

/// Where the texel-coordinate values (TexelCoordinates, binding::kTexelCoordinates)
/// lie, in reals: what texel_coordinates.comp writes and scattering_texel_coordinates
/// reads (TEXEL_* defines of the shader model).
struct TexelCoordinateLayout {
  std::size_t mu_s = 0;           ///< TEXEL_MU_S: μs of each μs index, [mapping][index]
  std::size_t sun_theta_max = 0;  ///< TEXEL_SUN_THETA_MAX: acos(μs_min)
  std::size_t mu_sky = 0;         ///< TEXEL_MU_SKY: μ of each sky μ index, [mapping][z][y − SCATTERING_MU/2]
  std::size_t count = 0;          ///< TEXEL_VALUE_COUNT
};
TexelCoordinateLayout texel_coordinate_layout(const atmosphere::lut::TableSizes& sizes);

struct ShaderModel {
  /// Everything atmosphere_common.glsl needs defined: the model, the table sizes,
  /// and the constants it shares with the C++ code (π, 1/4π, Penndorf's
  /// coefficients, the log-linear series limit, the WavelengthData fields and the
  /// TexelCoordinates layout), each from its C++ definition (real constants:
  /// float literals in fp32, names of fp64_constants entries in fp64).
  std::vector<gl::ShaderDefine> defines;
  /// The same for the render passes' programs, with everything that differs
  /// between atmospheres of the same table sizes and precision read at run
  /// time instead (MODEL_AT_RUN_TIME 1): the radii, the Rayleigh and Mie phase
  /// models, δ and the WavelengthData stride from its header; WavelengthData
  /// declared at its largest size; the precompute's own values (quadrature
  /// rules, moments, absorbers, the air-mass table) left out, so no render
  /// program can read them. Atmospheres that differ only in those share every
  /// program: a frame's programs do not multiply with its atmospheres.
  std::vector<gl::ShaderDefine> shared_defines;
  /// WavelengthData (a uniform block, binding::kWavelengthData): a header of
  /// kModelHeaderVectors real4s — (bottom radius, top radius, Rayleigh
  /// depolarisation δ, H = √(rt² − rb²)), (Rayleigh phase model, Mie phase
  /// model, fields per group, has Mie), (the μs distance mapping's limit A,
  /// the tabulated Mie phase's offset in TableData, 0, 0) — then real4 fields per group: the one way the model's
  /// parameters reach every shader. H and A are computed as the shaders
  /// compute them, in their precision (shader_model.cpp: shell_constants).
  std::vector<double> wavelength_data;
  std::vector<double> table_data;  ///< TableData (binding 1)
  std::size_t group_count = 0;     ///< ceil(wavelengths / 4)
  TexelCoordinateLayout texel_layout;
  bool fp64 = false;  ///< made for double shaders (USE_FP64)
  /// fp64 only: every real constant of the double shaders (the elementary
  /// functions' ln 2 and π/2 splits, π, 1/4π, Penndorf's coefficients, the
  /// radii, …) as the C++ double, in the order the defines name them
  /// (PI → fp64_constants[k / 4].xyzw[k % 4]): the Fp64Constants uniform block,
  /// whole dvec4s. No double constant is a GLSL literal, which a driver may read
  /// through float (NVIDIA 580.159.04). fp32 shaders get float literals.
  std::vector<double> fp64_constants;
};

/// A ShaderModel's values on the GPU, bound where its shaders read them:
/// WavelengthData and Fp64Constants (uniform blocks) and TableData (a storage
/// buffer). The precompute, the render passes and the tests all make and bind
/// these, the one way a model's parameters reach a shader.
struct ModelBuffers {
  ModelBuffers() = default;
  explicit ModelBuffers(const ShaderModel& model);
  /// At binding::kWavelengthData, kFp64Constants (uniform buffers) and kTableData (storage).
  void bind() const;
  gl::Buffer wavelength_data, table_data, fp64_constants;  ///< fp64_constants: none (id 0) in fp32
};

/// The defines and buffer contents for `model` with the table sizes and
/// quadrature settings of `options`, for double (`fp64`) or float shaders.
ShaderModel shader_model(const atmosphere::AtmosphereModel& model, const atmosphere::lut::PrecomputeOptions& options,
                         bool fp64);

/// A GLSL literal of `value`: 17 significant digits and the LF suffix in double
/// (round-trips exactly), 9 digits in float.
std::string glsl_literal(double value, bool fp64);
/// A storage buffer of `values` as doubles (fp64) or floats.
gl::Buffer real_buffer(const std::vector<double>& values, bool fp64);

}  // namespace zenith::render
