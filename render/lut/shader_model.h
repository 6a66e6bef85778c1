#pragma once
// What a shader that includes shaders/atmosphere_common.glsl needs to know about
// an atmosphere model: the #defines that specialise it (radii, table sizes, phase
// models, which terms exist) and the contents of its two model storage buffers
// (per-wavelength-group coefficients at binding 0, profiles, quadrature rules and
// the air-mass table at binding 1). Shared by the GPU precompute and the renderer.
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
  /// TexelCoordinates layout), each from its C++ definition.
  std::vector<gl::ShaderDefine> defines;
  std::vector<double> wavelength_data;  ///< WavelengthData (binding 0): real4 fields per group
  std::vector<double> table_data;       ///< TableData (binding 1)
  std::size_t group_count = 0;          ///< ceil(wavelengths / 4)
  TexelCoordinateLayout texel_layout;
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
