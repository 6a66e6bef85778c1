// The lookup tables' parameterization (included by atmosphere_common.glsl,
// after physics.glsl): the shell's geometry, the mappings between (r, μ, μs, ν)
// and texture coordinates of the transmittance, irradiance and scattering
// tables, and the texel coordinates the precompute derives once
// (atmosphere/lut/parameterization.cpp).

// ------------------------------------------------------------ geometry (parameterization.cpp)

// The shell's radii (the shader model's BOTTOM_RADIUS, TOP_RADIUS: float
// literals in fp32, Fp64Constants entries in fp64, so names rather than constants).
#define RB BOTTOM_RADIUS
#define RT TOP_RADIUS

real clamp_cosine(real mu) { return clamp(mu, real(-1), real(1)); }
real safe_sqrt(real a) { return sqrt(max(a, real(0))); }
/// a² − b² as (a − b)(a + b): r − RB is exact near the ground, where r² − RB²
/// cancels (difference_of_squares, parameterization.cpp: in float, 1 m above
/// Mars' ground, r² − RB² is 6 ulp of r² and u_μ at the horizon was off by 0.2).
real difference_of_squares(real a, real b) {
  PRECISE real d = (a - b) * (a + b);
  return d;
}

/// H = √(rt² − rb²). The shared render programs (MODEL_AT_RUN_TIME) read it
/// from WavelengthData's header, computed on the CPU with these operations in
/// the shader's precision (shader_model.cpp: shell_constants), where the
/// precompute's compiler folds the literals: the same bits either way.
real horizon_distance_at_top() {
#if MODEL_AT_RUN_TIME
  return wavelength_data[0].w;
#else
  PRECISE real h = safe_sqrt(difference_of_squares(RT, RB));
  return h;
#endif
}
real horizon_distance(real r) {
  PRECISE real rho = safe_sqrt(difference_of_squares(r, RB));
  return rho;
}
/// r from ρ, the inverse of horizon_distance (radius_from_horizon_distance):
/// exactly RB at ρ = 0, at most RT. A correctly rounded sqrt gives the first by
/// itself; NVIDIA's fp64 sqrt (driver 580.159.04) is 1 ulp off there, which made
/// r − RB = 9e-10 m at the ground layer and its ground-hitting texels μ ≈ 0
/// instead of −1; at ρ = H, 1 ulp above RT makes d_min < 0 and μ = 1 come out ≈ 0.
real radius_from_horizon_distance(real rho) {
  PRECISE real r = rho == real(0) ? RB : min(sqrt(rho * rho + RB * RB), RT);
  return r;
}
/// μs_min = cos(90° + 3α) = −sin 3α, α = acos(rb/rt), −1 when 3α ≥ 90°: below
/// that sun no point of any ray in the shell is lit (the 3α argument is at
/// ShellGeometry::min_sun_cosine, parameterization.cpp). With s = sin α = H/rt,
/// sin 3α = 3s − 4s³ (the same arithmetic as the CPU).
real min_sun_cosine() {
  PRECISE real s = horizon_distance_at_top() / RT;
  PRECISE real mu_s = s >= real(0.5) ? real(-1) : -(real(3) * s - real(4) * s * s * s);
  return mu_s;
}

real distance_to_top(real r, real mu) {
  PRECISE real r_mu = r * mu;
  PRECISE real disc = r_mu * r_mu - difference_of_squares(r, RT);
  PRECISE real d = max(real(0), -r_mu + safe_sqrt(disc));
  return d;
}

real distance_to_bottom(real r, real mu) {
  PRECISE real r_mu = r * mu;
  PRECISE real disc = r_mu * r_mu - difference_of_squares(r, RB);
  PRECISE real d = max(real(0), -r_mu - safe_sqrt(disc));
  return d;
}

bool ray_hits_ground(real r, real mu) {
  PRECISE real r_mu = r * mu;
  PRECISE real disc = r_mu * r_mu - difference_of_squares(r, RB);
  return mu < real(0) && disc >= real(0);
}

real distance_to_nearest_boundary(real r, real mu, bool hits_ground) {
  return hits_ground ? distance_to_bottom(r, mu) : distance_to_top(r, mu);
}

real texture_coord_from_unit(real x, int n) {
  PRECISE real u = real(0.5) / real(n) + x * (real(1) - real(1) / real(n));
  return u;
}
real unit_from_texture_coord(real u, int n) {
  PRECISE real x = (u - real(0.5) / real(n)) / (real(1) - real(1) / real(n));
  return x;
}

// ---- transmittance T(r, μ)

real2 transmittance_uv(real r, real mu) {
  PRECISE real H = horizon_distance_at_top();
  PRECISE real rho = horizon_distance(r);
  PRECISE real d = distance_to_top(r, mu);
  PRECISE real d_min = RT - r, d_max = rho + H;
  PRECISE real x_mu = d_max > d_min ? (d - d_min) / (d_max - d_min) : real(0);
  return real2(texture_coord_from_unit(clamp(x_mu, real(0), real(1)), TRANSMITTANCE_MU),
               texture_coord_from_unit(clamp(rho / H, real(0), real(1)), TRANSMITTANCE_R));
}

void transmittance_r_mu(real u_mu, real v_r, out real r_out, out real mu_out) {
  PRECISE real H = horizon_distance_at_top();
  PRECISE real rho = H * unit_from_texture_coord(v_r, TRANSMITTANCE_R);
  PRECISE real r = radius_from_horizon_distance(rho);
  PRECISE real d_min = RT - r, d_max = rho + H;
  PRECISE real d = d_min + unit_from_texture_coord(u_mu, TRANSMITTANCE_MU) * (d_max - d_min);
  PRECISE real mu = d == real(0) ? real(1) : clamp_cosine((H * H - rho * rho - d * d) / (real(2) * r * d));
  r_out = r;
  mu_out = mu;
}

// ---- irradiance E(r, μs)

real2 irradiance_uv(real r, real mu_s) {
  PRECISE real x_r = (r - RB) / (RT - RB);
  return real2(texture_coord_from_unit(clamp(real(0.5) * mu_s + real(0.5), real(0), real(1)), IRRADIANCE_MU_S),
               texture_coord_from_unit(clamp(x_r, real(0), real(1)), IRRADIANCE_R));
}

void irradiance_r_mu_s(real u_mu_s, real v_r, out real r, out real mu_s) {
  PRECISE real r_value = RB + unit_from_texture_coord(v_r, IRRADIANCE_R) * (RT - RB);
  PRECISE real mu_s_value = clamp_cosine(real(2) * unit_from_texture_coord(u_mu_s, IRRADIANCE_MU_S) - real(1));
  r = r_value;
  mu_s = mu_s_value;
}

// ---- scattering S(r, μ, μs, ν), 4D packed into 3D: x = ν index · SCATTERING_MU_S + μs, y = μ, z = r

/// How μ (rays that do not hit the ground) and μs are mapped in a 4D table
/// (AngleMapping of parameterization.h): the single-scattering tables use
/// Bruneton's distance mapping, the multiple-scattering ones (density, delta,
/// multiple) its average with a mapping uniform in angle.
const int ANGLE_MAPPING_DISTANCE = 0;
const int ANGLE_MAPPING_BLENDED = 1;

/// Texel-coordinate values computed once per precompute by texel_coordinates.comp:
/// μs of each μs index per mapping, acos(μs_min), then μ of each sky (upper-half)
/// μ index per mapping and r layer. Offsets (TexelCoordinateLayout of
/// render/lut/shader_model.h, defined by the shader model): TEXEL_MU_S
/// [mapping][μs index], TEXEL_SUN_THETA_MAX acos(μs_min), TEXEL_MU_SKY
/// [mapping][z][y − SCATTERING_MU/2], TEXEL_VALUE_COUNT in all.
layout(std430, binding = TEXEL_COORDINATES_BINDING) buffer TexelCoordinates { real texel_values[]; };

/// A of distance_mapping_mu_s, its value at μs_min: from WavelengthData's
/// header in the shared render programs, as horizon_distance_at_top().
real distance_mapping_limit() {
#if MODEL_AT_RUN_TIME
  return wavelength_data[2].x;
#else
  PRECISE real d_min = RT - RB, d_max = horizon_distance_at_top();
  PRECISE real A = (distance_to_top(RB, min_sun_cosine()) - d_min) / (d_max - d_min);
  return A;
#endif
}

real distance_mapping_mu_s(real mu_s) {
  PRECISE real d_min = RT - RB, d_max = horizon_distance_at_top();
  PRECISE real a = (distance_to_top(RB, mu_s) - d_min) / (d_max - d_min);
  PRECISE real A = distance_mapping_limit();
  return max(real(1) - a / A, real(0)) / (real(1) + a);
}

/// `theta_max` = acos(μs_min) (sun_theta_max(): computed once, the value the CPU computes per call).
real unit_from_mu_s(real mu_s, int mapping, real theta_max) {
  if (mapping == ANGLE_MAPPING_DISTANCE) return distance_mapping_mu_s(mu_s);
  PRECISE real theta = acos_r(clamp(mu_s, real(-1), real(1)));
  PRECISE real uniform_part = max(real(0), real(1) - theta / theta_max);
  return real(0.5) * distance_mapping_mu_s(mu_s) + real(0.5) * uniform_part;
}

/// Inverse of unit_from_mu_s by bisection on μs ∈ [μs_min, 1] (as on the CPU, 64 steps).
real mu_s_from_unit(real x, int mapping) {
  real lo = min_sun_cosine(), hi = real(1);
  if (x <= real(0)) return lo;
  if (x >= real(1)) return real(1);
  const real theta_max = acos_r(min_sun_cosine());
  for (int i = 0; i < 64; ++i) {
    PRECISE real mid = real(0.5) * (lo + hi);
    if (unit_from_mu_s(mid, mapping, theta_max) < x) lo = mid;
    else hi = mid;
  }
  return real(0.5) * (lo + hi);
}

/// √((1 − μ²)(1 − μs²)), the half-width of the range of ν at μ, μs (nu_spread).
real nu_spread(real mu, real mu_s) {
  PRECISE real s = sqrt(max(real(0), (real(1) - mu * mu) * (real(1) - mu_s * mu_s)));
  return s;
}

/// u_ν = φ/π, φ the azimuth between view and sun at μ, μs (scattering_u_nu).
real scattering_u_nu(real mu, real mu_s, real nu) {
  const real spread = nu_spread(mu, mu_s);
  if (!(spread > real(NU_SPREAD_MIN))) return real(0);
  PRECISE real cos_phi = clamp((nu - mu * mu_s) / spread, real(-1), real(1));
  return acos_r(cos_phi) / PI;
}

/// ν at u_ν = x for μ, μs (scattering_nu_from_unit).
real scattering_nu_from_unit(real mu, real mu_s, real x) {
  PRECISE real nu = mu * mu_s + nu_spread(mu, mu_s) * cos_r(PI * x);
  return clamp(nu, real(-1), real(1));
}

/// μ ↔ [0, 1] for rays that do not hit the ground (unit_from_mu_sky).
real unit_from_mu_sky(real r, real mu, int mapping) {
  PRECISE real H = horizon_distance_at_top(), rho = horizon_distance(r);
  PRECISE real r_mu = r * mu;
  PRECISE real d = -r_mu + safe_sqrt(r_mu * r_mu - difference_of_squares(r, RT));
  PRECISE real d_min = RT - r, d_max = rho + H;
  PRECISE real distance = d_max == d_min ? real(0) : clamp((d - d_min) / (d_max - d_min), real(0), real(1));
  if (mapping == ANGLE_MAPPING_DISTANCE) return distance;
  PRECISE real theta_horizon = acos_r(clamp(-rho / r, real(-1), real(1)));  // zenith angle of the horizon
  PRECISE real angle = clamp(acos_r(clamp(mu, real(-1), real(1))) / theta_horizon, real(0), real(1));
  PRECISE real x = real(0.5) * distance + real(0.5) * angle;
  return x;
}

/// Inverse of unit_from_mu_sky: closed form for the distance mapping, bisection for the blend.
real mu_sky_from_unit(real r, real x, int mapping) {
  PRECISE real H = horizon_distance_at_top(), rho = horizon_distance(r);
  if (mapping == ANGLE_MAPPING_DISTANCE) {
    PRECISE real d_min = RT - r, d_max = rho + H;
    PRECISE real d = d_min + (d_max - d_min) * x;
    PRECISE real mu = d == real(0) ? real(1) : clamp_cosine((H * H - rho * rho - d * d) / (real(2) * r * d));
    return mu;
  }
  real lo = -rho / r, hi = real(1);  // x decreases as μ increases
  for (int i = 0; i < 64; ++i) {
    PRECISE real mid = real(0.5) * (lo + hi);
    if (unit_from_mu_sky(r, mid, mapping) > x) lo = mid;
    else hi = mid;
  }
  return real(0.5) * (lo + hi);
}

/// r and ρ at the centre of r layer z of the scattering tables.
real texel_r(int z, out real rho_out) {
  PRECISE real u_r = (real(z) + real(0.5)) / real(SCATTERING_R);
  PRECISE real rho = horizon_distance_at_top() * unit_from_texture_coord(u_r, SCATTERING_R);
  PRECISE real r = radius_from_horizon_distance(rho);
  rho_out = rho;
  return r;
}

/// The unit coordinate of sky μ index y (≥ SCATTERING_MU/2).
real texel_unit_mu_sky(int y) {
  PRECISE real u_mu = (real(y) + real(0.5)) / real(SCATTERING_MU);
  PRECISE real x = unit_from_texture_coord(real(2) * u_mu - real(1), SCATTERING_MU / 2);
  return x;
}

struct ScatteringUV {
  real u_nu, u_mu_s, u_mu, u_r;
};

/// acos(μs_min), stored by texel_coordinates.comp.
real sun_theta_max() { return texel_values[TEXEL_SUN_THETA_MAX]; }

// The four coordinates of scattering_uvwz (parameterization.cpp) separately, so a
// loop in which some are fixed computes those once.
real scattering_u_r(real r) {
  PRECISE real H = horizon_distance_at_top();
  PRECISE real rho = horizon_distance(r);
  PRECISE real u = texture_coord_from_unit(clamp(rho / H, real(0), real(1)), SCATTERING_R);
  return u;
}

real scattering_u_mu(real r, real mu, bool hits_ground, int mapping) {
  const int half_mu = SCATTERING_MU / 2;
  if (hits_ground) {
    // Distance to the ground, between r − rb (straight down) and ρ (tangent).
    PRECISE real rho = horizon_distance(r);
    PRECISE real r_mu = r * mu;
    PRECISE real disc = r_mu * r_mu - difference_of_squares(r, RB);
    PRECISE real d = -r_mu - safe_sqrt(disc);
    PRECISE real d_min = r - RB, d_max = rho;
    PRECISE real x = d_max == d_min ? real(0) : clamp((d - d_min) / (d_max - d_min), real(0), real(1));
    PRECISE real u = real(0.5) - real(0.5) * texture_coord_from_unit(x, half_mu);
    return u;
  }
  PRECISE real u = real(0.5) + real(0.5) * texture_coord_from_unit(unit_from_mu_sky(r, mu, mapping), half_mu);
  return u;
}

real scattering_u_mu_s(real mu_s, int mapping) {
  return texture_coord_from_unit(unit_from_mu_s(mu_s, mapping, sun_theta_max()), SCATTERING_MU_S);
}

ScatteringUV scattering_uvwz(real r, real mu, real mu_s, real nu, bool hits_ground, int mapping) {
  ScatteringUV uv;
  uv.u_r = scattering_u_r(r);
  uv.u_mu = scattering_u_mu(r, mu, hits_ground, mapping);
  uv.u_mu_s = scattering_u_mu_s(mu_s, mapping);
  uv.u_nu = scattering_u_nu(mu, mu_s, nu);
  return uv;
}

struct ScatteringCoordinates {
  real r, mu, mu_s, nu;
  bool hits_ground;
};

/// Physical coordinates at the centre of texel (x, y, z) of the packed 3D table
/// (μs and sky μ from the values texel_coordinates.comp computed by bisection).
ScatteringCoordinates scattering_texel_coordinates(int x, int y, int z, int mapping) {
  const int nu_index = x / SCATTERING_MU_S, mu_s_index = x % SCATTERING_MU_S;
  PRECISE real u_mu = (real(y) + real(0.5)) / real(SCATTERING_MU);
  PRECISE real x_nu = real(nu_index) / real(SCATTERING_NU - 1);

  ScatteringCoordinates c;
  real rho;
  c.r = texel_r(z, rho);
  const int half_mu = SCATTERING_MU / 2;
  if (u_mu < real(0.5)) {
    PRECISE real d_min = c.r - RB, d_max = rho;
    PRECISE real d = d_min + (d_max - d_min) * unit_from_texture_coord(real(1) - real(2) * u_mu, half_mu);
    PRECISE real mu = d == real(0) ? real(-1) : clamp_cosine(-(rho * rho + d * d) / (real(2) * c.r * d));
    c.mu = mu;
    c.hits_ground = true;
  } else {
    c.mu = texel_values[TEXEL_MU_SKY + (mapping * SCATTERING_R + z) * half_mu + (y - half_mu)];
    c.hits_ground = false;
  }
  c.mu_s = texel_values[TEXEL_MU_S + mapping * SCATTERING_MU_S + mu_s_index];
  c.nu = scattering_nu_from_unit(c.mu, c.mu_s, x_nu);
  return c;
}
