#pragma once
// The binding points (and a few sizes) that the C++ side and the GLSL shaders share: storage
// buffers (layout(std430, binding = ...)), uniform buffers (layout(std140, ...)),
// texture units (samplers) and image units. This is the only place their numbers are written: the program factory
// (render/shader_programs.h) injects each one as `#define <NAME> <value>` into
// every shader loaded from shaders/ (shader_interface_defines()), and the
// shaders declare `layout(binding = <NAME>)`. The GL wrapper
// (render/gl/shader_program.h) knows none of them.
//
// GL keeps storage bindings, uniform-buffer bindings, texture units and image units apart; numbers need
// only differ within one kind among the resources of one program (the
// precompute's harmonic buffers and the frame's FrameRgb share 6, for example,
// and never meet in a program).
#include <tuple>
#include <vector>

#include "atmosphere/solar_limb_darkening.h"
#include "render/gl/shader_program.h"

namespace zenith::render::binding {

// ---- storage buffers
inline constexpr unsigned kTableData = 1;             ///< TABLE_DATA_BINDING (atmosphere/physics.glsl)
inline constexpr unsigned kTexelCoordinates = 2;      ///< TEXEL_COORDINATES_BINDING (atmosphere_common.glsl)
inline constexpr unsigned kRowSums = 3;               ///< ROW_SUMS_BINDING (radiance_sum.comp)
inline constexpr unsigned kBodies = 4;                ///< BODIES_BINDING (render/frame.glsl)
inline constexpr unsigned kTiles = 5;                 ///< TILES_BINDING (render/frame.glsl)
inline constexpr unsigned kFrameRgb = 6;              ///< FRAME_RGB_BINDING (render/frame_rgb.glsl)
inline constexpr unsigned kAzimuthMoments = 6;        ///< AZIMUTH_MOMENTS_BINDING (harmonics.glsl)
inline constexpr unsigned kHarmonicCoefficients = 7;  ///< HARMONIC_COEFFICIENTS_BINDING (harmonics.glsl)
inline constexpr unsigned kViewTransmittance = 8;     ///< VIEW_TRANSMITTANCE_BINDING (view_ray.glsl)
inline constexpr unsigned kViewRayCoordinates = 9;    ///< VIEW_RAY_COORDINATES_BINDING (view_ray.glsl)
inline constexpr unsigned kBlackTiles = 10;           ///< BLACK_TILES_BINDING (render/band_output.glsl)
inline constexpr unsigned kStarSplats = 11;           ///< STAR_SPLATS_BINDING (render/star_splat.comp)
inline constexpr unsigned kStarAccumulator = 12;      ///< STAR_ACCUMULATOR_BINDING (render/star_accumulator.glsl)
inline constexpr unsigned kNightSkyTable = 13;        ///< NIGHT_SKY_TABLE_BINDING (render/night_sky.comp)
inline constexpr unsigned kStarPixelList = 14;        ///< STAR_PIXEL_LIST_BINDING (render/star_pixels.comp)
inline constexpr unsigned kAirShadows = 15;           ///< AIR_SHADOWS_BINDING (render/frame.glsl)

// ---- uniform buffers
inline constexpr unsigned kWavelengthData =
    0;  ///< WAVELENGTH_DATA_BINDING (atmosphere/physics.glsl): the model's parameters
inline constexpr unsigned kFp64Constants =
    1;  ///< FP64_CONSTANTS_BINDING (atmosphere/maths.glsl): fp64 shaders' constants

// ---- texture units: the tables (precompute and render passes), then the frame's own
inline constexpr unsigned kTransmittanceUnit = 0;    ///< TRANSMITTANCE_UNIT (atmosphere_common.glsl)
inline constexpr unsigned kSingleRayleighUnit = 1;   ///< SINGLE_RAYLEIGH_UNIT
inline constexpr unsigned kSingleMieUnit = 2;        ///< SINGLE_MIE_UNIT
inline constexpr unsigned kDeltaRadianceUnit = 3;    ///< DELTA_RADIANCE_UNIT (precompute, previous_order.glsl)
inline constexpr unsigned kMultipleUnit = 3;         ///< MULTIPLE_UNIT (render/atmosphere_segment.glsl)
inline constexpr unsigned kDeltaIrradianceUnit = 4;  ///< DELTA_IRRADIANCE_UNIT (precompute)
inline constexpr unsigned kIrradianceUnit = 4;       ///< IRRADIANCE_UNIT (render/atmosphere_segment.glsl)
inline constexpr unsigned kDensityUnit = 5;          ///< DENSITY_UNIT (multiple_scattering.comp)
inline constexpr unsigned kSkyViewUnit = 5;          ///< SKY_VIEW_UNIT (render/atmosphere_tile.comp)
inline constexpr unsigned kEclipseSkyUnit = 6;       ///< ECLIPSE_SKY_UNIT (render/atmosphere_tile.comp)
inline constexpr unsigned kRayTableUnit = 7;         ///< RAY_TABLE_UNIT (projection.glsl)
inline constexpr unsigned kAlbedoMapsUnit = 8;       ///< ALBEDO_MAPS_UNIT (render/surface_albedo.glsl)
inline constexpr unsigned kMoonAlbedoUnit = 9;       ///< MOON_ALBEDO_UNIT (render/night_sky.comp: the Moon's face)
inline constexpr unsigned kShadowProfileUnit = 10;   ///< SHADOW_PROFILE_UNIT (render/moon_shadow.glsl)
inline constexpr unsigned kShadowFieldUnit = 11;     ///< SHADOW_FIELD_UNIT (render/moon_shadow.glsl)
inline constexpr unsigned kPresentFrameUnit = 0;     ///< PRESENT_FRAME_UNIT (render/present.frag)
inline constexpr unsigned kDisplayRadianceUnit = 0;  ///< DISPLAY_RADIANCE_UNIT (render/display_*.comp)
inline constexpr unsigned kBlendMaskUnit = 1;        ///< BLEND_MASK_UNIT (render/display_transform.glsl)
// The MPCDI colour profile's LUTs (render/display/colour_profile_textures.h, display_transform.glsl).
inline constexpr unsigned kDecodeLutUnit = 2;     ///< DECODE_LUT_UNIT: 1D
inline constexpr unsigned kCorrectLut1dUnit = 3;  ///< CORRECT_LUT_1D_UNIT
inline constexpr unsigned kCorrectLut3dUnit = 4;  ///< CORRECT_LUT_3D_UNIT
inline constexpr unsigned kEncodeLut1dUnit = 5;   ///< ENCODE_LUT_1D_UNIT
inline constexpr unsigned kEncodeLut3dUnit = 6;   ///< ENCODE_LUT_3D_UNIT

// ---- image units: what a compute pass writes (the precompute's tables, the sky-view table)
inline constexpr unsigned kOutputImage = 0;        ///< OUTPUT_IMAGE
inline constexpr unsigned kSecondOutputImage = 1;  ///< SECOND_OUTPUT_IMAGE (single Mie, accumulated sums)
// ---- image units of the render passes' G-buffer (gbuffer.comp, atmosphere_pass.comp, resolve.comp)
inline constexpr unsigned kGbufferHitImage = 0;            ///< GBUFFER_HIT_IMAGE
inline constexpr unsigned kGbufferAlbedoImage = 1;         ///< GBUFFER_ALBEDO_IMAGE
inline constexpr unsigned kRadianceSumImage = 2;           ///< RADIANCE_SUM_IMAGE
inline constexpr unsigned kTransmittanceProductImage = 3;  ///< TRANSMITTANCE_PRODUCT_IMAGE

}  // namespace zenith::render::binding

namespace zenith::render {

/// Texels a row of a colour 1D LUT's texture (LUT_1D_ROW_TEXELS,
/// render/display/colour_profile_textures.h, display_transform.glsl).
inline constexpr int kLut1dRowTexels = 1024;

/// Coefficients of the sun's limb darkening polynomial (LIMB_COEFFICIENTS:
/// group_light.glsl's limb_polynomial[], direct_light.comp's sun_rgb_limb[]).
inline constexpr int kLimbCoefficients = int(std::tuple_size_v<decltype(atmosphere::LimbDarkening::coefficients)>);

}  // namespace zenith::render

namespace zenith::render {

/// The defines every shader loaded from shaders/ gets before its own: each
/// binding point above, LIMB_COEFFICIENTS, TILE_SIZE, TILE_ROW_SHIFT and
/// TILE_COLUMN_MASK (render/frame/tile_culling.h: the render passes' work
/// groups and tiles, the packing of a tile list's words), PROJECTION_KIND_*
/// (warp/projection.h's ProjectionKind), and PI_F, π as a float literal
/// (core/units.h's kPi).
std::vector<gl::ShaderDefine> shader_interface_defines();

}  // namespace zenith::render
