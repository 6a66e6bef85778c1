#pragma once
// The display pass of a live frame, on the GPU: from a rendered frame's
// exposed radiance (Renderer::render_to_texture) to what its projector is sent,
// in a texture a window draws (render/window/output_windows.h) — tone mapping,
// a fade, the output stage (blend mask α, black level β: a number or, from an
// MPCDI region's beta map, a value per pixel) and the display
// encoding, shaders/render/display_transform.glsl has the equations. The CPU
// path computes the same (image::tone_map, warp::apply_blend,
// image::display_encode; with an MPCDI colour profile, MpcdiColourProfile::process
// of the encoded signal); the GPU's codes equal it within ±1 (8 and 16 bit:
// the float arithmetic before the rounding is good to a few ulp, so only a
// value within that of a rounding boundary can land on the neighbouring code;
// a 3D LUT's hardware trilinear weights add the bound of colour_profile_textures.h).
//
// Pixels leave the GPU only where they leave the machine: a thumbnail is
// reduced on the GPU (at most kMaxThumbnailEdgePx a side) before its few
// values are read back; a file or a test reads the display texture itself
// (offline frames read it back asynchronously through pixel buffer objects,
// frame_readback.h).
// Needs a current GL 4.5 context.
#include <array>
#include <utility>
#include <vector>

#include "image/display_encoding.h"
#include "image/tone_mapping.h"
#include "render/display/colour_profile_textures.h"
#include "render/gl/first_dispatch_warmup.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"
#include "render/gl/texture_rows_draw.h"
#include "render/renderer.h"
#include "warp/blending.h"

namespace zenith::render::display {

/// A fade of the picture toward a colour: level 0 shows the picture, 1 only
/// the colour (black: a fade to black; with level 1, a blackout). Applied to
/// display-linear values before the output stage, so the projectors' blend and
/// black level stay as calibrated.
struct Fade {
  double level = 0.0;                     ///< in [0, 1]
  std::array<double, 3> colour{0, 0, 0};  ///< display-linear RGB, each in [0, 1]
};

/// What one output's display pass does. The blend mask is a texture of the
/// frame's size (blend_mask_texture()), kept by the caller for as long as the
/// output exists: r32f α, or rg32f (α, β) where the output's β is a map (an
/// MPCDI region's beta map), which then replaces `black_level`.
struct OutputStage {
  image::ToneMapping tone = image::ToneMapping::exponential;
  /// Whether the output stage applies (warp/blending.h: P·α·(1 − β) + β). Off,
  /// α and β are not used (an output with neither a blend nor a black level).
  bool blended = false;
  const gl::Texture* blend_mask = nullptr;  ///< r32f α or rg32f (α, β), row 0 at the top; nullptr: α = 1
  double black_level = 0.0;                 ///< β in [0, 0.5] (unused with an rg32f mask: its β)
  image::DisplayEncoding encoding;
  Fade fade;
  /// An MPCDI region's colour profile, its LUTs uploaded once for the output
  /// (kept by the caller while the output exists); nullptr or empty: none.
  /// With one, the output stage runs inside the profile's processPixel on
  /// E(P), the signal `encoding` gives without α and β
  /// (display_transform.glsl; docs/warp-meshes.md, "Colour profile").
  const ColourProfileTextures* colour = nullptr;
};

/// The texture of a blend mask (row 0 at the top), for OutputStage::blend_mask:
/// r32f α, or rg32f (α, β) for a mask with a β map (BlendMask::beta). Made
/// once per output; a live frame reads it on the GPU, nothing comes back.
gl::Texture blend_mask_texture(const warp::BlendMask& mask);

/// A thumbnail's size for a frame of width × height and a longer side of at
/// most edge_px: the longer side min(edge_px, its length), the other keeping the
/// aspect ratio (rounded, at least 1). Throws std::invalid_argument for sizes below 1.
std::array<int, 2> thumbnail_size(int width_px, int height_px, int edge_px);
inline constexpr int kMaxThumbnailEdgePx = 64;

/// A thumbnail of display-linear means, read back from the GPU.
struct ThumbnailMeans {
  int width_px = 0, height_px = 0;
  std::vector<float> rgb;  ///< width · height · 3, each in [0, 1], row 0 at the top
};

class DisplayEncoder {
 public:
  /// Compiles nothing yet: each program on first use.
  DisplayEncoder() = default;

  /// `radiance` (a 2D texture, e.g. rgba32f from Renderer::render_to_texture)
  /// through `stage` into `display` (rgba8 or rgba16, the same size). Throws
  /// std::invalid_argument for other formats or sizes, a fade or black level
  /// out of range, a gamma outside [kMinDisplayGamma, kMaxDisplayGamma] or a
  /// blend mask of another size.
  void encode(const gl::Texture& radiance, const OutputStage& stage, gl::Texture& display);
  /// The same for one band of a frame still in the renderer's output buffer
  /// (a GpuBandSink of Renderer::render_on_gpu): draws the band's rows of
  /// `display` (rgba8 or rgba16 of the frame's size). The steady live frame:
  /// no radiance texture written or read. Equal to encode() of the same frame.
  void encode_band(const GpuBand& band, const OutputStage& stage, gl::Texture& display);
  /// The thumbnail of what `display` would show: each pixel the mean of the
  /// display-linear values (clamped to [0, 1], NaN as 0) of the frame pixels it
  /// covers (cluster/node/thumbnail.h), reduced on the GPU; edge_px in
  /// [1, kMaxThumbnailEdgePx]. The encoding is not applied (the caller encodes
  /// for its viewer). Reads back thumbnail_size() pixels only.
  ThumbnailMeans thumbnail(const gl::Texture& radiance, const OutputStage& stage, int edge_px);

  /// Queues encode_band's first draw for `stage` into a texture of
  /// `display`'s format on `warmup`'s thread (render/gl/first_dispatch_warmup.h),
  /// with stand-ins shaped as the textures encode_band binds: where llvmpipe
  /// generates the program's machine code at its first draw, a first frame's
  /// display pass then loads it from Mesa's cache instead. Builds the program now.
  void warm_band(gl::FirstDispatchWarmup& warmup, const OutputStage& stage, const gl::Texture& display);
  /// The same for encode()'s program, reading `radiance`.
  void warm_encode(gl::FirstDispatchWarmup& warmup, const gl::Texture& radiance, const OutputStage& stage,
                   const gl::Texture& display);

 private:
  /// The textures the display pass binds for `stage`, by unit: one for every
  /// sampler display_transform.glsl declares — the stage's blend mask and
  /// colour LUTs, and a 1 × 1 texture of the sampler's kind where the stage
  /// has none — so that what llvmpipe keys the program's machine code by never
  /// depends on what another pass left bound to those units.
  std::vector<std::pair<unsigned, const gl::Texture*>> stage_textures(const OutputStage& stage);
  /// `stage_textures`' shapes, for a warm-up.
  gl::DispatchShapes stage_shapes(const OutputStage& stage);
  /// Sets display_transform.glsl's uniforms and binds stage_textures (the mask of `width` × `height`).
  void set_stage(const gl::ShaderProgram& program, int width, int height, const OutputStage& stage);
  /// display_encode.frag's program reading a band (FROM_BAND) or a radiance
  /// texture, with the stage's colour profile compiled in or not
  /// (COLOUR_PROFILE); built on first use.
  gl::ShaderProgram& encode_program(bool from_band, const OutputStage& stage);
  /// Draws `program` over rows [first_row, first_row + rows) of `display`.
  void draw_rows(const gl::ShaderProgram& program, gl::Texture& display, int first_row, int rows);

  std::array<gl::ShaderProgram, 4>
      encode_programs_;       // present.vert + display_encode.frag, [2·FROM_BAND + COLOUR_PROFILE]
  gl::TextureRowsDraw rows_;  // the display texture's rows as the framebuffer
  gl::ShaderProgram thumbnail_program_;
  gl::Texture thumbnail_target_;       // rgba32f, (re)allocated per thumbnail size
  gl::Texture unused_2d_, unused_3d_;  // bound to the samplers a stage leaves without a texture
};

}  // namespace zenith::render::display
