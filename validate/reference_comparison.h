#pragma once
// Error of the CPU path against the reference solver, per region. No GL.
//
// What is compared: single scattering. The tables hold single Rayleigh and
// single Mie in-scattering without their phase functions (lookup_tables.h),
// so the single-scattering sky radiance of the model is
//
//   L1_tables = S_R(r, μ, μs, ν) P_R(ν) + S_M(r, μ, μs, ν) P_M(ν)
//             + [ray hits the ground] T(x, g) (a/π) max(0, μs(g)) T_sun(g)
//
// — the same steps as TableQueries::sky_radiance (cameras outside the
// atmosphere moved to where the ray enters it by the same formula) with the
// multiple-scattering table and the skylight on the ground left out. The
// reference is the exact single scattering of atmosphere/reference/
// single_scattering.h (adaptive Gauss–Kronrod along the ray, analytic shadow
// and sphere breakpoints, point sun): L1 + L_ground. Cheap (≈ ms per ray), so
// hundreds per region; the path tracer (all orders) would need ~1e5 paths per
// ray for 1% and is left to the accuracy tests (tests/atmosphere/accuracy_test.cpp).
//
// Error per configuration: e = max_λ |L1_tables − L1_ref| / max(L1_ref, floor)
// (floor: see CpuStressOptions::floor_sr and docs/validation.md).
//
// Configurations are drawn per region (each region gets the same count) from
// targeted distributions: cameras in the atmosphere at log-uniform altitudes
// 1 m…R_top; the sun's zenith uniform in cos over the day, uniform in 90°–108°
// (twilight) or 108°–180° (night); views uniform in nadir angle over the
// ground, within 1° of the horizon with |δ| log-uniform down to 1e-10 rad, or
// above the band; from space, cameras at log-uniform altitudes up to 40 au
// looking at the shell.
#include <cstdint>
#include <functional>
#include <string>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"
#include "validate/stress_geometry.h"
#include "validate/stress_statistics.h"

namespace zenith::validate {

/// L1_tables above [sr^-1 per unit solar irradiance].
atmosphere::Spectrum table_single_scattering(const atmosphere::AtmosphereModel& model,
                                             const atmosphere::lut::TableQueries& queries, const Configuration& c);

/// Configuration `index` of the targeted distribution of `region` (classify() gives `region` back).
Configuration configuration_in_region(Region region, double ground_radius_m, double top_radius_m, std::uint64_t seed,
                                      std::uint64_t stream, std::uint64_t index);

struct ReferenceComparisonOptions {
  std::size_t samples_per_region = 100;
  std::uint64_t seed = 1;
  std::uint64_t stream = 0;
  double floor_sr = 1e-6;
  double relative_tolerance = 1e-6;  ///< of the reference quadrature
  unsigned threads = 0;
  std::function<void(std::size_t done, std::size_t total)> progress;  ///< serialized
};

/// Fills `regions[r].reference` for every region.
void compare_with_reference(const atmosphere::AtmosphereModel& model, const atmosphere::lut::TableQueries& queries,
                            const std::string& label, const ReferenceComparisonOptions& options, RegionTable& regions);

}  // namespace zenith::validate
