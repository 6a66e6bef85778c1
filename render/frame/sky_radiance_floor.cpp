#include "render/frame/sky_radiance_floor.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "atmosphere/lut/parameterization.h"

namespace zenith::render {
namespace {

using atmosphere::lut::AngleMapping;

/// The float arithmetic of the GPU's reads (weights, the geometric blend's
/// exp and log) can land a few ulp under the smallest texel: a margin of 1e-3.
constexpr double kFloatMargin = 0.999;

/// A read at texel-centred coordinate u over n texels: the texel below, the one
/// above (the same at the ends) and the weight t of the one above.
struct Between {
  std::size_t lo = 0, hi = 0;
  double t = 0.0;
};
Between texels_read(double u, std::size_t n) {
  const double x = std::clamp(u * static_cast<double>(n) - 0.5, 0.0, static_cast<double>(n - 1));
  const double lo = std::min(std::floor(x), static_cast<double>(n > 1 ? n - 2 : 0));
  return {static_cast<std::size_t>(lo), std::min(static_cast<std::size_t>(lo) + 1, n - 1), x - lo};
}

/// The least a μs blend of two columns whose reads are at least a and b can
/// give: the geometric a^(1−t) b^t where both are positive (the lookups blend
/// geometrically, linearly, or in between, and the linear blend is the larger);
/// else the smaller of them, or 0 (any blend of a, b lies between them).
double least_blend(double a, double b, double t) {
  if (a > 0.0 && b > 0.0) return std::pow(a, 1.0 - t) * std::pow(b, t);
  return std::min({a, b, 0.0});
}

/// Per radius row z, μs column c and channel, the smallest texel of the sky
/// half (y ≥ height / 2) over every ν slice into out[(z * mu_s_size + c) *
/// channels + channel]. The multiple-scattering table's tail of orders can
/// leave a texel below 0: the minimum keeps its sign.
void sky_half_minima(const atmosphere::lut::Table3D& t, std::size_t mu_s_size, std::vector<double>& out) {
  out.assign(t.depth * mu_s_size * t.channels, std::numeric_limits<double>::infinity());
  for (std::size_t z = 0; z < t.depth; ++z)
    for (std::size_t y = t.height / 2; y < t.height; ++y)
      for (std::size_t x = 0; x < t.width; ++x) {
        const float* v = t.texel(x, y, z);
        double* m = &out[(z * mu_s_size + x % mu_s_size) * t.channels];
        for (std::size_t i = 0; i < t.channels; ++i) m[i] = std::min(m[i], static_cast<double>(v[i]));
      }
}

/// The least of texel × phase for texels ≥ `lowest` and phases in [p_min, p_max] (≥ 0).
double least_product(double lowest, double p_min, double p_max) {
  return lowest >= 0.0 ? lowest * p_min : lowest * p_max;
}

}  // namespace

SkyRadianceFloor::SkyRadianceFloor(const atmosphere::AtmosphereModel& model,
                                   const atmosphere::lut::LookupTables& tables, bool multiple_scattering)
    : geometry_(tables.geometry), sizes_(tables.sizes), channels_(tables.channels) {
  const std::size_t n = sizes_.scattering_mu_s;
  // The Rayleigh phase k (1 + a ν²) is extreme at ν = 0 or ±1.
  const double p_r[3] = {model.rayleigh_phase_function(1.0), model.rayleigh_phase_function(-1.0),
                         model.rayleigh_phase_function(0.0)};
  sky_half_minima(tables.single_rayleigh, n, rayleigh_);
  for (double& v : rayleigh_)
    v = least_product(v, std::max(0.0, *std::min_element(p_r, p_r + 3)), *std::max_element(p_r, p_r + 3));
  // The Mie phase's extremes (one minimum: Henyey–Greenstein, double HG,
  // Cornette–Shanks) on a grid of 4097 cosines, widened by 1 % for what falls between them.
  mie_.assign(rayleigh_.size(), 0.0);
  if (model.has_mie()) {
    sky_half_minima(tables.single_mie, n, mie_);
    constexpr int kGrid = 4096;
    for (std::size_t i = 0; i < channels_; ++i) {
      double p_lo = std::numeric_limits<double>::infinity(), p_hi = 0.0;
      for (int k = 0; k <= kGrid; ++k) {
        const double p = model.mie_phase(i, -1.0 + 2.0 * k / kGrid);
        p_lo = std::min(p_lo, p);
        p_hi = std::max(p_hi, p);
      }
      for (std::size_t j = i; j < mie_.size(); j += channels_)
        mie_[j] = least_product(mie_[j], 0.99 * std::max(p_lo, 0.0), 1.01 * p_hi);
    }
  }
  if (multiple_scattering)
    sky_half_minima(tables.multiple, n, multiple_);
  else
    multiple_.assign(rayleigh_.size(), 0.0);
}

std::vector<double> SkyRadianceFloor::radiance_per_irradiance(double mu_s, double radius_m) const {
  std::vector<double> out(channels_, 0.0);
  if (channels_ == 0) return out;
  const double mu = std::clamp(mu_s, -1.0, 1.0);
  const double r = std::clamp(radius_m, geometry_.bottom_radius_m, geometry_.top_radius_m);
  const std::size_t n = sizes_.scattering_mu_s;
  // Every pixel's read is at the camera's radius and the sun's cosine there:
  // the same row weights and μs blend for all; only μ and ν vary.
  const Between single =
      texels_read(atmosphere::lut::scattering_u_mu_s(geometry_, sizes_, mu, AngleMapping::Distance), n);
  const Between multiple =
      texels_read(atmosphere::lut::scattering_u_mu_s(geometry_, sizes_, mu, AngleMapping::Blended), n);
  const Between rows = texels_read(
      atmosphere::lut::scattering_uvwz(geometry_, sizes_, r, 1.0, mu, mu, false, AngleMapping::Distance).u_r,
      sizes_.scattering_r);
  // The least a column's read gives: bilinear in (μ, r) with the rows' weights, each row's least texel.
  const auto column = [&](const std::vector<double>& minima, std::size_t c, std::size_t i) {
    return (1.0 - rows.t) * minima[(rows.lo * n + c) * channels_ + i] +
           rows.t * minima[(rows.hi * n + c) * channels_ + i];
  };
  for (std::size_t i = 0; i < channels_; ++i) {
    const double rayleigh = least_blend(column(rayleigh_, single.lo, i), column(rayleigh_, single.hi, i), single.t);
    const double mie = least_blend(column(mie_, single.lo, i), column(mie_, single.hi, i), single.t);
    const double scattered =
        least_blend(column(multiple_, multiple.lo, i), column(multiple_, multiple.hi, i), multiple.t);
    out[i] = std::max(0.0, kFloatMargin * (rayleigh + mie + scattered));
  }
  return out;
}

}  // namespace zenith::render
