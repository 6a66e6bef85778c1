// Texel coordinates of the sky-view table (render/frame/sky_view_table.h):
// the in-scattered radiance, and the ground's lighting, seen from a camera
// inside an atmosphere, by direction, after Hillaire 2020 ("A Scalable and Production
// Ready Sky and Atmosphere Rendering Technique", section 5.3). A direction is
// its zenith angle θ (from the camera's up) and its azimuth φ from the sun's
// vertical plane (the sky is symmetric about it: ν = μ μs + √(1−μ²)√(1−μs²) cos φ).
//
// Two halves, each a whole layer so bilinear filtering never mixes them: the
// sky (θ from 0 to the geometric horizon θh) and the ground (θh to π). Which
// half a pixel reads is decided by its own ray (does it end on this planet's
// ground?), like the 4D tables' halves, so there is no line at the horizon.
// Texels crowd toward the horizon, where the light changes fastest, and
// toward the sun's azimuth:
//
//   θh     = π − asin(RB / r)                      (cos θh = −√(1 − RB²/r²))
//   sky    x = 1 − √(1 − θ/θh)                     θ = θh (1 − (1 − x)²)
//   ground x = √((θ − θh) / (π − θh))              θ = θh + (π − θh) x²
//   φ      x = √((1 − cos φ) / 2) = sin(φ/2)        cos φ = 1 − 2x²
//
// and a unit x ∈ [0, 1] maps to u = 0.5/n + x (1 − 1/n) over n texels, so the
// end values fall on texel centres (no extrapolation at the zenith, the
// horizon, the nadir, toward or away from the sun).
// Include after atmosphere_common.glsl (RB).

// SKY_VIEW_AZIMUTH_TEXELS, SKY_VIEW_ZENITH_TEXELS (per half) and SKY_VIEW_LAYERS
// (per wavelength group: the sky half's A and M, then the ground half's A, M,
// G_sun and G_sky) are defined by the C++ side (SkyViewTable::defines()).
#define SKY_VIEW_SKY 0
#define SKY_VIEW_GROUND 2


float sky_view_u(float x) { return 0.5 / float(SKY_VIEW_AZIMUTH_TEXELS) + x * (1.0 - 1.0 / float(SKY_VIEW_AZIMUTH_TEXELS)); }
float sky_view_v(float x) { return 0.5 / float(SKY_VIEW_ZENITH_TEXELS) + x * (1.0 - 1.0 / float(SKY_VIEW_ZENITH_TEXELS)); }

/// Texture coordinates (u, v) of zenith angle θ and cos φ in the sky (ground = false) or ground half.
vec2 sky_view_uv(float theta, float cos_phi, float theta_horizon, bool ground) {
  const float x_phi = sqrt(clamp(0.5 - 0.5 * cos_phi, 0.0, 1.0));
  const float x_theta = ground ? sqrt(clamp((theta - theta_horizon) / (PI_F - theta_horizon), 0.0, 1.0))
                               : 1.0 - sqrt(clamp(1.0 - theta / theta_horizon, 0.0, 1.0));
  return vec2(sky_view_u(x_phi), sky_view_v(x_theta));
}

/// The inverse, at texel (i, j): zenith angle and cos φ.
void sky_view_direction(ivec2 texel, float theta_horizon, bool ground, out float theta, out float cos_phi) {
  const float x_phi = float(texel.x) / float(SKY_VIEW_AZIMUTH_TEXELS - 1);
  const float x_theta = float(texel.y) / float(SKY_VIEW_ZENITH_TEXELS - 1);
  cos_phi = 1.0 - 2.0 * x_phi * x_phi;
  theta = ground ? theta_horizon + (PI_F - theta_horizon) * x_theta * x_theta
                 : theta_horizon * (1.0 - (1.0 - x_theta) * (1.0 - x_theta));
}
