#include "render/shader_bindings.h"

#include <fmt/format.h>

#include "core/units.h"
#include "render/frame/air_shadows.h"
#include "render/frame/tile_culling.h"
#include "warp/projection.h"

namespace zenith::render {

std::vector<gl::ShaderDefine> shader_interface_defines() {
  using namespace binding;
  struct Point {
    const char* name;
    unsigned value;
  };
  constexpr Point kPoints[] = {
      {"WAVELENGTH_DATA_BINDING", kWavelengthData},
      {"FP64_CONSTANTS_BINDING", kFp64Constants},
      {"TABLE_DATA_BINDING", kTableData},
      {"TEXEL_COORDINATES_BINDING", kTexelCoordinates},
      {"ROW_SUMS_BINDING", kRowSums},
      {"BODIES_BINDING", kBodies},
      {"TILES_BINDING", kTiles},
      {"FRAME_RGB_BINDING", kFrameRgb},
      {"AZIMUTH_MOMENTS_BINDING", kAzimuthMoments},
      {"HARMONIC_COEFFICIENTS_BINDING", kHarmonicCoefficients},
      {"VIEW_TRANSMITTANCE_BINDING", kViewTransmittance},
      {"VIEW_RAY_COORDINATES_BINDING", kViewRayCoordinates},
      {"BLACK_TILES_BINDING", kBlackTiles},
      {"STAR_SPLATS_BINDING", kStarSplats},
      {"STAR_ACCUMULATOR_BINDING", kStarAccumulator},
      {"NIGHT_SKY_TABLE_BINDING", kNightSkyTable},
      {"STAR_PIXEL_LIST_BINDING", kStarPixelList},
      {"AIR_SHADOWS_BINDING", kAirShadows},
      {"TRANSMITTANCE_UNIT", kTransmittanceUnit},
      {"SINGLE_RAYLEIGH_UNIT", kSingleRayleighUnit},
      {"SINGLE_MIE_UNIT", kSingleMieUnit},
      {"DELTA_RADIANCE_UNIT", kDeltaRadianceUnit},
      {"MULTIPLE_UNIT", kMultipleUnit},
      {"DELTA_IRRADIANCE_UNIT", kDeltaIrradianceUnit},
      {"IRRADIANCE_UNIT", kIrradianceUnit},
      {"DENSITY_UNIT", kDensityUnit},
      {"SKY_VIEW_UNIT", kSkyViewUnit},
      {"ECLIPSE_SKY_UNIT", kEclipseSkyUnit},
      {"RAY_TABLE_UNIT", kRayTableUnit},
      {"ALBEDO_MAPS_UNIT", kAlbedoMapsUnit},
      {"MOON_ALBEDO_UNIT", kMoonAlbedoUnit},
      {"SHADOW_PROFILE_UNIT", kShadowProfileUnit},
      {"SHADOW_FIELD_UNIT", kShadowFieldUnit},
      {"PRESENT_FRAME_UNIT", kPresentFrameUnit},
      {"DISPLAY_RADIANCE_UNIT", kDisplayRadianceUnit},
      {"BLEND_MASK_UNIT", kBlendMaskUnit},
      {"DECODE_LUT_UNIT", kDecodeLutUnit},
      {"CORRECT_LUT_1D_UNIT", kCorrectLut1dUnit},
      {"CORRECT_LUT_3D_UNIT", kCorrectLut3dUnit},
      {"ENCODE_LUT_1D_UNIT", kEncodeLut1dUnit},
      {"ENCODE_LUT_3D_UNIT", kEncodeLut3dUnit},
      {"OUTPUT_IMAGE", kOutputImage},
      {"SECOND_OUTPUT_IMAGE", kSecondOutputImage},
      {"GBUFFER_HIT_IMAGE", kGbufferHitImage},
      {"GBUFFER_ALBEDO_IMAGE", kGbufferAlbedoImage},
      {"RADIANCE_SUM_IMAGE", kRadianceSumImage},
      {"TRANSMITTANCE_PRODUCT_IMAGE", kTransmittanceProductImage},
  };
  std::vector<gl::ShaderDefine> defines;
  for (const Point& p : kPoints) defines.push_back({p.name, fmt::format("{}", p.value)});
  defines.push_back({"TILE_SIZE", fmt::format("{}", kTileSize)});
  defines.push_back({"TILE_ROW_SHIFT", fmt::format("{}u", kTileRowShift)});
  defines.push_back({"TILE_COLUMN_MASK", fmt::format("{:#x}u", kTileColumnMask)});
  defines.push_back({"LUT_1D_ROW_TEXELS", fmt::format("{}", kLut1dRowTexels)});
  defines.push_back({"LIMB_COEFFICIENTS", fmt::format("{}", kLimbCoefficients)});
  defines.push_back({"AIR_SHADOW_ENTRIES", fmt::format("{}", kAirShadowEntries)});
  defines.push_back({"MAX_AIR_SHADOWS", fmt::format("{}", kMaxAirShadows)});
  struct Kind {
    const char* name;
    warp::ProjectionKind kind;
  };
  constexpr Kind kKinds[] = {
      {"PROJECTION_KIND_PLANAR", warp::ProjectionKind::planar},
      {"PROJECTION_KIND_FISHEYE", warp::ProjectionKind::fisheye},
      {"PROJECTION_KIND_CYLINDRICAL", warp::ProjectionKind::cylindrical},
      {"PROJECTION_KIND_EQUIRECTANGULAR", warp::ProjectionKind::equirectangular},
      {"PROJECTION_KIND_CUBE_FACE", warp::ProjectionKind::cube_face},
      {"PROJECTION_KIND_RAY_TABLE", warp::ProjectionKind::ray_table},
  };
  for (const Kind& k : kKinds) defines.push_back({k.name, fmt::format("{}", static_cast<int>(k.kind))});
  // 9 significant digits round-trip a float (as render/lut/shader_model.cpp's glsl_literal).
  defines.push_back({"PI_F", fmt::format("{:.8e}", static_cast<float>(core::kPi))});
  return defines;
}

}  // namespace zenith::render
