#include "atmosphere/lut/sky_radiance_bound.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "atmosphere/lut/parameterization.h"
#include "core/units.h"

namespace zenith::atmosphere::lut {
namespace {

/// The column above `mu_s` of a texel-centred coordinate over n columns: the
/// last column any read at a cosine ≤ mu_s can weigh.
std::size_t column_above(double u, std::size_t n) {
  const double x = std::clamp(u * static_cast<double>(n) - 0.5, 0.0, static_cast<double>(n - 1));
  return static_cast<std::size_t>(std::ceil(x));
}

/// Per radius row z, column of the packed 4D table (x = ν index · mu_s_size +
/// μs index) and channel, the largest texel into out[(z * mu_s_size + column) * channels + channel].
void column_maxima(const Table3D& t, std::size_t mu_s_size, std::vector<double>& out) {
  out.assign(t.depth * mu_s_size * t.channels, 0.0);
  for (std::size_t z = 0; z < t.depth; ++z)
    for (std::size_t y = 0; y < t.height; ++y)
      for (std::size_t x = 0; x < t.width; ++x) {
        const float* v = t.texel(x, y, z);
        double* m = &out[(z * mu_s_size + x % mu_s_size) * t.channels];
        for (std::size_t i = 0; i < t.channels; ++i) m[i] = std::max(m[i], static_cast<double>(v[i]));
      }
}

/// Per μs column and channel, the largest single-Mie texel times the largest
/// phase any lookup weighing it can apply: a texel is weighed only by lookups
/// within one cell of it in μ, r, μs and ν, whose view–source angle γ is at
/// least the difference of their zenith angles and, from the azimuth φ ≥
/// φ_min of that ν slice, cos γ ≤ cos(θv − θs) − sin θv sin θs (1 − cos φ_min).
/// The forward peak then counts only where view and source can be close.
void mie_column_maxima(const AtmosphereModel& model, const LookupTables& tables, std::vector<double>& out) {
  const Table3D& t = tables.single_mie;
  const TableSizes& s = tables.sizes;
  const std::size_t n_mu_s = s.scattering_mu_s, n_nu = s.scattering_nu, n_mu = t.height, n_r = t.depth;
  const std::size_t channels = t.channels;
  out.assign(n_r * n_mu_s * channels, 0.0);
  if (!model.has_mie()) return;
  // The phase on a grid of ν, per channel; P_M(ν ≤ ν_hi) ≤ max(P_M(grid point above ν_hi), P_M(−1)) for
  // phase functions with one minimum (Henyey–Greenstein, double HG, Cornette–Shanks).
  constexpr std::size_t kGrid = 4096;
  std::vector<double> phase((kGrid + 1) * channels);
  for (std::size_t k = 0; k <= kGrid; ++k)
    for (std::size_t i = 0; i < channels; ++i)
      phase[k * channels + i] = model.mie_phase(i, -1.0 + 2.0 * static_cast<double>(k) / kGrid);
  // Zenith angles of the texel centres: the view's by (μ, r), the source's by column.
  std::vector<double> theta_v(n_mu * n_r), theta_s(n_mu_s);
  for (std::size_t z = 0; z < n_r; ++z)
    for (std::size_t y = 0; y < n_mu; ++y)
      theta_v[z * n_mu + y] = std::acos(
          std::clamp(scattering_texel_coordinates(tables.geometry, s, 0, y, z, AngleMapping::Distance).mu, -1.0, 1.0));
  for (std::size_t c = 0; c < n_mu_s; ++c)
    theta_s[c] = std::acos(
        std::clamp(scattering_texel_coordinates(tables.geometry, s, c, 0, 0, AngleMapping::Distance).mu_s, -1.0, 1.0));
  const auto range = [](const std::vector<double>& v, std::size_t lo, std::size_t hi) {
    const auto [a, b] = std::minmax_element(v.begin() + static_cast<std::ptrdiff_t>(lo),
                                            v.begin() + static_cast<std::ptrdiff_t>(hi) + 1);
    return std::pair{*a, *b};
  };
  for (std::size_t z = 0; z < n_r; ++z)
    for (std::size_t y = 0; y < n_mu; ++y) {
      double v_lo = 4.0, v_hi = -1.0;  // θv over the neighbouring texels in μ and r
      for (std::size_t zz = z > 0 ? z - 1 : 0; zz <= std::min(z + 1, n_r - 1); ++zz) {
        const auto [a, b] = range(theta_v, zz * n_mu + (y > 0 ? y - 1 : 0), zz * n_mu + std::min(y + 1, n_mu - 1));
        v_lo = std::min(v_lo, a);
        v_hi = std::max(v_hi, b);
      }
      for (std::size_t c = 0; c < n_mu_s; ++c) {
        const auto [s_lo, s_hi] = range(theta_s, c > 0 ? c - 1 : 0, std::min(c + 1, n_mu_s - 1));
        const double d_theta = std::max({0.0, v_lo - s_hi, s_lo - v_hi});
        const double sines = std::min(std::sin(v_lo), std::sin(v_hi)) * std::min(std::sin(s_lo), std::sin(s_hi));
        for (std::size_t k = 0; k < n_nu; ++k) {
          const double phi_min = core::kPi * static_cast<double>(k > 0 ? k - 1 : 0) / static_cast<double>(n_nu - 1);
          const double nu_hi =
              std::clamp(std::cos(d_theta) - std::max(sines, 0.0) * (1.0 - std::cos(phi_min)), -1.0, 1.0);
          const std::size_t g =
              std::min<std::size_t>(kGrid, static_cast<std::size_t>(std::ceil((nu_hi + 1.0) * 0.5 * kGrid)));
          const float* v = t.texel(k * n_mu_s + c, y, z);
          double* m = &out[(z * n_mu_s + c) * channels];
          for (std::size_t i = 0; i < channels; ++i)
            m[i] = std::max(m[i], static_cast<double>(v[i]) * std::max(phase[g * channels + i], phase[i]));
        }
      }
    }
}

}  // namespace

SkyRadianceBound::SkyRadianceBound(const AtmosphereModel& model, const LookupTables& tables)
    : geometry_(tables.geometry), sizes_(tables.sizes), channels_(tables.channels) {
  const std::size_t n = sizes_.scattering_mu_s;
  std::vector<double> rayleigh;
  column_maxima(tables.single_rayleigh, n, rayleigh);
  mie_column_maxima(model, tables, mie_);
  column_maxima(tables.multiple, n, multiple_);
  // The Rayleigh phase's largest value: at ν = ±1 (or 0 for a negative anisotropy).
  const double p_r = std::max(
      {model.rayleigh_phase_function(1.0), model.rayleigh_phase_function(-1.0), model.rayleigh_phase_function(0.0)});
  single_ = rayleigh;
  for (double& v : single_) v *= p_r;
  // The ground's sky irradiance is read at RB: the table's first row (texel-centred, clamped).
  const Table2D& e = tables.irradiance;  // x: μs, y: r
  irradiance_.assign(e.width * channels_, 0.0);
  for (std::size_t y = 0; y < std::min<std::size_t>(e.height, 1); ++y)
    for (std::size_t x = 0; x < e.width; ++x)
      for (std::size_t i = 0; i < channels_; ++i)
        irradiance_[x * channels_ + i] =
            std::max(irradiance_[x * channels_ + i], static_cast<double>(e.data[(y * e.width + x) * channels_ + i]));
}

std::vector<double> SkyRadianceBound::radiance_per_irradiance(double mu_s_max, std::optional<double> radius_m) const {
  std::vector<double> out(channels_, 0.0);
  if (channels_ == 0) return out;
  const double mu = std::clamp(mu_s_max, -1.0, 1.0);
  const std::size_t n = sizes_.scattering_mu_s, rows = sizes_.scattering_r;
  const std::size_t single_top = column_above(scattering_u_mu_s(geometry_, sizes_, mu, AngleMapping::Distance), n);
  const std::size_t multiple_top = column_above(scattering_u_mu_s(geometry_, sizes_, mu, AngleMapping::Blended), n);
  const std::size_t irradiance_columns = irradiance_.size() / channels_;
  const std::size_t irradiance_top =
      column_above(irradiance_uv(geometry_, sizes_, geometry_.bottom_radius_m, mu).u_mu_s, irradiance_columns);
  // The rows a read at `radius_m` weighs (all without one): the two around its texel-centred coordinate.
  std::size_t row_lo = 0, row_hi = rows - 1;
  if (radius_m) {
    const double u = scattering_uvwz(geometry_, sizes_, *radius_m, 1.0, mu, mu, false, AngleMapping::Distance).u_r;
    const double x = std::clamp(u * static_cast<double>(rows) - 0.5, 0.0, static_cast<double>(rows - 1));
    row_lo = static_cast<std::size_t>(std::floor(x));
    row_hi = static_cast<std::size_t>(std::ceil(x));
  }
  for (std::size_t i = 0; i < channels_; ++i) {
    double rayleigh = 0.0, mie = 0.0, multiple = 0.0, sky = 0.0;
    for (std::size_t z = row_lo; z <= row_hi; ++z) {
      for (std::size_t c = 0; c <= single_top; ++c) {
        rayleigh = std::max(rayleigh, single_[(z * n + c) * channels_ + i]);
        mie = std::max(mie, mie_[(z * n + c) * channels_ + i]);
      }
      for (std::size_t c = 0; c <= multiple_top; ++c)
        multiple = std::max(multiple, multiple_[(z * n + c) * channels_ + i]);
    }
    for (std::size_t c = 0; c <= irradiance_top; ++c) sky = std::max(sky, irradiance_[c * channels_ + i]);
    const double ground = (std::max(mu, 0.0) + sky) / core::kPi;
    out[i] = rayleigh + mie + multiple + ground;
  }
  return out;
}

double source_cosine_bound(double mu_s_camera, double camera_radius_m, double ground_radius_m, double top_radius_m,
                           bool bodies_inside) {
  if (camera_radius_m > top_radius_m) return 1.0;
  const double r = std::max(camera_radius_m, ground_radius_m);
  const double arc = std::acos(std::min(ground_radius_m / r, 1.0)) +
                     (bodies_inside ? std::acos(std::min(ground_radius_m / top_radius_m, 1.0)) : 0.0);
  const double zenith = std::acos(std::clamp(mu_s_camera, -1.0, 1.0));
  return std::cos(std::max(zenith - arc, 0.0));
}

}  // namespace zenith::atmosphere::lut
