// The Moon's shadow on the air in a solar eclipse, read on the GPU: what
// astro/moon_shadow.cpp computes on the CPU (MoonShadow::place, direct_light,
// scattered_light, skylight_left), from the same tables uploaded by
// render/frame/eclipse_sky_table.cpp, for one group of 4 wavelengths.
//
// Points are given camera-relative (world-oriented, metres) with their
// altitude: the shadow's frame (s toward the Sun, e1 from the axis toward the
// planet's centre, e2 = s × e1) is set from double on the CPU through the
// camera's own offset from the axis and distance along it, so nothing here
// subtracts large numbers:
//   q(p) = q_c + (p·e1, p·e2)          the offset from the axis
//   D(p) = D_c − p·s                   the distance to the Moon's centre along the axis
//   x(p) = atan(|q|, D) − (asin(R_m / √(D² + |q|²)) − r_m0)   the Moon's limb from the Sun's centre
//
// V(p) = profile(x), linear over PROFILE_SAMPLES texels as MoonShadow::profile_at;
// V̄(p, v) from the first 57 numbers per node (trilinear in the node coordinates
// t_u = sign(u)√|u|, t_v = √|v|, the altitude), each scatterer's phase
// function to its Legendre terms l ≤ 4 past its forward share f (delta-M),
// and for the gas the eclipsed light's polarization P (astro/moon_shadow.h):
//   ∫ P(ω·v) L dω ∝ (1 − f) max(0, a + 3 k₁ (m·v) + 5 k₂ (3 vᵀMv − a)/2
//                                  + 4π Σ_{l=3,4} k_l Σ_m Y_lm(v) c_lm + (3Δ/4) vᵀPv)
//                   + f L(v),
//   L(v) the light arriving from straight behind: the view ray's own beyond p
//   (its share left, from eclipse_sky.comp, times the daylight's terms l ≤ 2),
//   or where not known max(0, a + 3 (m·v) + 5 (3 vᵀMv − a)/2),
//   c_lm the light's real spherical harmonics' coefficients (astro::kShadowHigherMoments),
//   V̄ = Σ_scatterers β (eclipsed) / Σ_scatterers β (daylight, scalar: the tables' own),
// eased to 1 between one and two penumbra radii from the axis.
//
// Include after atmosphere_common.glsl. Defines: SHADOW_PROFILE_SAMPLES,
// SHADOW_FIELD_ACROSS, SHADOW_FIELD_SIDE, SHADOW_FIELD_LEVELS,
// SHADOW_FIELD_VALUES (57), SHADOW_FIELD_ALTITUDES (a float[] literal, metres).

/// V per texel for the group's wavelengths (width PROFILE_SAMPLES, height 1).
layout(binding = SHADOW_PROFILE_UNIT) uniform sampler2D shadow_profile;
/// V̄'s numbers: x across e1, y along |e2|, z = value · LEVELS + altitude level.
layout(binding = SHADOW_FIELD_UNIT) uniform sampler3D shadow_field;

uniform vec3 shadow_sun;                 // s
uniform vec3 shadow_e1, shadow_e2;       // e1, e2
uniform vec2 shadow_camera_across;       // q_c: the camera's offset from the axis along e1, e2 [m]
uniform float shadow_camera_along;       // D_c: the Moon's centre ahead of the camera along s [m]
uniform float shadow_moon_radius;        // R_m [m]
uniform float shadow_moon_radius_0;      // r_m0: the Moon's angular radius the profile was made for [rad]
uniform float shadow_profile_end;        // r_s + r_m0 [rad]: beyond it V = 1
uniform float shadow_field_end;          // the field's half width [m]: the penumbra's radius
uniform vec4 shadow_mie_k1, shadow_mie_k2;  // the aerosols' Legendre k₁ … k₄ past their forward share
uniform vec4 shadow_mie_k3, shadow_mie_k4;
uniform vec4 shadow_mie_forward;            // the aerosols' forward share f (delta-M) per wavelength
uniform float shadow_rayleigh_k1, shadow_rayleigh_k2;
uniform float shadow_rayleigh_dipole;    // 3Δ/4: the weight of the arriving light's polarization for the gas

const float kShadowAltitudes[SHADOW_FIELD_LEVELS] = SHADOW_FIELD_ALTITUDES;

/// Where a point lies relative to the shadow (MoonShadow::Place).
struct ShadowPlace {
  float limb;    // x [rad]; 1e30 where the Moon is behind the point
  vec2 across;   // q·e1, q·e2 [m]
  float altitude;
};

ShadowPlace shadow_place(vec3 offset_m, float altitude_m) {
  ShadowPlace p;
  p.across = shadow_camera_across + vec2(dot(offset_m, shadow_e1), dot(offset_m, shadow_e2));
  p.altitude = altitude_m;
  p.limb = 1e30;
  const float along = shadow_camera_along - dot(offset_m, shadow_sun);
  if (along > 0.0) {
    const float perp = length(p.across);
    const float moon_radius = asin(min(1.0, shadow_moon_radius / sqrt(along * along + perp * perp)));
    p.limb = max(0.0, atan(perp, along) - (moon_radius - shadow_moon_radius_0));
  }
  return p;
}

/// V: the share of the Sun's limb-darkened light that reaches the point directly.
vec4 shadow_direct_light(ShadowPlace p) {
  if (!(p.limb < shadow_profile_end)) return vec4(1.0);
  const float f = p.limb / shadow_profile_end * float(SHADOW_PROFILE_SAMPLES - 1);
  return texture(shadow_profile, vec2((f + 0.5) / float(SHADOW_PROFILE_SAMPLES), 0.5));
}

/// vᵀMv for a symmetric M given as xx, yy, zz, xy, xz, yz.
vec4 shadow_quadratic(vec4 M[6], vec3 v) {
  return M[0] * (v.x * v.x) + M[1] * (v.y * v.y) + M[2] * (v.z * v.z) +
         2.0 * (M[3] * (v.x * v.y) + M[4] * (v.x * v.z) + M[5] * (v.y * v.z));
}
/// The real spherical harmonics of degree 3 and 4 of the unit v: core/spherical_harmonics.h's polynomials, in
/// its order (Y_3,−3 … Y_3,3, Y_4,−4 … Y_4,4).
void shadow_harmonics(vec3 v, out float y[16]) {
  const float x2 = v.x * v.x, y2 = v.y * v.y, z2 = v.z * v.z;
  y[0] = 0.5900435899266435 * v.y * (3.0 * x2 - y2);
  y[1] = 2.890611442640554 * v.x * v.y * v.z;
  y[2] = 0.4570457994644658 * v.y * (5.0 * z2 - 1.0);
  y[3] = 0.3731763325901154 * v.z * (5.0 * z2 - 3.0);
  y[4] = 0.4570457994644658 * v.x * (5.0 * z2 - 1.0);
  y[5] = 1.445305721320277 * v.z * (x2 - y2);
  y[6] = 0.5900435899266435 * v.x * (x2 - 3.0 * y2);
  y[7] = 2.503342941796705 * v.x * v.y * (x2 - y2);
  y[8] = 1.770130769779931 * v.y * v.z * (3.0 * x2 - y2);
  y[9] = 0.9461746957575601 * v.x * v.y * (7.0 * z2 - 1.0);
  y[10] = 0.6690465435572892 * v.y * v.z * (7.0 * z2 - 3.0);
  y[11] = 0.1057855469152043 * (35.0 * z2 * z2 - 30.0 * z2 + 3.0);
  y[12] = 0.6690465435572892 * v.x * v.z * (7.0 * z2 - 3.0);
  y[13] = 0.4730873478787800 * (x2 - y2) * (7.0 * z2 - 1.0);
  y[14] = 1.770130769779931 * v.x * v.z * (x2 - 3.0 * y2);
  y[15] = 0.6258357354491761 * (x2 * (x2 - 3.0 * y2) - y2 * (3.0 * x2 - y2));
}
/// The light's terms l = 3 and 4, (2l + 1) ∫ P_l(ω·v) L dω = 4π Σ_m Y_lm(v) c_lm, from its coefficients c (the
/// values from `first` on) and v's harmonics.
void shadow_higher(vec4 values[SHADOW_FIELD_VALUES], int first, float harmonics[16], out vec4 l3, out vec4 l4) {
  l3 = vec4(0.0);
  l4 = vec4(0.0);
  for (int n = 0; n < 7; ++n) l3 += values[first + n] * harmonics[n];
  for (int n = 7; n < 16; ++n) l4 += values[first + n] * harmonics[n];
  l3 *= 4.0 * PI_F;
  l4 *= 4.0 * PI_F;
}
/// The light arriving from straight behind to its terms l ≤ 2, a + 3 m·v + 5 (3 vᵀMv − a)/2, clipped at 0.
vec4 shadow_straight_behind(vec4 a, vec4 m[3], vec4 M[6], vec3 v) {
  return max(a + 3.0 * (m[0] * v.x + m[1] * v.y + m[2] * v.z) + 2.5 * (3.0 * shadow_quadratic(M, v) - a), 0.0);
}
/// ∫ P(ω·v) L dω (the 1/4π dropped), never negative, from a, m, M, P and the terms
/// l = 3, 4 of the light, the light `straight` arriving from straight behind, and
/// k₁ … k₄, 3Δ/4 and the forward share f of the scatterer.
vec4 phase_weighted(vec4 a, vec4 m[3], vec4 M[6], vec4 P[6], vec4 l3, vec4 l4, vec4 straight, vec3 v, vec4 k1,
                    vec4 k2, vec4 k3, vec4 k4, vec4 dipole, vec4 forward) {
  const vec4 mv = m[0] * v.x + m[1] * v.y + m[2] * v.z;
  const vec4 q = 2.5 * (3.0 * shadow_quadratic(M, v) - a);
  const vec4 spread = a + 3.0 * k1 * mv + k2 * q + k3 * l3 + k4 * l4 + dipole * shadow_quadratic(P, v);
  return (1.0 - forward) * max(spread, 0.0) + forward * straight;
}

/// V̄ for light scattered along v by two scatterers (scattering coefficients
/// β_a, β_b, Legendre k₁, k₂ each; the first's weight of the polarization, it
/// has no forward share and no terms l > 2; the second scatters all
/// polarizations alike, its k₃, k₄ and forward share f_b): MoonShadow::share_left.
/// `behind_left`, where ≥ 0, is the share left of the light arriving from
/// straight behind (the view ray's own, beyond p); where < 0 that light is the
/// node's terms l ≤ 2.
vec4 shadow_share_left(ShadowPlace p, vec3 v, vec4 beta_a, vec4 k1_a, vec4 k2_a, vec4 dipole_a, vec4 beta_b, vec4 k1_b,
                       vec4 k2_b, vec4 k3_b, vec4 k4_b, vec4 f_b, vec4 behind_left) {
  if (p.limb >= 1e29) return vec4(1.0);
  const float reach = length(p.across) / shadow_field_end;
  if (reach >= 2.0) return vec4(1.0);
  const float fade = smoothstep(1.0, 2.0, reach);
  // Node coordinates, texel-centred: hardware trilinear filtering is the CPU's interpolation.
  const float u = clamp(p.across.x / shadow_field_end, -1.0, 1.0);
  const float fu = 0.5 * (1.0 + sign(u) * sqrt(abs(u))) * float(SHADOW_FIELD_ACROSS - 1);
  const float fv = sqrt(min(abs(p.across.y) / shadow_field_end, 1.0)) * float(SHADOW_FIELD_SIDE - 1);
  const float altitude = clamp(p.altitude, 0.0, kShadowAltitudes[SHADOW_FIELD_LEVELS - 1]);
  float level = 0.0;
  for (int l = 0; l + 1 < SHADOW_FIELD_LEVELS; ++l)
    if (altitude >= kShadowAltitudes[l])
      level = float(l) + min(1.0, (altitude - kShadowAltitudes[l]) / (kShadowAltitudes[l + 1] - kShadowAltitudes[l]));
  const vec2 xy = vec2((fu + 0.5) / float(SHADOW_FIELD_ACROSS), (fv + 0.5) / float(SHADOW_FIELD_SIDE));
  const float depth = float(SHADOW_FIELD_VALUES * SHADOW_FIELD_LEVELS);
  vec4 values[SHADOW_FIELD_VALUES];
  for (int c = 0; c < SHADOW_FIELD_VALUES; ++c)
    values[c] = texture(shadow_field, vec3(xy, (float(c * SHADOW_FIELD_LEVELS) + level + 0.5) / depth));
  // v in the basis (e1, e2, s), mirrored across the plane of the axis and e1 beyond it.
  const vec3 w = vec3(dot(v, shadow_e1), (p.across.y < 0.0 ? -1.0 : 1.0) * dot(v, shadow_e2), dot(v, shadow_sun));
  const vec4 m_e[3] = vec4[3](values[1], values[2], values[3]);
  const vec4 M_e[6] = vec4[6](values[4], values[5], values[6], values[7], values[8], values[9]);
  const vec4 m_d[3] = vec4[3](values[10], values[11], values[12]);
  const vec4 M_d[6] = vec4[6](values[13], values[14], values[15], values[16], values[17], values[18]);
  const vec4 P_e[6] = vec4[6](values[19], values[20], values[21], values[22], values[23], values[24]);
  float harmonics[16];
  shadow_harmonics(w, harmonics);
  vec4 l3_e, l4_e, l3_d, l4_d;
  shadow_higher(values, 25, harmonics, l3_e, l4_e);
  shadow_higher(values, 41, harmonics, l3_d, l4_d);
  const vec4 none = vec4(0.0);
  const vec4 behind_d = shadow_straight_behind(vec4(1.0), m_d, M_d, w);
  const vec4 behind_e = mix(shadow_straight_behind(values[0], m_e, M_e, w), behind_left * behind_d,
                            greaterThanEqual(behind_left, vec4(0.0)));
  const vec4 eclipsed =
      beta_a *
          phase_weighted(values[0], m_e, M_e, P_e, l3_e, l4_e, behind_e, w, k1_a, k2_a, none, none, dipole_a, none) +
      beta_b * phase_weighted(values[0], m_e, M_e, P_e, l3_e, l4_e, behind_e, w, k1_b, k2_b, k3_b, k4_b, none, f_b);
  const vec4 unpolarized[6] = vec4[6](none, none, none, none, none, none);
  const vec4 daylight =
      beta_a * phase_weighted(vec4(1.0), m_d, M_d, unpolarized, l3_d, l4_d, behind_d, w, k1_a, k2_a, none, none,
                              none, none) +
      beta_b * phase_weighted(vec4(1.0), m_d, M_d, unpolarized, l3_d, l4_d, behind_d, w, k1_b, k2_b, k3_b, k4_b,
                              none, f_b);
  const vec4 share = mix(vec4(1.0), clamp(eclipsed / daylight, 0.0, 1.0), greaterThan(daylight, vec4(0.0)));
  return mix(share, vec4(1.0), fade);
}

/// V̄ of the multiple scattering the air at p sends along v (the light travels along −v), with the share
/// left of the light arriving from straight behind where known (≥ 0: shadow_share_left).
vec4 shadow_scattered_light(ShadowPlace p, vec3 v, vec4 behind_left) {
  const float h = clamp(p.altitude, 0.0, kShadowAltitudes[SHADOW_FIELD_LEVELS - 1]);
  const vec4 beta_r = vec4(wavelength_field(FIELD_RAYLEIGH_SCATTERING) * rayleigh_density(real(h)));
  const vec4 beta_m = vec4(wavelength_field(FIELD_MIE_SCATTERING) * mie_density(real(h)));
  return shadow_share_left(p, v, beta_r, vec4(shadow_rayleigh_k1), vec4(shadow_rayleigh_k2),
                           vec4(shadow_rayleigh_dipole), beta_m, shadow_mie_k1, shadow_mie_k2, shadow_mie_k3,
                           shadow_mie_k4, shadow_mie_forward, behind_left);
}

/// The share of the skylight left on a horizontal surface of the ground whose
/// outward normal is `up`: max(0, n·ω) = ¼ (1 + 2 P₁ + 5/4 P₂ + …).
vec4 shadow_skylight_left(ShadowPlace p, vec3 up) {
  return shadow_share_left(p, up, vec4(1.0), vec4(2.0 / 3.0), vec4(0.25), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0),
                           vec4(0.0), vec4(0.0), vec4(0.0), vec4(-1.0));
}
