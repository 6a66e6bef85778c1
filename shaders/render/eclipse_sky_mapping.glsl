// Texel coordinates of the eclipse-sky table (render/frame/eclipse_sky_table.h):
// the share of the sky's light the Moon's shadow leaves, by direction from a
// camera inside an atmosphere. The shadow breaks the sky's symmetry about the
// sun's vertical plane, so the azimuth runs all the way round: φ from the
// sun's vertical plane toward `w` = up × (the sun's horizontal direction),
// in (−π, π], texel-centred at both ends (the same direction, the same
// value). The zenith angle is the sky-view table's (sky_view_mapping.glsl):
// two halves, each a whole layer, crowded toward the horizon θh:
//   sky    x = 1 − √(1 − (θ − θ0)/(θh − θ0))     ground x = √((θ − θh) / (π − θh))
//   φ      x = (φ + π) / 2π
// θ0 is 0 for a camera inside the shell. From outside it (orbit) only the
// directions within the shell's disc meet any air: θ0 = π − asin(RT/r), the
// sky half is then the limb's ring (rays that pass the ground) and the ground
// half the planet's disc, evenly in θ there (ground x = (θ − θh) / (π − θh)):
// seen from above, the umbra lies anywhere on the disc, and the crowding
// toward θh left 4.5° texels at the nadir from 400 km, where the air's light
// falls a thousandfold across the umbra's 14° (measured: worst 27 % → 7.5 %
// against the CPU's sum, RendererEclipse.TheAirOverTheUmbraSeenFromOrbit…).
// and x ∈ [0, 1] maps to u = 0.5/n + x (1 − 1/n) over n texels.
// ECLIPSE_SKY_AZIMUTH_TEXELS, ECLIPSE_SKY_ZENITH_TEXELS (per half) and
// ECLIPSE_SKY_LAYERS (per group: the sky half's A and M shares, then the
// ground half's and its skylight's share left on the ground) are defined by
// the C++ side (EclipseSkyTable::defines()).
#define ECLIPSE_SKY_SKY 0
#define ECLIPSE_SKY_GROUND 2

/// Texture coordinates of zenith angle θ and azimuth φ in the sky (ground = false) or ground half.
vec2 eclipse_sky_uv(float theta, float phi, float theta_top, float theta_horizon, bool ground) {
  const float x_phi = clamp((phi + PI_F) / (2.0 * PI_F), 0.0, 1.0);
  const float x_ground = clamp((theta - theta_horizon) / (PI_F - theta_horizon), 0.0, 1.0);
  const float x_theta = ground ? (theta_top > 0.0 ? x_ground : sqrt(x_ground))
                               : 1.0 - sqrt(clamp(1.0 - (theta - theta_top) / (theta_horizon - theta_top), 0.0, 1.0));
  const vec2 n = vec2(ECLIPSE_SKY_AZIMUTH_TEXELS, ECLIPSE_SKY_ZENITH_TEXELS);
  return 0.5 / n + vec2(x_phi, x_theta) * (1.0 - 1.0 / n);
}

/// The inverse, at texel (i, j): zenith angle and azimuth.
void eclipse_sky_direction(ivec2 texel, float theta_top, float theta_horizon, bool ground, out float theta,
                           out float phi) {
  const float x_phi = float(texel.x) / float(ECLIPSE_SKY_AZIMUTH_TEXELS - 1);
  const float x_theta = float(texel.y) / float(ECLIPSE_SKY_ZENITH_TEXELS - 1);
  phi = -PI_F + 2.0 * PI_F * x_phi;
  theta = ground ? theta_horizon + (PI_F - theta_horizon) * (theta_top > 0.0 ? x_theta : x_theta * x_theta)
                 : theta_top + (theta_horizon - theta_top) * (1.0 - (1.0 - x_theta) * (1.0 - x_theta));
}
