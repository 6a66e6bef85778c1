#version 450
// Presentation of a finished frame (render/window/frame_presenter.h): the
// frame's linear sRGB × exposure, tone mapped and sRGB encoded here, so the
// bytes on screen equal image::display_byte (render/image/tone_mapping.h, the
// PNG writer's mapping) within 1. The target must not be an sRGB framebuffer
// (GL_FRAMEBUFFER_SRGB is disabled while drawing): the encoding is explicit so
// the result does not depend on what the window system's visual offers.
// Keep the operators in step with tone_mapping.cpp.

in vec2 frame_uv;
layout(location = 0) out vec4 colour;

// The frame as uploaded: row 0 of the data (the top of the image) at t = 0,
// i.e. upside down for GL; flipped when sampling below.
layout(binding = PRESENT_FRAME_UNIT) uniform sampler2D frame;
// image::ToneMapping: 0 exponential (1 − exp(−x), Costa et al.), 1 clamp (min(x, 1)).
uniform int tone_mapping;

/// The tone mapping operator for x ≥ 0; negative and NaN give 0, +∞ gives 1.
float tone_map(float x) {
  if (isnan(x) || x <= 0.0) return 0.0;
  if (tone_mapping == 1) return min(x, 1.0);
  // 1 − exp(−x) cancels for small x; its series keeps the relative precision
  // there (as expm1 does on the CPU). The cut-over error is below 1e-10.
  if (x < 1e-3) return x * (1.0 - x * (0.5 - x * (1.0 / 6.0)));
  return 1.0 - exp(-x);
}

/// IEC 61966-2-1 sRGB encoding of a linear value, clamped to [0, 1].
float srgb_encode(float linear) {
  if (!(linear > 0.0)) return 0.0;
  if (linear >= 1.0) return 1.0;
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

void main() {
  const vec3 x = texture(frame, vec2(frame_uv.x, 1.0 - frame_uv.y)).rgb;
  colour = vec4(srgb_encode(tone_map(x.r)), srgb_encode(tone_map(x.g)), srgb_encode(tone_map(x.b)), 1.0);
}
