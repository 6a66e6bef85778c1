#pragma once
// Closing the series of scattering orders.
//
// The tables hold L = L_1 + L_2 + … + L_N for the N orders computed, and the
// orders left out are not small enough to drop: on Earth each order adds about
// 0.4 of the one before (order 5: 1.1 % of the sky's radiance, orders 6–∞
// together another 0.8 %), and on Mars' twilight sky, lit mostly by light
// scattered many times, more. Each order is the one before passed through the
// same linear operator (the scattering density of the paper's Eq. 9, then its
// integral along the ray), so the orders tend to that operator's dominant
// eigenfunction, L_{n+1} ≈ k·L_n, with k below 1 (the single-scattering albedo
// times the fraction of scattered light that meets the medium again). Where
// they do, the orders after N sum as a geometric series:
//
//   Σ_{n>N} L_n ≈ L_N (k + k² + …) = L_N · k / (1 − k),   k = L_N / L_{N−1},
//
// per texel and wavelength, k measured from the last two orders computed.
//
// The ratio of one texel is noisier than the table's, and it settles later:
// after 5 orders some of Mars' texels still show ratios near 1 where their
// orders have not yet found the shape of the later ones, and the series
// summed with them overshoots (a cap of 0.9 alone doubled Mars' error at 5
// orders). So k is capped per wavelength at 1.25 × the whole table's ratio
// ΣL_N / ΣL_{N−1} (the dominant eigenvalue's estimate, kSeriesTailTableMargin),
// and at kSeriesTailMaxRatio: an optically very thick, white atmosphere (the
// ratio near 1) cannot multiply the last order by more than 1/(1 − 0.9) − 1 = 9.
// Where L_{N−1} or L_N is 0 (no light) there is no tail. The same holds for
// the sky irradiance E_n, whose orders follow the radiance's one order behind.
//
// Measured against the converged series (24 orders) texel by texel
// (bench/series_tail_bench.cpp; docs/lookup-tables.md, "Closing the series").
//
// The CPU precompute uses these functions; shaders/series_tail.comp is their
// GPU twin for the radiance (the irradiance tail of the GPU precompute is
// computed here, after its readback: a 64×16 table).
#include <algorithm>

#include "atmosphere/lut/table.h"

namespace zenith::atmosphere::lut {

/// Largest ratio k of two consecutive orders the tail assumes.
inline constexpr double kSeriesTailMaxRatio = 0.9;
/// A texel's ratio is capped at this multiple of its table's.
inline constexpr double kSeriesTailTableMargin = 1.25;

/// The cap of one wavelength's texel ratios, from the sums of its last two
/// orders over the whole table: min(1.25 · last_sum / before_sum, 0.9); 0
/// where either sum is not positive.
inline double series_tail_ratio_cap(double last_sum, double before_sum) {
  if (!(last_sum > 0.0) || !(before_sum > 0.0)) return 0.0;
  return std::min(kSeriesTailTableMargin * last_sum / before_sum, kSeriesTailMaxRatio);
}

/// The factor k / (1 − k) of the last order's value that stands for every later
/// order, k = last / before_last capped at `ratio_cap` (< 1); 0 where
/// before_last ≤ 0 or last ≤ 0 (nothing to extrapolate).
inline double series_tail_factor(double last, double before_last, double ratio_cap) {
  if (!(last > 0.0) || !(before_last > 0.0)) return 0.0;
  const double k = std::min(last / before_last, ratio_cap);
  return k / (1.0 - k);
}

/// Adds the tail of every texel and channel to `sum` (the multiple-scattering
/// or irradiance table) and replaces `last` by it (for the caller's share of
/// the tail); `before_last` is the order before. The caps come from the
/// tables' own sums per channel. Returns Σ of the tail over every texel and
/// channel.
double add_series_tail(Table3D& last, const Table3D& before_last, Table3D& sum);
double add_series_tail(Table2D& last, const Table2D& before_last, Table2D& sum);

}  // namespace zenith::atmosphere::lut
