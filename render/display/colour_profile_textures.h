#pragma once
// An MPCDI colour profile (warp/colour_profile.h) on the GPU, for the display
// pass (render/display/display_encoder.h): its LUTs as textures, uploaded once
// per output (not per frame), and the numbers of its stages.
//
//  * a 1D LUT of N entries is an rgba32f 2D texture of min(N, kLut1dRowTexels) texels a
//    row (entry i at (i mod W, i div W)): one texture for the three channels,
//    of any size MPCDI allows (65536 entries: a 1D texture would exceed
//    GL_MAX_TEXTURE_SIZE, 16384 on llvmpipe). The shader reads the two entries
//    around x · (N − 1) with texelFetch and interpolates in float: the CPU's
//    CubeLut::apply to float rounding.
//  * a 3D LUT of N³ points is an rgba32f 3D texture with trilinear filtering,
//    sampled at half-texel-corrected coordinates (x · (N − 1) + 0.5) / N, so
//    lattice point i sits at its texel's centre and x = 0 and 1 hit the first
//    and last points exactly. The hardware's filter weights are fixed point
//    (8 fractional bits on NVIDIA), so the result is within 2^−9 · Δ of the
//    CPU's trilinear value, Δ the largest difference between neighbouring
//    lattice values: for a 17³ LUT of a matrix of row sums ≤ 1, about 4e-4 in
//    linear light — below one 8-bit code after the encode where the signal is
//    above black (docs/warp-meshes.md, "Colour profile").
// Needs a current GL 4.5 context.
#include <array>
#include <utility>

#include "render/gl/shader_program.h"
#include "render/gl/texture.h"
#include "render/shader_bindings.h"
#include "warp/colour_profile.h"

namespace zenith::render::display {

class ColourProfileTextures {
 public:
  ColourProfileTextures() = default;  ///< none: the identity
  /// Uploads the LUTs of `profile`, which it copies.
  explicit ColourProfileTextures(const warp::MpcdiColourProfile& profile);

  const warp::MpcdiColourProfile& profile() const { return profile_; }
  bool empty() const { return !present_; }

  /// Sets the colour uniforms of display_transform.glsl on `program` (one
  /// compiled with COLOUR_PROFILE 1); nothing without a profile.
  void set_uniforms(const gl::ShaderProgram& program) const;
  /// The LUT textures by the unit display_transform.glsl reads each from;
  /// null where the profile has no such LUT.
  std::array<std::pair<unsigned, const gl::Texture*>, 5> lut_textures() const;

 private:
  warp::MpcdiColourProfile profile_;
  bool present_ = false;
  gl::Texture decode_1d_, correct_1d_, correct_3d_, encode_1d_, encode_3d_;
};

/// The texture of a 1D LUT (layout above).
gl::Texture lut_1d_texture(const warp::CubeLut& lut);
/// The 3D texture of a 3D LUT (red along x, green y, blue z), trilinear.
gl::Texture lut_3d_texture(const warp::CubeLut& lut);

}  // namespace zenith::render::display
