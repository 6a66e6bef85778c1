// What a projector shows of a rendered frame (render/display/display_encoder.h),
// per pixel, in this order:
//
//   P  = T(x)                       tone mapping of the exposed radiance x
//                                   (image/tone_mapping.h: 1 − exp(−x), or min(x, 1))
//   P  = mix(P, fade_colour, f)     the fade toward a display-linear colour (level f
//                                   in [0, 1]; 0: none), before the output stage so
//                                   that a fade blends across overlaps like the picture
//   P' = P · α · (1 − β) + β        the output stage: blend mask α, black level β
//                                   (warp/blending.h; only where the output has one;
//                                   β per pixel from the mask's second channel where
//                                   the output has a black-level map, an MPCDI beta map)
//   V  = E(P')                      the display encoding: sRGB or P'^(1/γ)
//                                   (image/display_encoding.h)
//
// With an MPCDI colour profile (warp/colour_profile.h, VESA MPCDI v2.0 §2.5)
// the output stage moves into the profile, as a media player applies it to
// the signal it would send (docs/warp-meshes.md, "Colour profile"):
//
//   S  = E(P)                       zenith's signal, without α and β
//   L  = decode(S)                  (S)^γ_d or the decode 1D LUT (§2.5.1.1)
//   L  = correct(L)                 1D LUT then the primaries matrix, or the 3D LUT (§2.5.1.2)
//   L' = α · L · (1 − β) + β        processPixel's local correction (§2.5.2)
//   V  = encode(L')                 L'^(1/γ_e), the encode 1D or 3D LUT, or L' (none) (§2.5.1.3)
//
// The CPU path is image::tone_map, warp::apply_blend and image::display_encode
// (cluster/node/output_writer.h's display_image), and MpcdiColourProfile::process
// with a profile: keep the operators in step.

// image::ToneMapping: 0 exponential, 1 clamp.
uniform int tone_mapping;
/// Whether the output stage applies (a blend mask or a black level).
uniform bool output_stage;
/// Whether blend_mask holds α (else α = 1).
uniform bool has_blend_mask;
/// Whether blend_mask's second channel holds β (an rg32f mask; else β = black_level).
uniform bool has_black_level_map;
/// α (r) and, with has_black_level_map, β (g) per pixel of the frame, row 0 at the top (as the frame).
layout(binding = BLEND_MASK_UNIT) uniform sampler2D blend_mask;
uniform float black_level;  // β in [0, 0.5] without a black-level map
uniform float fade_level;   // f in [0, 1]
uniform vec3 fade_colour;   // display-linear RGB in [0, 1]
// image::DisplayEncoding: 0 sRGB, 1 gamma (V = L^inverse_gamma).
uniform int transfer;
uniform float inverse_gamma;

// The MPCDI colour profile (render/display/colour_profile_textures.h):
// COLOUR_PROFILE 1 compiles its stages in, 0 leaves them out — a display pass
// without a profile is a program of its own, without the LUT reads (on a CPU
// rasterizer they were most of its machine code, generated at its first draw).
#if COLOUR_PROFILE
uniform int decode_type;   // 0 gamma, 1 lut1d
uniform float decode_gamma;
uniform int correct_type;  // 0 none, 1 lut1d-primary, 2 lut3d
uniform bool has_correct_lut_1d;
uniform mat3 primaries;    // row i: output channel i's weights of (R, G, B)
uniform int encode_type;   // 0 none, 1 gamma, 2 lut1d, 3 lut3d
uniform float encode_inverse_gamma;
uniform int decode_lut_size, correct_lut_size, encode_lut_size;
// 1D LUTs: entry i at texel (i mod LUT_1D_ROW_TEXELS, i div LUT_1D_ROW_TEXELS).
layout(binding = DECODE_LUT_UNIT) uniform sampler2D decode_lut;
layout(binding = CORRECT_LUT_1D_UNIT) uniform sampler2D correct_lut_1d;
layout(binding = ENCODE_LUT_1D_UNIT) uniform sampler2D encode_lut_1d;
// 3D LUTs: red along x, trilinear filtering.
layout(binding = CORRECT_LUT_3D_UNIT) uniform sampler3D correct_lut_3d;
layout(binding = ENCODE_LUT_3D_UNIT) uniform sampler3D encode_lut_3d;
#endif  // COLOUR_PROFILE

/// The tone mapping operator for x ≥ 0; negative and NaN give 0, +∞ gives 1.
float tone_map(float x) {
  if (isnan(x) || x <= 0.0) return 0.0;
  if (tone_mapping == 1) return min(x, 1.0);
  // 1 − exp(−x) cancels for small x; its series keeps the relative precision
  // there (as expm1 does on the CPU). The cut-over error is below 1e-10.
  if (x < 1e-3) return x * (1.0 - x * (0.5 - x * (1.0 / 6.0)));
  return 1.0 - exp(-x);
}

/// P: the tone mapped, faded display-linear value of exposed radiance x.
vec3 content_linear(vec3 x) {
  vec3 v = vec3(tone_map(x.r), tone_map(x.g), tone_map(x.b));
  if (fade_level > 0.0) v = mix(v, fade_colour, fade_level);
  return v;
}

/// α of pixel p: the blend mask's, 1 without one or without the output stage.
float stage_alpha(ivec2 p) { return output_stage && has_blend_mask ? texelFetch(blend_mask, p, 0).r : 1.0; }
/// β of pixel p: the black-level map's, else the black level; 0 without the output stage.
float stage_black_level(ivec2 p) {
  if (!output_stage) return 0.0;
  return has_blend_mask && has_black_level_map ? texelFetch(blend_mask, p, 0).g : black_level;
}

/// P' of pixel p (frame coordinates, row 0 at the top) for exposed radiance x.
vec3 display_linear(ivec2 p, vec3 x) {
  vec3 v = content_linear(x);
  if (output_stage) {
    const float beta = stage_black_level(p);
    v = v * (stage_alpha(p) * (1.0 - beta)) + beta;
  }
  return v;
}

/// E: the display encoding of a display-linear value, clamped to [0, 1] (NaN → 0).
float display_encode(float linear) {
  if (!(linear > 0.0)) return 0.0;
  if (linear >= 1.0) return 1.0;
  if (transfer == 1) return pow(linear, inverse_gamma);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

#if COLOUR_PROFILE
/// Entry i of a 1D LUT's texture.
vec3 lut_entry(sampler2D lut, int i) {
  return texelFetch(lut, ivec2(i % LUT_1D_ROW_TEXELS, i / LUT_1D_ROW_TEXELS), 0).rgb;
}

/// A 1D LUT of `size` entries on each channel of x (clamped to [0, 1]): the
/// entries around x · (size − 1), interpolated linearly (warp::CubeLut::apply).
vec3 apply_lut_1d(sampler2D lut, int size, vec3 x) {
  const vec3 position = clamp(x, 0.0, 1.0) * float(size - 1);
  const ivec3 i = min(ivec3(position), ivec3(size - 2));
  const vec3 t = position - vec3(i);
  const vec3 r = mix(lut_entry(lut, i.r), lut_entry(lut, i.r + 1), t.r);
  const vec3 g = mix(lut_entry(lut, i.g), lut_entry(lut, i.g + 1), t.g);
  const vec3 b = mix(lut_entry(lut, i.b), lut_entry(lut, i.b + 1), t.b);
  return vec3(r.r, g.g, b.b);
}

/// A 3D LUT of size³ points at x (clamped to [0, 1]), trilinear by the
/// texture unit: lattice point i at the centre of texel i, (i + 0.5) / size.
vec3 apply_lut_3d(sampler3D lut, int size, vec3 x) {
  const float n = float(size);
  return texture(lut, (clamp(x, 0.0, 1.0) * (n - 1.0) + 0.5) / n).rgb;
}

/// processPixel (VESA MPCDI v2.0 §2.5.2) of zenith's signal s (each in [0, 1])
/// with blend weight alpha and black level beta; the result in [0, 1]
/// (warp::MpcdiColourProfile::process).
vec3 mpcdi_process(vec3 s, float alpha, float beta) {
  // Stage 1, decode: Linear = (Encoded / Scale)^gamma (§2.5.1.2.4), or the 1D LUT.
  vec3 l = decode_type == 1 ? apply_lut_1d(decode_lut, decode_lut_size, s) : pow(s, vec3(decode_gamma));
  // Stage 2, correct: the 1D LUT then the primaries, or the 3D LUT; kept in [0, 1].
  if (correct_type == 1) {
    if (has_correct_lut_1d) l = apply_lut_1d(correct_lut_1d, correct_lut_size, l);
    l = primaries * l;
  } else if (correct_type == 2) {
    l = apply_lut_3d(correct_lut_3d, correct_lut_size, l);
  }
  l = clamp(l, 0.0, 1.0);
  l = l * (alpha * (1.0 - beta)) + beta;
  // Stage 3, encode: Encoded = Scale · Linear^(1/gamma), a LUT, or none.
  if (encode_type == 1) l = pow(l, vec3(encode_inverse_gamma));
  if (encode_type == 2) l = apply_lut_1d(encode_lut_1d, encode_lut_size, l);
  if (encode_type == 3) l = apply_lut_3d(encode_lut_3d, encode_lut_size, l);
  return clamp(l, 0.0, 1.0);
}
#endif  // COLOUR_PROFILE

/// V: what pixel p sends the display for exposed radiance x, each channel in
/// [0, 1] (times code_max: the code): E(P') without a colour profile, the
/// profile's processPixel of E(P) with one.
vec3 display_signal(ivec2 p, vec3 x) {
#if COLOUR_PROFILE
  const vec3 v = content_linear(x);
  const vec3 s = vec3(display_encode(v.r), display_encode(v.g), display_encode(v.b));
  return mpcdi_process(s, stage_alpha(p), stage_black_level(p));
#else
  const vec3 v = display_linear(p, x);
  return vec3(display_encode(v.r), display_encode(v.g), display_encode(v.b));
#endif
}
