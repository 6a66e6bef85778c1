#pragma once
// A precomputed table set (paper section 5.1) and the radiance queries that
// read it. All radiances are per unit solar irradiance at the top of the
// atmosphere (sr^-1), so the sun's brightness never shapes the tables; the
// renderer multiplies by the solar spectral irradiance.
//
// Tables (one channel per working wavelength):
//  * transmittance T(r, μ) from a point to the top of the atmosphere, for rays
//    that do not hit the ground, with the air-mass stretch included;
//  * irradiance E(r, μs) on a horizontal surface from skylight only (orders ≥ 1;
//    the direct sun, T·μs, is added at query time);
//  * single Rayleigh and single Mie in-scattering S1(r, μ, μs, ν) without their
//    phase functions (so the Mie phase, which varies per wavelength, is applied
//    at full resolution at query time: the single Mie term is kept in full colour);
//  * multiple scattering (orders 2..n) with phase functions already applied.
#include <string>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/parameterization.h"
#include "atmosphere/lut/table.h"
#include "atmosphere/vec3.h"

namespace zenith::atmosphere::lut {

struct LookupTables {
  ShellGeometry geometry{};
  TableSizes sizes{};
  std::size_t channels = 0;
  Table2D transmittance;
  Table2D irradiance;
  Table3D single_rayleigh;
  Table3D single_mie;
  Table3D multiple;
  int scattering_orders = 0;  ///< highest order included
  std::string hash;           ///< lookup_table_hash() of the model they were made for

  /// Allocates zeroed tables of the given sizes.
  static LookupTables allocate(const ShellGeometry& g, const TableSizes& s, std::size_t channels);
};

/// Samples a packed 4D scattering-like table at `uv`: trilinear in (μs, μ, r)
/// within the two nearest ν slices, then linear in ν by hand.
void sample_scattering_table(const Table3D& table, const TableSizes& sizes, const ScatteringUVWZ& uv, double* out);

/// As sample_scattering_table, but geometric in μs: each ν slice is read
/// bilinearly in (μ, r) at the two nearest μs texel columns a and b and blended
/// as a^(1−t)·b^t per channel (linearly where either is zero). Used for every
/// read of the final tables (single Rayleigh, single Mie, multiple). Through
/// twilight S falls by about e per degree of solar depression — the shadow of
/// the planet climbs through an exponential atmosphere — and linear
/// interpolation across 1–1.6° μs texels overshoots: at the paper's 32 μs
/// texels the Earth twilight sky came out 10–90 % too bright (RMS 0.30 against
/// the path tracer), geometric blending gives RMS 0.07, better than linear
/// interpolation in a table with twice the μs texels (0.09). Elsewhere the two
/// agree to second order. The precompute reads its own tables the same way: the
/// scattering density along each ray and the last order's radiance (read
/// linearly, J's e-fold fall per degree of depression across
/// 3–4° texels made the deep twilight 2–3× too bright at −18°; an earlier
/// test at sun −4° on small tables had measured these reads slightly worse,
/// 0.10 against 0.07) (docs/lookup-tables.md, "Interpolation in μs"). On a
/// column's centre (t = 0) only that column is read.
/// Blend of neighbouring μs texels a, b at t ∈ [0, 1]: a^(1−t)·b^t while
/// |ln(b/a)| ≤ kGeometricBlendFullLogRatio, fading to the linear (1−t)·a + t·b
/// over the next unit of |ln(b/a)|, linear where either is zero. Through
/// twilight neighbouring texels differ by up to e⁴ and need the geometric form
/// (full geometric up to e² gave RMS 0.13 instead of 0.07); across the planet's
/// shadow edge, where one side is nearly zero, the fade keeps the result
/// continuous as a value goes to zero (a geometric mean would collapse to zero
/// there, and jump back to linear at exactly zero). Logarithm and exponential
/// in float, as in GLSL.
constexpr float kGeometricBlendFullLogRatio = 5.0f;
double geometric_blend(double a, double b, double t);
void sample_scattering_table_geometric_mu_s(const Table3D& table, const TableSizes& sizes, const ScatteringUVWZ& uv,
                                            double* out);

/// Read-only queries on a table set and the model that made it.
class TableQueries {
 public:
  TableQueries(const AtmosphereModel& model, const LookupTables& tables);

  std::size_t channels() const { return tables_.channels; }
  const LookupTables& tables() const { return tables_; }

  /// T from (r, μ) to the top of the atmosphere; the ray must not hit the ground.
  void transmittance_to_top(double r_m, double mu, double* out) const;
  /// T over a distance d along (r, μ); `hits_ground`: the ray (continued) ends on the ground.
  void transmittance(double r_m, double mu, double d_m, bool hits_ground, double* out) const;
  /// T to the sun's centre from (r, μs); zero when the planet blocks it.
  void transmittance_to_sun(double r_m, double mu_s, double* out) const;
  /// Ground irradiance on a horizontal surface at (r, μs): direct + sky [per unit solar irradiance].
  void irradiance(double r_m, double mu_s, bool include_direct, double* out) const;
  /// In-scattered radiance S(r, μ, μs, ν) along the ray to its boundary, all orders, phases applied.
  void scattering(double r_m, double mu, double mu_s, double nu, bool hits_ground, double* out) const;
  /// The three terms separately (no phase applied to the single terms); any
  /// of them may be null where it is not needed.
  void scattering_terms(double r_m, double mu, double mu_s, double nu, bool hits_ground, double* rayleigh, double* mie,
                        double* multiple) const;

  /// Sky radiance seen from `camera_m` (planet-centred) along unit `view`, sun
  /// along unit `sun`: in-scattering along the ray plus, where it hits the
  /// ground, the ground's reflected light attenuated to the camera. Excludes the
  /// sun disc. Cameras outside the atmosphere look from where the ray enters it.
  Spectrum sky_radiance(const Vec3& camera_m, const Vec3& view, const Vec3& sun) const;
  /// Ground irradiance (direct + sky) on a horizontal surface at altitude h.
  Spectrum ground_irradiance(double altitude_m, double sun_zenith_rad) const;

 private:
  const AtmosphereModel& model_;
  const LookupTables& tables_;
};

}  // namespace zenith::atmosphere::lut
