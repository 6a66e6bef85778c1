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
  /// The three terms separately (no phase applied to the single terms);
  /// `multiple` may be null when only the single terms are needed.
  void scattering_terms(double r_m, double mu, double mu_s, double nu, bool hits_ground, double* rayleigh,
                        double* mie, double* multiple) const;

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
