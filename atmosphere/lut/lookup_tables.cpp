#include "atmosphere/lut/lookup_tables.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "atmosphere/constants.h"

namespace zenith::atmosphere::lut {

LookupTables LookupTables::allocate(const ShellGeometry& g, const TableSizes& s, std::size_t channels) {
  s.check();
  LookupTables t;
  t.geometry = g;
  t.sizes = s;
  t.channels = channels;
  t.transmittance = Table2D(s.transmittance_mu, s.transmittance_r, channels);
  t.irradiance = Table2D(s.irradiance_mu_s, s.irradiance_r, channels);
  t.single_rayleigh = Table3D(s.scattering_width(), s.scattering_mu, s.scattering_r, channels);
  t.single_mie = Table3D(s.scattering_width(), s.scattering_mu, s.scattering_r, channels);
  t.multiple = Table3D(s.scattering_width(), s.scattering_mu, s.scattering_r, channels);
  return t;
}

TableQueries::TableQueries(const AtmosphereModel& model, const LookupTables& tables) : model_(model), tables_(tables) {}

void TableQueries::transmittance_to_top(double r_m, double mu, double* out) const {
  const TransmittanceUV uv = transmittance_uv(tables_.geometry, tables_.sizes, r_m, mu);
  tables_.transmittance.sample(uv.u_mu, uv.v_r, out);
}

void TableQueries::transmittance(double r_m, double mu, double d_m, bool hits_ground, double* out) const {
  // T(x, y) from ratios of tabulated transmittances to the top, always along
  // rays pointing *up* (short, well-resolved paths), never as the ratio of two
  // long grazing paths:
  //  * ascending segment (μ ≥ 0):   T = T_top(x, μ) / T_top(y, μ_y);
  //  * descending segment (it ends on the ground, or before its lowest point):
  //    reverse it, T = T_top(y, −μ_y) / T_top(x, −μ);
  //  * a segment through its lowest point p (radius r·√(1−μ²), horizontal there):
  //    T = [T_top(p, 0)/T_top(x, −μ)] · [T_top(p, 0)/T_top(y, μ_y)].
  const ShellGeometry& g = tables_.geometry;
  const double r_d =
      std::clamp(std::sqrt(d_m * d_m + 2.0 * r_m * mu * d_m + r_m * r_m), g.bottom_radius_m, g.top_radius_m);
  const double mu_d = std::clamp((r_m * mu + d_m) / r_d, -1.0, 1.0);
  std::array<double, kMaxChannels> a{}, b{}, p{};
  if (mu >= 0.0 && !hits_ground) {
    transmittance_to_top(r_m, mu, a.data());
    transmittance_to_top(r_d, mu_d, b.data());
    for (std::size_t c = 0; c < channels(); ++c) out[c] = b[c] > 0.0 ? std::min(a[c] / b[c], 1.0) : 0.0;
  } else if (hits_ground || mu_d <= 0.0) {
    transmittance_to_top(r_d, -mu_d, a.data());
    transmittance_to_top(r_m, -mu, b.data());
    for (std::size_t c = 0; c < channels(); ++c) out[c] = b[c] > 0.0 ? std::min(a[c] / b[c], 1.0) : 0.0;
  } else {
    const double r_p = std::max(r_m * std::sqrt(std::max(0.0, 1.0 - mu * mu)), g.bottom_radius_m);
    transmittance_to_top(r_p, 0.0, p.data());
    transmittance_to_top(r_m, -mu, a.data());
    transmittance_to_top(r_d, mu_d, b.data());
    for (std::size_t c = 0; c < channels(); ++c)
      out[c] = a[c] > 0.0 && b[c] > 0.0 ? std::min(p[c] / a[c], 1.0) * std::min(p[c] / b[c], 1.0) : 0.0;
  }
}

void TableQueries::transmittance_to_sun(double r_m, double mu_s, double* out) const {
  if (tables_.geometry.ray_hits_ground(r_m, mu_s)) {
    std::fill(out, out + channels(), 0.0);
    return;
  }
  transmittance_to_top(r_m, mu_s, out);
}

void TableQueries::irradiance(double r_m, double mu_s, bool include_direct, double* out) const {
  const IrradianceUV uv = irradiance_uv(tables_.geometry, tables_.sizes, r_m, mu_s);
  tables_.irradiance.sample(uv.u_mu_s, uv.v_r, out);
  if (!include_direct || mu_s <= 0.0) return;
  std::array<double, kMaxChannels> t{};
  transmittance_to_sun(r_m, mu_s, t.data());
  for (std::size_t c = 0; c < channels(); ++c) out[c] += t[c] * mu_s;
}

void sample_scattering_table(const Table3D& table, const TableSizes& s, const ScatteringUVWZ& uv, double* out) {
  // ν is the slowest-varying part of x: interpolate by hand between two ν slices.
  const double x_nu = uv.u_nu * double(s.scattering_nu - 1);
  const double nu_floor = std::min(std::floor(x_nu), double(s.scattering_nu - 1));
  const double t = x_nu - nu_floor;
  const double u0 = (nu_floor + uv.u_mu_s) / double(s.scattering_nu);
  const double u1 = (std::min(nu_floor + 1.0, double(s.scattering_nu - 1)) + uv.u_mu_s) / double(s.scattering_nu);
  std::array<double, kMaxChannels> a{}, b{};
  table.sample(u0, uv.u_mu, uv.u_r, a.data());
  table.sample(u1, uv.u_mu, uv.u_r, b.data());
  for (std::size_t ch = 0; ch < table.channels; ++ch) out[ch] = a[ch] * (1.0 - t) + b[ch] * t;
}

double geometric_blend(double a, double b, double t) {
  const double linear = a * (1.0 - t) + b * t;
  if (!(a > 0.0 && b > 0.0)) return linear;
  // |ln(b/a)| in float (GLSL has no double log or pow, and the GPU precompute
  // repeats this for the second order's source; the tables are float anyway).
  const float log_ratio = std::log(float(std::clamp(b / a, 1e-30, 1e30)));
  const float weight = std::clamp((kGeometricBlendFullLogRatio + 1.0f - std::abs(log_ratio)), 0.0f, 1.0f);
  if (weight == 0.0f) return linear;
  const double geometric = a * double(std::exp(float(t) * log_ratio));
  return linear + double(weight) * (geometric - linear);
}

void sample_scattering_table_geometric_mu_s(const Table3D& table, const TableSizes& s, const ScatteringUVWZ& uv,
                                            double* out) {
  // The μs texel columns either side of u_μs (texel centres at (i + ½)/n).
  const double n = double(s.scattering_mu_s);
  const double x = std::clamp(uv.u_mu_s * n - 0.5, 0.0, n - 1.0);
  const double i0 = std::min(std::floor(x), n - 2.0);
  const double t = x - i0;
  ScatteringUVWZ column_a = uv, column_b = uv;
  column_a.u_mu_s = (i0 + 0.5) / n;
  column_b.u_mu_s = (i0 + 1.5) / n;
  std::array<double, kMaxChannels> a{}, b{};
  sample_scattering_table(table, s, column_a, a.data());
  if (t == 0.0) {  // on a column's centre (the precompute's sphere integrals): the blend is a
    for (std::size_t c = 0; c < table.channels; ++c) out[c] = a[c];
    return;
  }
  sample_scattering_table(table, s, column_b, b.data());
  for (std::size_t c = 0; c < table.channels; ++c) out[c] = geometric_blend(a[c], b[c], t);
}

void TableQueries::scattering_terms(double r_m, double mu, double mu_s, double nu, bool hits_ground, double* rayleigh,
                                    double* mie, double* multiple) const {
  if (rayleigh || mie) {
    const ScatteringUVWZ single =
        scattering_uvwz(tables_.geometry, tables_.sizes, r_m, mu, mu_s, nu, hits_ground, AngleMapping::Distance);
    if (rayleigh) sample_scattering_table_geometric_mu_s(tables_.single_rayleigh, tables_.sizes, single, rayleigh);
    if (mie) sample_scattering_table_geometric_mu_s(tables_.single_mie, tables_.sizes, single, mie);
  }
  if (multiple)
    sample_scattering_table_geometric_mu_s(
        tables_.multiple, tables_.sizes,
        scattering_uvwz(tables_.geometry, tables_.sizes, r_m, mu, mu_s, nu, hits_ground, AngleMapping::Blended),
        multiple);
}

void TableQueries::scattering(double r_m, double mu, double mu_s, double nu, bool hits_ground, double* out) const {
  std::array<double, kMaxChannels> rayleigh{}, mie{}, multiple{};
  scattering_terms(r_m, mu, mu_s, nu, hits_ground, rayleigh.data(), mie.data(), multiple.data());
  const double phase_r = model_.rayleigh_phase_function(nu);
  for (std::size_t c = 0; c < channels(); ++c)
    out[c] = rayleigh[c] * phase_r + mie[c] * model_.mie_phase(c, nu) + multiple[c];
}

Spectrum TableQueries::sky_radiance(const Vec3& camera_m, const Vec3& view, const Vec3& sun) const {
  const ShellGeometry& g = tables_.geometry;
  Spectrum result(channels(), 0.0);
  Vec3 x = camera_m;
  double r = length(x);
  double rmu = dot(x, view);
  if (r > g.top_radius_m) {
    // Outside: move to where the ray enters the shell, or see nothing.
    const double disc = rmu * rmu - r * r + g.top_radius_m * g.top_radius_m;
    if (disc < 0.0 || rmu >= 0.0) return result;
    x = x + view * (-rmu - std::sqrt(disc));
    r = g.top_radius_m;
    rmu = dot(x, view);
  }
  r = std::max(r, g.bottom_radius_m);
  const double mu = std::clamp(rmu / r, -1.0, 1.0);
  const double mu_s = std::clamp(dot(x, sun) / r, -1.0, 1.0);
  const double nu = std::clamp(dot(view, sun), -1.0, 1.0);
  const bool hits_ground = g.ray_hits_ground(r, mu);

  std::array<double, kMaxChannels> s{};
  scattering(r, mu, mu_s, nu, hits_ground, s.data());
  for (std::size_t c = 0; c < channels(); ++c) result[c] = s[c];

  if (hits_ground) {
    // Lambertian ground: L = albedo/π · E(direct + sky), attenuated to the camera.
    const double d = g.distance_to_bottom_m(r, mu);
    const Vec3 ground = x + view * d;
    const double mu_s_ground = std::clamp(dot(normalize(ground), sun), -1.0, 1.0);
    std::array<double, kMaxChannels> e{}, t{};
    irradiance(g.bottom_radius_m, mu_s_ground, true, e.data());
    transmittance(r, mu, d, true, t.data());
    for (std::size_t c = 0; c < channels(); ++c) result[c] += t[c] * model_.ground_albedo[c] / kPi * e[c];
  }
  return result;
}

Spectrum TableQueries::ground_irradiance(double altitude_m, double sun_zenith_rad) const {
  Spectrum e(channels());
  std::array<double, kMaxChannels> out{};
  irradiance(tables_.geometry.bottom_radius_m + altitude_m, std::cos(sun_zenith_rad), true, out.data());
  for (std::size_t c = 0; c < channels(); ++c) e[c] = out[c];
  return e;
}

}  // namespace zenith::atmosphere::lut
