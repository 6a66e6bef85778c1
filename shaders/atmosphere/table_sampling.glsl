// Reading the lookup tables (included by atmosphere_common.glsl, after
// parameterization.glsl): linear interpolation by hand from texel fetches, the
// 4D scattering read with its geometric blend in μs, and the transmittance
// queries (atmosphere/lut/table.cpp, lookup_tables.cpp).

// ------------------------------------------------------------ tables (table.cpp)
// GL_LINEAR + GL_CLAMP_TO_EDGE by hand from texelFetch, weights in `real`, so the
// result is the CPU's Table2D/Table3D::sample (hardware filtering has 8-bit weights on some GPUs).

struct Lerp {
  int i0, i1;
  real t;
};

Lerp linear_taps(real u, int n) {
  PRECISE real x = u * real(n) - real(0.5);
  PRECISE real f = floor(x);
  Lerp l;
  l.t = x - f;
  const int i = int(f);
  l.i0 = clamp(i, 0, n - 1);
  l.i1 = clamp(i + 1, 0, n - 1);
  return l;
}

real4 sample_table_2d(sampler2D table, int width, int height, real u, real v) {
  const Lerp a = linear_taps(u, width), b = linear_taps(v, height);
  const real4 p00 = real4(texelFetch(table, ivec2(a.i0, b.i0), 0)), p10 = real4(texelFetch(table, ivec2(a.i1, b.i0), 0)),
              p01 = real4(texelFetch(table, ivec2(a.i0, b.i1), 0)), p11 = real4(texelFetch(table, ivec2(a.i1, b.i1), 0));
  PRECISE real w00 = (real(1) - a.t) * (real(1) - b.t), w10 = a.t * (real(1) - b.t), w01 = (real(1) - a.t) * b.t,
             w11 = a.t * b.t;
  return w00 * p00 + w10 * p10 + w01 * p01 + w11 * p11;
}

real4 sample_table_3d(sampler3D table, int width, int height, int depth, real u, real v, real w) {
  const Lerp a = linear_taps(u, width), b = linear_taps(v, height), d = linear_taps(w, depth);
  real4 out_value = real4(0);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        PRECISE real weight = (i == 0 ? real(1) - a.t : a.t) * (j == 0 ? real(1) - b.t : b.t) *
                            (k == 0 ? real(1) - d.t : d.t);
        if (weight == real(0)) continue;
        const ivec3 p = ivec3(i == 0 ? a.i0 : a.i1, j == 0 ? b.i0 : b.i1, k == 0 ? d.i0 : d.i1);
        out_value += weight * real4(texelFetch(table, p, 0));
      }
  return out_value;
}

/// sample_scattering_table (lookup_tables.cpp): trilinear in (μs, μ, r) within the
/// two nearest ν slices, then linear in ν by hand.
real4 sample_scattering_table(sampler3D table, ScatteringUV uv) {
  PRECISE real x_nu = uv.u_nu * real(SCATTERING_NU - 1);
  PRECISE real nu_floor = min(floor(x_nu), real(SCATTERING_NU - 1));
  PRECISE real t = x_nu - nu_floor;
  PRECISE real u0 = (nu_floor + uv.u_mu_s) / real(SCATTERING_NU);
  PRECISE real u1 = (min(nu_floor + real(1), real(SCATTERING_NU - 1)) + uv.u_mu_s) / real(SCATTERING_NU);
  const int width = SCATTERING_NU * SCATTERING_MU_S;
  const real4 a = sample_table_3d(table, width, SCATTERING_MU, SCATTERING_R, u0, uv.u_mu, uv.u_r);
  const real4 b = sample_table_3d(table, width, SCATTERING_MU, SCATTERING_R, u1, uv.u_mu, uv.u_r);
  return a * (real(1) - t) + b * t;
}

/// geometric_blend (lookup_tables.h): a^(1−t)·b^t while |ln(b/a)| ≤
/// GEOMETRIC_BLEND_FULL_LOG_RATIO (kGeometricBlendFullLogRatio, defined by the
/// shader model), fading to linear over the next unit, linear where either is
/// zero; logarithm and exponential in float, as on the CPU.
real geometric_blend(real a, real b, real t) {
  const real linear_value = a * (real(1) - t) + b * t;
  if (!(a > real(0) && b > real(0))) return linear_value;
  const float log_ratio = log(float(clamp(b / a, real(1e-30), real(1e30))));
  const float weight = clamp(GEOMETRIC_BLEND_FULL_LOG_RATIO + 1.0 - abs(log_ratio), 0.0, 1.0);
  if (weight == 0.0) return linear_value;
  const real geometric = a * real(exp(float(t) * log_ratio));
  return linear_value + real(weight) * (geometric - linear_value);
}
real4 geometric_blend(real4 a, real4 b, real t) {
  return real4(geometric_blend(a.x, b.x, t), geometric_blend(a.y, b.y, t), geometric_blend(a.z, b.z, t),
               geometric_blend(a.w, b.w, t));
}

/// The μs texel columns either side of u_μs and the blend weight between them
/// (sample_scattering_table_geometric_mu_s, lookup_tables.cpp).
struct MuSColumns {
  real u_a, u_b, t;
};
MuSColumns mu_s_columns(real u_mu_s) {
  const real n = real(SCATTERING_MU_S);
  PRECISE real x = clamp(u_mu_s * n - real(0.5), real(0), n - real(1));
  PRECISE real i0 = min(floor(x), n - real(2));
  MuSColumns c;
  c.t = x - i0;
  c.u_a = (i0 + real(0.5)) / n;
  c.u_b = (i0 + real(1.5)) / n;
  return c;
}

/// sample_scattering_table_geometric_mu_s (lookup_tables.cpp): the final
/// tables' read, geometric in μs between the two nearest texel columns, each
/// read like sample_scattering_table.
real4 sample_scattering_table_geometric_mu_s(sampler3D table, ScatteringUV uv) {
  const MuSColumns c = mu_s_columns(uv.u_mu_s);
  ScatteringUV column_a = uv, column_b = uv;
  column_a.u_mu_s = c.u_a;
  column_b.u_mu_s = c.u_b;
  const real4 a = sample_scattering_table(table, column_a);
  if (c.t == real(0)) return a;  // on a column's centre (the precompute's sphere integrals): the blend is a
  return geometric_blend(a, sample_scattering_table(table, column_b), c.t);
}

// ------------------------------------------------------------ transmittance queries (lookup_tables.cpp)

layout(binding = TRANSMITTANCE_UNIT) uniform sampler2D transmittance_texture;

real4 transmittance_to_top(real r, real mu) {
  const real2 uv = transmittance_uv(r, mu);
  return sample_table_2d(transmittance_texture, TRANSMITTANCE_MU, TRANSMITTANCE_R, uv.x, uv.y);
}

real transmittance_ratio(real a, real b) { return b > real(0) ? min(a / b, real(1)) : real(0); }
real4 transmittance_ratio(real4 a, real4 b) {
  return real4(transmittance_ratio(a.x, b.x), transmittance_ratio(a.y, b.y), transmittance_ratio(a.z, b.z),
               transmittance_ratio(a.w, b.w));
}

/// TableQueries::transmittance: T over a distance d along (r, μ), always from ratios of
/// transmittances to the top along upward rays (three cases, as on the CPU).
real4 transmittance(real r, real mu, real d, bool hits_ground) {
  PRECISE real r_d = clamp(sqrt(d * d + real(2) * r * mu * d + r * r), RB, RT);
  PRECISE real mu_d = clamp((r * mu + d) / r_d, real(-1), real(1));
  if (mu >= real(0) && !hits_ground) {
    return transmittance_ratio(transmittance_to_top(r, mu), transmittance_to_top(r_d, mu_d));
  } else if (hits_ground || mu_d <= real(0)) {
    return transmittance_ratio(transmittance_to_top(r_d, -mu_d), transmittance_to_top(r, -mu));
  }
  PRECISE real r_p = max(r * sqrt(max(real(0), real(1) - mu * mu)), RB);
  const real4 p = transmittance_to_top(r_p, real(0));
  const real4 a = transmittance_to_top(r, -mu);
  const real4 b = transmittance_to_top(r_d, mu_d);
  // Per lane, 0 where a or b is not positive; selected on whole vectors (NVIDIA refuses a double
  // vector written at a non-constant index, C9999 __setVectorIndex).
  const bvec4 positive = bvec4(uvec4(greaterThan(a, real4(0))) & uvec4(greaterThan(b, real4(0))));
  const real4 safe_a = mix(real4(1), a, positive), safe_b = mix(real4(1), b, positive);
  return mix(real4(0), min(p / safe_a, real4(1)) * min(p / safe_b, real4(1)), positive);
}

/// TableQueries::transmittance_to_sun: zero when the planet blocks the sun's centre.
real4 transmittance_to_sun(real r, real mu_s) {
  if (ray_hits_ground(r, mu_s)) return real4(0);
  return transmittance_to_top(r, mu_s);
}
