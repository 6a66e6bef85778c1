#pragma once
// One Monte Carlo path sample of the sky radiance: the estimator behind
// path_tracer.h (which documents the physics, the stretch weight and the
// conventions), exposed for custom estimators such as flux integrals in tests.
#include <cstddef>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/rayleigh_polarization.h"
#include "atmosphere/reference/delta_tracking.h"
#include "atmosphere/reference/geometry.h"
#include "atmosphere/reference/majorant_grid.h"
#include "atmosphere/reference/medium.h"
#include "atmosphere/reference/random.h"
#include "atmosphere/reference/sun_disc.h"

namespace zenith::atmosphere::reference {

/// Which scattering orders a path counts, and when Russian roulette starts.
struct PathSettings {
  int min_scattering_order = 1;            ///< ≥ 1
  int max_scattering_order = 1000;         ///< ≥ min_scattering_order
  int russian_roulette_start_order = 4;    ///< ≥ 1
  std::size_t majorant_shell_count = 128;  ///< sub-shells of the delta-tracking majorant
  bool polarized = false;                  ///< vector radiative transfer (polarization.h); scalar if false
  bool aerosol_depolarizes = false;        ///< with polarized: the aerosols' light leaves unpolarized (polarization.h)
};

/// Read-only after construction; share one between threads. Keeps a reference
/// to the model, which must outlive it. Not copyable (it points into itself).
class PathIntegrator {
 public:
  /// Throws std::invalid_argument for inconsistent settings or an invalid sun.
  PathIntegrator(const AtmosphereModel& model, const SunDisc& sun, const PathSettings& settings);
  PathIntegrator(const PathIntegrator&) = delete;
  PathIntegrator& operator=(const PathIntegrator&) = delete;

  /// One sample of the sky radiance arriving at ray.point_at(0), travelling along
  /// −ray.direction(), at wavelength index i [sr^-1 per unit solar irradiance].
  /// The ray must start inside the atmosphere shell (up to rounding).
  /// `majorant_violations` is incremented for every tentative collision where
  /// β_ext exceeded the majorant.
  double radiance(const Ray& ray, std::size_t wavelength, Pcg32& rng, std::size_t& majorant_violations) const;

  /// One sample of what an analyser measures of that light: ⟨A, T⟩ for its coherency
  /// tensor T (polarization.h), A symmetric and across the ray — A = 1 the radiance, as
  /// radiance(); e₁e₁ᵀ − e₂e₂ᵀ and e₁e₂ᵀ + e₂e₁ᵀ its Stokes Q and U in a frame (e₁, e₂)
  /// across it. The analyser changes only the path's importance, never its draws, so one
  /// generator state gives one path for every A. Throws std::logic_error unless the
  /// settings are polarized (scalar transfer knows only the radiance).
  double analysed_radiance(const Ray& ray, const Mat3& analyser, std::size_t wavelength, Pcg32& rng,
                           std::size_t& majorant_violations) const;

  /// One sample of the direct sun irradiance on a surface element at `point_m`
  /// with unit normal `normal`: L_sun Ω · max(0, n·ω_s) · T̂(point, ω_s), ω_s
  /// uniform on the disc, T̂ by ratio tracking [per unit solar irradiance].
  double direct_irradiance(const Vec3& point_m, const Vec3& normal, std::size_t wavelength, Pcg32& rng,
                           std::size_t& majorant_violations) const;

  /// One ratio-tracking sample of the transmittance from `point_m` along
  /// `direction` to the top of the atmosphere; 0 if the planet is in the way,
  /// 1 if the ray never meets the atmosphere.
  double transmittance_to_space(const Vec3& point_m, const Vec3& direction, std::size_t wavelength, Pcg32& rng,
                                std::size_t& majorant_violations) const;

  const AtmosphereModel& model() const { return *model_; }
  const SunDisc& sun() const { return sun_; }

 private:
  /// The path behind radiance() and analysed_radiance(): the camera's importance starts at `analyser`.
  double traced(const Ray& ray, const Mat3& analyser, std::size_t wavelength, Pcg32& rng,
                std::size_t& majorant_violations) const;

  const AtmosphereModel* model_;
  AtmosphereMedium medium_;
  MajorantGrid majorants_;
  TrackingMedium tracking_;
  SunDisc sun_;
  double sun_weight_;
  PathSettings settings_;
};

}  // namespace zenith::atmosphere::reference
