// One atmosphere along one pixel's ray, for one group of 4 wavelengths (paper
// section 5.2, Algorithm 1): shared by the G-buffer path's atmosphere pass
// (atmosphere_pass.comp), the one-pass tiles of a single atmosphere
// (atmosphere_tile.comp) and the sky-view table (sky_view.comp).
//
// Segment of the ray inside the shell, from the entry point x0 (the camera
// itself when it is inside) to the exit or to the body hit at y:
//   sky:               S = S(x0)                     T = T(x0 → top)
//   other body inside: S = S(x0) − T(x0,y) S(y)      T = T(x0, y)   (aerial perspective)
//   own ground:        S = S(x0) + T(x0,y) L_g       T = 0
// with L_g = ρ/π (E_sun T_sun(y) V + E_sky(y)) the Lambertian ground lit by the
// direct sun (partly below the horizon near sunset, eclipsed by other bodies:
// V) and the sky irradiance table. S(r, μ, μs, ν) = R(…) P_R(ν) + M(…) P_M(ν)
// + multiple(…), tables per unit solar irradiance (times E_sun by the caller).
//
// Include after atmosphere_common.glsl and frame.glsl. Defines:
//   MULTIPLE_SCATTERING  0 drops the multiple-scattering table (single only)
//   ECLIPSES             0 drops the shadows of other bodies on the ground
//   TILE_GROUND, TILE_OTHERS  what the rays can meet (atmosphere_tile.comp):
//                        the cases they cannot meet are left out; both
//                        default to 2, every case
//   ECLIPSE_SKY          1: the Moon's shadow on the air (a solar eclipse):
//                        the includer defines eclipse_shares() and
//                        eclipse_direct_light() (atmosphere_tile.comp, from the
//                        frame's eclipse-sky table): S's smooth and Mie parts
//                        times the shares the shadow leaves along the ray, the
//                        ground's direct sun times V and its skylight times
//                        the share left where the ray ends
#ifndef TILE_GROUND
#define TILE_GROUND 2
#endif
#ifndef TILE_OTHERS
#define TILE_OTHERS 2
#endif
#ifndef ECLIPSE_SKY
#define ECLIPSE_SKY 0
#endif

#if ECLIPSE_SKY
/// What the Moon's shadow leaves of the light along `ray` from the camera (to
/// the ground where `ground`): of the smooth part A, of the single Mie part M,
/// and of the skylight on the ground where the ray ends.
struct EclipseShares {
  vec4 smooth_part, mie, skylight;
};
EclipseShares eclipse_shares(vec3 ray, bool ground);
/// V: the share of the sun's direct light the Moon leaves at `point` (camera-relative) on the ground.
vec4 eclipse_direct_light(vec3 point);
#endif

layout(binding = SINGLE_RAYLEIGH_UNIT) uniform sampler3D single_rayleigh_texture;
layout(binding = SINGLE_MIE_UNIT) uniform sampler3D single_mie_texture;
layout(binding = MULTIPLE_UNIT) uniform sampler3D multiple_texture;
layout(binding = IRRADIANCE_UNIT) uniform sampler2D irradiance_texture;

uniform int planet;              // index of the body this atmosphere surrounds (its data: the_body, frame.glsl)
uniform float camera_top_power;  // |c|² − RT² [m²], in double on the CPU

/// S split by smoothness in direction: S = smooth + mie · P_M(ν). The single
/// Mie term without its phase, whose forward peak no coarse table could hold.
struct Inscatter {
  real4 smooth_part;  // Rayleigh (phase applied) and orders ≥ 2
  real4 mie;          // single Mie, phase not applied
};

/// A final 4D table at `uv`: sample_scattering_table_geometric_mu_s
/// (atmosphere_common.glsl), geometric in μs between the two nearest μs texel
/// columns (through twilight S falls exponentially with the sun's depression;
/// lookup_tables.h). With USE_FP64 the CPU's interpolation done by hand from
/// texel fetches, in double; otherwise the texture unit's own filtering,
/// bilinear in (μ, r) at each column's texel centre, four reads (two μs columns
/// in each of the two ν slices; the tables are GL_LINEAR, clamped to the edge).
/// The slice coordinate (ν index + u_μs) / NU on a column's centre reads no
/// neighbouring column and no neighbouring slice. A CPU rasterizer runs the hand
/// filter's address and weight arithmetic per texel; its own filter is several
/// times cheaper (docs/rendering-performance.md).
real4 sample_table_4d(sampler3D table, ScatteringUV uv) {
#if USE_FP64
  return sample_scattering_table_geometric_mu_s(table, uv);
#else
  const float x_nu = uv.u_nu * float(SCATTERING_NU - 1);
  const float nu_floor = min(floor(x_nu), float(SCATTERING_NU - 1));
  const float t = x_nu - nu_floor;
  const float nu_ceil = min(nu_floor + 1.0, float(SCATTERING_NU - 1));
  const MuSColumns c = mu_s_columns(uv.u_mu_s);
  const vec4 a = texture(table, vec3((nu_floor + c.u_a) / float(SCATTERING_NU), uv.u_mu, uv.u_r)) * (1.0 - t) +
                 texture(table, vec3((nu_ceil + c.u_a) / float(SCATTERING_NU), uv.u_mu, uv.u_r)) * t;
  const vec4 b = texture(table, vec3((nu_floor + c.u_b) / float(SCATTERING_NU), uv.u_mu, uv.u_r)) * (1.0 - t) +
                 texture(table, vec3((nu_ceil + c.u_b) / float(SCATTERING_NU), uv.u_mu, uv.u_r)) * t;
  return geometric_blend(a, b, c.t);
#endif
}

Inscatter inscatter(real r, real mu, real mu_s, real nu, bool hits_ground) {
  const ScatteringUV single = scattering_uvwz(r, mu, mu_s, nu, hits_ground, ANGLE_MAPPING_DISTANCE);
  Inscatter s;
  s.smooth_part = sample_table_4d(single_rayleigh_texture, single) * rayleigh_phase(nu);
#if MULTIPLE_SCATTERING
  s.smooth_part +=
      sample_table_4d(multiple_texture, scattering_uvwz(r, mu, mu_s, nu, hits_ground, ANGLE_MAPPING_BLENDED));
#endif
#if HAS_MIE
  s.mie = sample_table_4d(single_mie_texture, single);
#else
  s.mie = real4(0);
#endif
  return s;
}

/// S(r, μ, μs, ν) per unit solar irradiance, phase functions applied.
real4 scattering(real r, real mu, real mu_s, real nu, bool hits_ground) {
  const Inscatter s = inscatter(r, mu, mu_s, nu, hits_ground);
#if HAS_MIE
  return s.smooth_part + s.mie * model_mie_phase(nu);
#else
  return s.smooth_part;
#endif
}

/// Direct sun on a horizontal surface at radius r, per unit solar irradiance:
/// T_sun · μs · (fraction of the disc above the horizon). The fraction is the
/// area of the disc's part above the horizon line (a circular segment), so the
/// light fades over the ~0.5° of a sunset instead of switching off.
real4 direct_irradiance(real r, real mu_s) {
  const float mu_horizon = -sqrt(max(0.0, 1.0 - float(RB / r) * float(RB / r)));
  const float elevation = asin(clamp(float(mu_s), -1.0, 1.0)) - asin(mu_horizon);
  const float x = clamp(elevation / max(sun_angular_radius, 1e-6), -1.0, 1.0);
  const float fraction = (acos(-x) + x * sqrt(1.0 - x * x)) / PI_F;
  if (fraction <= 0.0 || mu_s <= real(0)) return real4(0);
  return transmittance_to_top(r, max(mu_s, real(mu_horizon))) * real(fraction) * mu_s;
}

/// The sky's irradiance on the ground where the sun's cosine is μs, per unit solar irradiance.
real4 sky_irradiance(real mu_s) {
  const real2 uv = irradiance_uv(RB, mu_s);
  return sample_table_2d(irradiance_texture, IRRADIANCE_MU_S, IRRADIANCE_R, uv.x, uv.y);
}

/// The ground's reflected light where the ray meets this planet at distance t,
/// per unit solar irradiance: L_g = ρ/π (E_sun T_sun(y) V + E_sky(y)), in an
/// eclipse with V the Moon's too and E_sky times the share `skylight_share` left.
real4 ground_radiance(vec3 ray, float t, real4 rho, real4 skylight_share) {
  const vec3 n = body_normal(the_body, ray, t);
  const real mu_s_ground = real(dot(n, sun_direction));
  real4 visibility = real4(sunlight_left(ray * t, planet));
#if ECLIPSE_SKY
  visibility *= real4(eclipse_direct_light(ray * t));
#endif
  return rho / PI * (direct_irradiance(RB, mu_s_ground) * visibility + sky_irradiance(mu_s_ground) * skylight_share);
}

/// This atmosphere's segment of `ray` (the 4D tables at the entry point):
/// in-scattered radiance S and transmittance T per unit solar irradiance. The
/// ray meets body `hit_body` at `hit_distance` (−1: no body); `rho` is the
/// ground's reflectance there when it is this planet. False where the shell
/// adds nothing (missed, behind the camera, hidden by a body in front of it):
/// then S = 0 and T = 1.
bool atmosphere_segment(vec3 ray, float hit_distance, int hit_body, real4 rho, out real4 radiance,
                        out real4 transmittance_segment) {
  radiance = real4(0);
  transmittance_segment = real4(1);
  const bool hits_body = hit_body >= 0;
  const bool own_ground = hits_body && hit_body == planet;
  const real nu = real(dot(ray, sun_direction));
  // The planet-centred frame: the camera at distance r along `up`.
  const vec3 up = -the_body.centre.xyz;
  const float r_camera = the_body.centre.w;
  const vec3 c = body_centre(the_body);
  float q, disc;
  if (!sphere_chord(ray, the_body.centre.xyz, r_camera, float(RT), camera_top_power, q, disc)) return false;
  const float half_chord = sqrt(disc);
  // Entry (0 inside the shell) and exit distances along the ray.
  const bool inside = camera_top_power <= 0.0;
  const float d_exit = q + half_chord;
  if (d_exit <= 0.0) return false;  // the shell is behind the camera
  const float d_entry = inside ? 0.0 : camera_top_power / (q + half_chord);
  if (hits_body && hit_distance <= d_entry) return false;  // a body in front of the shell hides it

  // The entry point x0: r, μ, μs there (the camera's own values when inside).
  real r, mu, mu_s;
  if (inside) {
    r = real(r_camera);
    mu = real(dot(up, ray));
    mu_s = real(dot(up, sun_direction));
  } else {
    const vec3 x0 = ray * d_entry - c;
    r = RT;
    mu = real(-half_chord / float(RT));  // entering: the ray is half a chord before its closest approach
    mu_s = clamp(real(dot(x0, sun_direction) / float(RT)), real(-1), real(1));
  }
  r = clamp(r, RB, max(RT, r));
  mu = clamp_cosine(mu);

  // The ray (continued) ends on the ground: decided by the hit for this
  // planet's own ground, so the table halves meet exactly where the ground's edge is drawn.
#if TILE_OTHERS == 2
  const bool continues_to_ground = own_ground || (hits_body && ray_hits_ground(r, mu));
#else
  const bool continues_to_ground = own_ground;
#endif
#if ECLIPSE_SKY
  const EclipseShares shares = eclipse_shares(ray, continues_to_ground);
  const Inscatter s = inscatter(r, mu, mu_s, nu, continues_to_ground);
  radiance = s.smooth_part * real4(shares.smooth_part);
#if HAS_MIE
  radiance += s.mie * real4(shares.mie) * model_mie_phase(nu);
#endif
  const real4 skylight_share = real4(shares.skylight);
#else
  radiance = scattering(r, mu, mu_s, nu, continues_to_ground);
  const real4 skylight_share = real4(1);
#endif

  // What the segment ends on; a case these rays cannot meet is left out of
  // the program (atmosphere_tile.comp), as a CPU rasterizer would run it anyway.
#if TILE_GROUND != 0
  if (own_ground) {
    const real d = real(hit_distance - d_entry);
    const real4 t = transmittance(r, mu, d, true);
    radiance += t * ground_radiance(ray, hit_distance, rho, skylight_share);
    transmittance_segment = real4(0);
  }
#endif
#if TILE_OTHERS == 2
  if (!own_ground && hits_body && hit_distance < d_exit) {
    // Another body inside the shell: aerial perspective S(x0) − T(x0, y) S(y).
    const real d = real(hit_distance - d_entry);
    transmittance_segment = transmittance(r, mu, d, continues_to_ground);
    const real r_y = clamp(sqrt(d * d + real(2) * r * mu * d + r * r), RB, RT);
    const real mu_y = clamp_cosine((r * mu + d) / r_y);
    const real mu_s_y = clamp_cosine((r * mu_s + d * nu) / r_y);
#if ECLIPSE_SKY
    // The shares are the whole ray's: the part beyond y is taken away with them.
    const Inscatter s_y = inscatter(r_y, mu_y, mu_s_y, nu, continues_to_ground);
    real4 beyond = s_y.smooth_part * real4(shares.smooth_part);
#if HAS_MIE
    beyond += s_y.mie * real4(shares.mie) * model_mie_phase(nu);
#endif
#else
    const real4 beyond = scattering(r_y, mu_y, mu_s_y, nu, continues_to_ground);
#endif
    radiance = max(radiance - transmittance_segment * beyond, real4(0));
  }
  const bool to_top = !own_ground && !(hits_body && hit_distance < d_exit);
#else
  const bool to_top = !own_ground;
#endif
#if TILE_GROUND != 1
  if (to_top) transmittance_segment = transmittance_to_top(r, mu);
#endif
  return true;
}
