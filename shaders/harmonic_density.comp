#version 450 core
// Scattering density, step 3 of 3 (harmonics.glsl): for one column (r, μs)
// and one view μ of the table, J for every ν of the table:
//   D_m = c_m Σ_l q_l a_lm P̄_l^m(μ),   J(μ, ν) = Σ_m D_m cos(mφ_v),
// with q_l = β_R ρ_R(h) p_l^R + β_M ρ_M(h) p_l^M the phase functions' Legendre
// moments times the scattering coefficients at the column's altitude, and φ_v
// the view's azimuth from the sun's vertical. One group of 4 wavelengths.
layout(local_size_x = 64) in;

#include "atmosphere_common.glsl"
#include "harmonics.glsl"

layout(binding = OUTPUT_IMAGE, rgba32f) uniform writeonly image3D density_image;

void main() {
  const int invocation = int(gl_GlobalInvocationID.x);
  if (invocation >= COLUMNS * SCATTERING_MU) return;
  const int column = invocation / SCATTERING_MU, y = invocation % SCATTERING_MU;
  const int z = column / SCATTERING_MU_S, mu_s_index = column % SCATTERING_MU_S;
  const ScatteringCoordinates c = scattering_texel_coordinates(mu_s_index, y, z, ANGLE_MAPPING_BLENDED);
  const real h = c.r - RB;
  const real4 rayleigh = wavelength_field(FIELD_RAYLEIGH_SCATTERING) * rayleigh_density(h);
#if HAS_MIE
  const real4 mie = wavelength_field(FIELD_MIE_SCATTERING) * mie_density(h);
#endif

  // D_m, m = 0..L.
  real4 d[HARMONIC_ORDERS];
  const real x = c.mu;
  const int lanes_first = wavelength_group * 4 * HARMONIC_ORDERS;
  for (int m = 0; m < HARMONIC_ORDERS; ++m) {
    const real cm = azimuth_normalisation(m);
    real4 sum = real4(0);
    real p1 = legendre_diagonal(m, x), p2 = real(0);
    for (int l = m; l <= HARMONIC_DEGREE; ++l) {
      real p = p1;
      if (l == m + 1) {
        p = sqrt(real(2) * real(m) + real(3)) * x * p1;
      } else if (l >= m + 2) {
        p = legendre_step(l, m, x, p1, p2);
      }
      if (l > m) {
        p2 = p1;
        p1 = p;
      }
      real4 q = rayleigh * table_data[RAYLEIGH_MOMENTS + l];
#if HAS_MIE
      const int moment = MIE_MOMENTS + lanes_first + l;
      q += mie * real4(table_data[moment], table_data[moment + HARMONIC_ORDERS],
                       table_data[moment + 2 * HARMONIC_ORDERS], table_data[moment + 3 * HARMONIC_ORDERS]);
#endif
      sum += (cm * p) * q * harmonic_coefficients[column * HARMONIC_COUNT + harmonic_index(l, m)];
    }
    d[m] = sum;
  }

  const real sin_theta = sqrt(max(real(0), real(1) - c.mu * c.mu));
  const real sin_theta_s = sqrt(max(real(0), real(1) - c.mu_s * c.mu_s));
  const real denominator = sin_theta * sin_theta_s;
  for (int nu_index = 0; nu_index < SCATTERING_NU; ++nu_index) {
    const int x_texel = nu_index * SCATTERING_MU_S + mu_s_index;
    const ScatteringCoordinates cv = scattering_texel_coordinates(x_texel, y, z, ANGLE_MAPPING_BLENDED);
    const real cos_phi = denominator > real(0) ? clamp((cv.nu - c.mu * c.mu_s) / denominator, real(-1), real(1)) : real(1);
    real4 j = real4(0);
    real cos_prev = real(1), cos_m = real(1);
    for (int m = 0; m < HARMONIC_ORDERS; ++m) {
      j += cos_m * d[m];
      const real next = m == 0 ? cos_phi : real(2) * cos_phi * cos_m - cos_prev;
      cos_prev = cos_m;
      cos_m = next;
    }
    // The series cut at degree L can ring slightly below zero where J ≈ 0.
    imageStore(density_image, ivec3(x_texel, y, z), vec4(max(j, real4(0))));
  }
}
