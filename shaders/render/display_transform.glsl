// What a projector shows of a rendered frame (render/display/display_encoder.h),
// per pixel, in this order:
//
//   P  = T(x)                       tone mapping of the exposed radiance x
//                                   (image/tone_mapping.h: 1 − exp(−x), or min(x, 1))
//   P  = mix(P, fade_colour, f)     the fade toward a display-linear colour (level f
//                                   in [0, 1]; 0: none), before the output stage so
//                                   that a fade blends across overlaps like the picture
//   P' = P · α · (1 − β) + β        the output stage: blend mask α, black level β
//                                   (warp/blending.h; only where the output has one)
//   V  = E(P')                      the display encoding: sRGB or P'^(1/γ)
//                                   (image/display_encoding.h)
//
// The CPU path is image::tone_map, warp::apply_blend and image::display_encode
// (cluster/node/output_writer.h's display_image): keep the operators in step.

// image::ToneMapping: 0 exponential, 1 clamp.
uniform int tone_mapping;
/// Whether the output stage applies (a blend mask or a black level).
uniform bool output_stage;
/// Whether blend_mask holds α (else α = 1).
uniform bool has_blend_mask;
/// α per pixel of the frame, row 0 at the top (as the frame).
layout(binding = BLEND_MASK_UNIT) uniform sampler2D blend_mask;
uniform float black_level;  // β in [0, 0.5]
uniform float fade_level;   // f in [0, 1]
uniform vec3 fade_colour;   // display-linear RGB in [0, 1]
// image::DisplayEncoding: 0 sRGB, 1 gamma (V = L^inverse_gamma).
uniform int transfer;
uniform float inverse_gamma;

/// The tone mapping operator for x ≥ 0; negative and NaN give 0, +∞ gives 1.
float tone_map(float x) {
  if (isnan(x) || x <= 0.0) return 0.0;
  if (tone_mapping == 1) return min(x, 1.0);
  // 1 − exp(−x) cancels for small x; its series keeps the relative precision
  // there (as expm1 does on the CPU). The cut-over error is below 1e-10.
  if (x < 1e-3) return x * (1.0 - x * (0.5 - x * (1.0 / 6.0)));
  return 1.0 - exp(-x);
}

/// P' of pixel p (frame coordinates, row 0 at the top) for exposed radiance x.
vec3 display_linear(ivec2 p, vec3 x) {
  vec3 v = vec3(tone_map(x.r), tone_map(x.g), tone_map(x.b));
  if (fade_level > 0.0) v = mix(v, fade_colour, fade_level);
  if (output_stage) {
    const float alpha = has_blend_mask ? texelFetch(blend_mask, p, 0).r : 1.0;
    v = v * (alpha * (1.0 - black_level)) + black_level;
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
