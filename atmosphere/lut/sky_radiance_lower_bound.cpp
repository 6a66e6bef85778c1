#include "atmosphere/lut/sky_radiance_lower_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "atmosphere/lut/parameterization.h"
#include "core/units.h"

namespace zenith::atmosphere::lut {
namespace {

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
void sky_half_minima(const Table3D& t, std::size_t mu_s_size, std::vector<double>& out) {
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

/// The sky half (y ≥ height / 2) of a table, row after row.
void copy_sky_half(const Table3D& t, std::vector<float>& out) {
  const std::size_t half = t.height / 2, row = t.width * t.channels;
  out.resize(t.depth * (t.height - half) * row);
  for (std::size_t z = 0; z < t.depth; ++z)
    for (std::size_t y = half; y < t.height; ++y)
      std::copy_n(t.texel(0, y, z), row, &out[(z * (t.height - half) + (y - half)) * row]);
}

/// The Mie phase's grid of cosines (as the floor's minima above).
constexpr std::size_t kMieGrid = 4096;

/// The least of a + b ν² over ν in `nu` (the Rayleigh phase models' shape):
/// at the cosine nearest 0 or the farthest, whichever is smaller.
double least_quadratic(double a, double b, Interval nu) {
  const double nearest = nu.lo <= 0.0 && nu.hi >= 0.0 ? 0.0 : std::min(std::abs(nu.lo), std::abs(nu.hi));
  const double farthest = std::max(std::abs(nu.lo), std::abs(nu.hi));
  return std::min(a + b * nearest * nearest, a + b * farthest * farthest);
}
double largest_quadratic(double a, double b, Interval nu) {
  const double nearest = nu.lo <= 0.0 && nu.hi >= 0.0 ? 0.0 : std::min(std::abs(nu.lo), std::abs(nu.hi));
  const double farthest = std::max(std::abs(nu.lo), std::abs(nu.hi));
  return std::max(a + b * nearest * nearest, a + b * farthest * farthest);
}

}  // namespace

SkyRadianceLowerBound::SkyRadianceLowerBound(const AtmosphereModel& model, const LookupTables& tables,
                                             bool multiple_scattering)
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

  // The sky half as it is, for the frame's slices; the phases.
  copy_sky_half(tables.single_rayleigh, sky_rayleigh_);
  if (model.has_mie()) copy_sky_half(tables.single_mie, sky_mie_);
  if (multiple_scattering) copy_sky_half(tables.multiple, sky_multiple_);
  rayleigh_at_0_ = model.rayleigh_phase_function(0.0);
  rayleigh_at_1_ = model.rayleigh_phase_function(1.0);
  if (model.has_mie()) {
    mie_phase_grid_.resize((kMieGrid + 1) * channels_);
    for (std::size_t k = 0; k <= kMieGrid; ++k)
      for (std::size_t i = 0; i < channels_; ++i)
        mie_phase_grid_[k * channels_ + i] = model.mie_phase(i, -1.0 + 2.0 * static_cast<double>(k) / kMieGrid);
  }
}

std::vector<double> SkyRadianceLowerBound::radiance_per_irradiance(double mu_s, double radius_m) const {
  std::vector<double> out(channels_, 0.0);
  if (channels_ == 0) return out;
  const double mu = std::clamp(mu_s, -1.0, 1.0);
  const double r = std::clamp(radius_m, geometry_.bottom_radius_m, geometry_.top_radius_m);
  const std::size_t n = sizes_.scattering_mu_s;
  // Every pixel's read is at the camera's radius and the sun's cosine there:
  // the same row weights and μs blend for all; only μ and ν vary.
  const Between single = texels_read(scattering_u_mu_s(geometry_, sizes_, mu, AngleMapping::Distance), n);
  const Between multiple = texels_read(scattering_u_mu_s(geometry_, sizes_, mu, AngleMapping::Blended), n);
  const Between rows = texels_read(
      scattering_uvwz(geometry_, sizes_, r, 1.0, mu, mu, false, AngleMapping::Distance).u_r, sizes_.scattering_r);
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

SkyLowerBoundSlice SkyRadianceLowerBound::slice(double mu_s, double radius_m) const {
  SkyLowerBoundSlice out;
  if (channels_ == 0) return out;
  out.floor_ = this;
  out.channels_ = channels_;
  out.half_ = sizes_.scattering_mu / 2;
  out.nu_ = sizes_.scattering_nu;
  out.mu_s_ = std::clamp(mu_s, -1.0, 1.0);
  out.radius_m_ = std::clamp(radius_m, geometry_.bottom_radius_m, geometry_.top_radius_m);
  const std::size_t n = sizes_.scattering_mu_s, width = sizes_.scattering_width(), half = out.half_;
  const Between rows = texels_read(
      scattering_uvwz(geometry_, sizes_, out.radius_m_, 1.0, out.mu_s_, out.mu_s_, false, AngleMapping::Distance).u_r,
      sizes_.scattering_r);
  // The row weight the texture unit applies: within 1/256 of the exact one.
  const double tr_lo = std::max(0.0, rows.t - 1.0 / 256.0), tr_hi = std::min(1.0, rows.t + 1.0 / 256.0);
  const auto fill = [&](const std::vector<float>& sky, AngleMapping mapping, SkyLowerBoundSlice::Term& term) {
    if (sky.empty()) return false;
    const Between columns = texels_read(scattering_u_mu_s(geometry_, sizes_, out.mu_s_, mapping), n);
    term.a = columns.lo;
    term.b = columns.hi;
    // The shader's blend weight, from float coordinates: within 1e-3 of this one.
    term.t_lo = std::max(0.0, columns.t - 1e-3);
    term.t_hi = std::min(1.0, columns.t + 1e-3);
    for (auto [column, values] : {std::pair{term.a, &term.column_a}, std::pair{term.b, &term.column_b}}) {
      values->resize(out.nu_ * half * channels_);
      for (std::size_t k = 0; k < out.nu_; ++k)
        for (std::size_t y = 0; y < half; ++y)
          for (std::size_t i = 0; i < channels_; ++i) {
            const std::size_t x = k * n + column;
            const double v0 = sky[((rows.lo * half + y) * width + x) * channels_ + i];
            const double v1 = sky[((rows.hi * half + y) * width + x) * channels_ + i];
            (*values)[(k * half + y) * channels_ + i] =
                std::min((1.0 - tr_lo) * v0 + tr_lo * v1, (1.0 - tr_hi) * v0 + tr_hi * v1);
          }
    }
    return true;
  };
  fill(sky_rayleigh_, AngleMapping::Distance, out.rayleigh_);
  out.mie_on_ = fill(sky_mie_, AngleMapping::Distance, out.mie_);
  out.multiple_on_ = fill(sky_multiple_, AngleMapping::Blended, out.multiple_);
  return out;
}

double SkyLowerBoundSlice::least(const Term& term, std::size_t y0, std::size_t y1, std::size_t k0, std::size_t k1,
                                 std::size_t i) const {
  double a = std::numeric_limits<double>::infinity(), b = a;
  for (std::size_t k = k0; k <= k1; ++k)
    for (std::size_t y = y0; y <= y1; ++y) {
      a = std::min(a, term.column_a[(k * half_ + y) * channels_ + i]);
      b = std::min(b, term.column_b[(k * half_ + y) * channels_ + i]);
    }
  // The geometric blend of positive a, b is monotonic in t: its least is at an end.
  return std::min(least_blend(a, b, term.t_lo), least_blend(a, b, term.t_hi));
}

void SkyLowerBoundSlice::texel_ranges(Interval mu, Interval phi_rad, bool blended, std::size_t& y0, std::size_t& y1,
                                      std::size_t& k0, std::size_t& k1) const {
  const SkyRadianceLowerBound& f = *floor_;
  const AngleMapping mapping = blended ? AngleMapping::Blended : AngleMapping::Distance;
  const double n_mu = static_cast<double>(f.sizes_.scattering_mu);
  // u_μ of the sky half falls as μ rises; the read weighs the texels either
  // side of u n − 0.5, here widened by 1e-3 of a texel for the GPU's float coordinates.
  const auto y_of = [&](double m) {
    return scattering_uvwz(f.geometry_, f.sizes_, radius_m_, std::clamp(m, -1.0, 1.0), mu_s_, 0.0, false, mapping)
                   .u_mu *
               n_mu -
           0.5;
  };
  const double ya = y_of(mu.lo), yb = y_of(mu.hi);
  const double top = n_mu - 1.0, bottom = static_cast<double>(half_);
  y0 = static_cast<std::size_t>(std::clamp(std::floor(std::min(ya, yb) - 1e-3), bottom, top)) - half_;
  y1 = static_cast<std::size_t>(std::clamp(std::ceil(std::max(ya, yb) + 1e-3), bottom, top)) - half_;
  // u_ν = φ/π over nu_ − 1 slice spacings; acos in float near φ = 0 or π is
  // off by up to ~1e-3 rad: 1e-2 of a slice.
  const double slices = static_cast<double>(nu_ - 1);
  k0 = static_cast<std::size_t>(std::clamp(std::floor(phi_rad.lo / core::kPi * slices - 1e-2), 0.0, slices));
  k1 = static_cast<std::size_t>(std::clamp(std::ceil(phi_rad.hi / core::kPi * slices + 1e-2), 0.0, slices));
}

void SkyLowerBoundSlice::radiance_per_irradiance(Interval mu, Interval phi_rad, Interval nu_rayleigh, Interval nu_mie,
                                                 double* out) const {
  std::fill(out, out + channels_, 0.0);
  if (!floor_) return;
  const SkyRadianceLowerBound& f = *floor_;
  std::size_t y0, y1, k0, k1, yb0, yb1, kb0, kb1;
  texel_ranges(mu, phi_rad, false, y0, y1, k0, k1);
  texel_ranges(mu, phi_rad, true, yb0, yb1, kb0, kb1);
  const double a = f.rayleigh_at_0_, b = f.rayleigh_at_1_ - f.rayleigh_at_0_;
  const double p_r_lo = std::max(0.0, least_quadratic(a, b, nu_rayleigh)),
               p_r_hi = largest_quadratic(a, b, nu_rayleigh);
  // The Mie phase's grid points bracketing ν (one minimum: between grid points
  // it stays within 1 % of the bracketing points' least).
  const auto grid = [](double nu) { return (std::clamp(nu, -1.0, 1.0) + 1.0) * 0.5 * static_cast<double>(kMieGrid); };
  const std::size_t g0 = static_cast<std::size_t>(std::floor(grid(nu_mie.lo)));
  const std::size_t g1 = std::min(kMieGrid, static_cast<std::size_t>(std::ceil(grid(nu_mie.hi))));
  for (std::size_t i = 0; i < channels_; ++i) {
    double sum = least_product(least(rayleigh_, y0, y1, k0, k1, i), p_r_lo, p_r_hi);
    if (mie_on_) {
      double p_lo = std::numeric_limits<double>::infinity(), p_hi = 0.0;
      for (std::size_t g = g0; g <= g1; ++g) {
        p_lo = std::min(p_lo, f.mie_phase_grid_[g * channels_ + i]);
        p_hi = std::max(p_hi, f.mie_phase_grid_[g * channels_ + i]);
      }
      sum += least_product(least(mie_, y0, y1, k0, k1, i), 0.99 * std::max(p_lo, 0.0), 1.01 * p_hi);
    }
    if (multiple_on_) sum += least(multiple_, yb0, yb1, kb0, kb1, i);
    out[i] = std::max(0.0, kFloatMargin * sum);
  }
}

}  // namespace zenith::atmosphere::lut
