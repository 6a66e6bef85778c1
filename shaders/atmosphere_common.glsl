// Shared code of the lookup-table precomputation on the GPU
// (render/lut/gpu_precompute.cpp). Every function mirrors, operation for
// operation, the CPU implementation in atmosphere/lut/ (parameterization.cpp,
// table.cpp, lookup_tables.cpp, quadrature.h, cpu_precompute.cpp) and
// atmosphere/ (density_profile.cpp, phase_functions.cpp, air_mass.cpp), so the
// two paths produce the same tables (bit-identical on Mesa llvmpipe). Expressions
// keep the CPU's evaluation order (a · b · c is (a · b) · c, as in C++), and
// geometry is PRECISE (no fused multiply-add): change both sides together.
//
// Precision (USE_FP64): 1 runs geometry, quadrature sums and table
// interpolation in double, like the CPU. GLSL has no double exp/log/sin/cos/acos,
// so this file implements them (exp_r, log_r, sincos_r/cos_r, acos_r below,
// within a few ulp of the C library). 0 is the float fallback: every `real` is a
// float and the built-in functions are used. Tables are float32 either way.
//
// Wavelengths: one dispatch handles one group of 4 wavelengths (`wavelength_group`),
// so every radiance is a real4; the tables of group g are RGBA32F textures holding
// wavelengths 4g..4g+3 (unused lanes of the last group have zero coefficients).
//
// Defines set by the C++ side (all required):
//   USE_FP64                               1: double, 0: float
//   BOTTOM_RADIUS, TOP_RADIUS              metres (reals: see "Constants" below)
//   TRANSMITTANCE_MU, TRANSMITTANCE_R, IRRADIANCE_MU_S, IRRADIANCE_R,
//   SCATTERING_R, SCATTERING_MU, SCATTERING_MU_S, SCATTERING_NU   table sizes
//   GEOMETRIC_BLEND_FULL_LOG_RATIO                                 float literal (lookup_tables.h)
//   RAYLEIGH_PHASE                         0 classic, 1 Penndorf, 2 depolarized
//   RAYLEIGH_DEPOLARIZATION                δ (a real; used by RAYLEIGH_PHASE 2)
//   HAS_MIE                                0 drops every Mie term
//   MIE_PHASE                              0 Henyey–Greenstein, 1 double HG, 2 Cornette–Shanks, 3 tabulated
//   MIE_TABLE, MIE_TABLE_SAMPLES           the tabulated phase's offset in TableData (read from
//                                          WavelengthData's header at run time) and samples per wavelength
//   ABSORBER_COUNT                         0 drops the absorber loop
//   AIR_MASS                               0 drops the air-mass stretch
//   MODEL_HEADER_VECTORS                   real4s of WavelengthData before the groups' fields
//   WAVELENGTH_FIELDS                      real4s per wavelength group in WavelengthData
//   WAVELENGTH_DATA_SIZE                   real4s of WavelengthData (header + groups × fields)
//   MODEL_AT_RUN_TIME                      0: the precompute's programs, every value above a define;
//                                          1: the render passes' programs, shared by every atmosphere
//                                          (ShaderModel::shared_defines): the radii, δ, the phase models
//                                          and the field stride read from WavelengthData's header; the
//                                          precompute's own defines (rules, moments, absorbers, air mass)
//                                          absent, extinction() and air_mass_stretch() with them
//   RAYLEIGH_PROFILE, MIE_PROFILE, AIR_MASS_PROFILE, ABSORBER_PROFILES
//                                          offsets of profile descriptors in TableData
//   AIR_MASS_GROUND_RADIUS, AIR_MASS_TABLE, AIR_MASS_TABLE_SIZE   the stretch table
//   QUADRATURE_LOG_LINEAR                  1: log-linear interval rule, 0: trapezoid
//   SCATTERING_SAMPLES, TRANSMITTANCE_SAMPLES (even)
//   SPHERE_ZENITH_SAMPLES, SPHERE_RULE     Gauss–Legendre rule of the scattering density
//   HEMISPHERE_ZENITH_SAMPLES, HEMISPHERE_RULE   and of the sky irradiance (nodes, weights in TableData)
//   PI, INV_4PI, PENNDORF_A, PENNDORF_B, SERIES_LIMIT   reals: core/units.h,
//                                          atmosphere/phase_functions.h, atmosphere/lut/quadrature.h
//   LN2_HI, LN2_LO, INV_LN2, TWO_OVER_PI, PIO2_1, PIO2_1T, SQRT_HALF, FP64_CONSTANT_VECTORS   (fp64)
//   FIELD_*                                real4 fields of WavelengthData (shader_model.cpp)
//   TEXEL_MU_S, TEXEL_SUN_THETA_MAX, TEXEL_MU_SKY, TEXEL_VALUE_COUNT   TexelCoordinates layout
// and, for every shader loaded from shaders/, the binding points (*_BINDING,
// *_UNIT, *_IMAGE) of render/shader_bindings.h.
//
// Constants: every real constant shared with the C++ code is written once, in
// C++, and reaches the shaders through the shader model (shader_model.cpp): a
// float literal in fp32; in fp64 the bits of the C++ double in the
// Fp64Constants uniform block (atmosphere/maths.glsl), the define naming its
// entry, so no driver's reading of double literals can change one.
// The model's parameters reach every shader one way: the WavelengthData
// uniform block (atmosphere/physics.glsl).

// The code itself is in four files under shaders/atmosphere/, included here in
// this order (each uses only what the ones before it define; docs/shaders.md):
//   maths.glsl             precision, double elementary functions, quadrature, vectors
//   physics.glsl           the model's data, densities, extinction, air mass, phase functions
//   parameterization.glsl  geometry and the tables' coordinate mappings
//   table_sampling.glsl    interpolation, the 4D read, transmittance queries

#include "atmosphere/maths.glsl"
#include "atmosphere/physics.glsl"
#include "atmosphere/parameterization.glsl"
#include "atmosphere/table_sampling.glsl"

/// The slab of r (z) layers one dispatch covers starts here.
uniform int z_offset;
