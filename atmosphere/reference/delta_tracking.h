#pragma once
// Free-flight sampling (delta tracking) and transmittance estimation (ratio
// tracking) through the model's atmosphere, with the air-mass stretch.
//
// Along a ray with stretch s the attenuation coefficient is s·β_ext(h) (the
// stretch multiplies optical depth), while scattering adds light with the
// unstretched β_scat (see optical_depth.h and path_tracer.h). Both trackers use
// the ray-constant majorant s·β̄_k of the MajorantGrid shell k the ray is in:
//  * delta tracking (Woodcock 1965): tentative collisions are a Poisson process
//    of rate s·β̄_k; one at altitude h is real with probability
//    s·β_ext(h) / (s·β̄_k) = β_ext(h)/β̄_k. The first real collision is then
//    distributed with density s·β_ext(t)·T_s(0, t), T_s = exp(−s∫β_ext), and the
//    ray passes unscattered with probability T_s(0, end).
//  * residual ratio tracking (Novák, Selle & Jarosz 2014): the shell minorant β̲_k
//    is a control whose attenuation is analytic, and only the residual
//    β_ext − β̲_k is tracked, with tentative collisions at rate s(β̄_k − β̲_k):
//      T̂ = Π_segments exp(−s β̲_k ℓ_k) · Π_j (1 − (β_ext(h_j) − β̲_k)/(β̄_k − β̲_k)),
//    an unbiased estimate of T_s (for any positive rate; the bounds only keep
//    each factor in [0, 1]). Its relative variance is at most exp(τ_residual) − 1,
//    where plain ratio tracking with a tight majorant (β̲ = 0) behaves almost like a
//    binary hit-or-miss estimate, relative variance ≈ exp(τ) − 1.
// Crossing a shell boundary restarts the exponential clock with the next shell's
// rate (memorylessness), so one exponential variate in units of majorant optical
// depth serves all segments up to the next tentative collision.
#include <cstddef>

#include "atmosphere/reference/geometry.h"
#include "atmosphere/reference/majorant_grid.h"
#include "atmosphere/reference/medium.h"
#include "atmosphere/reference/random.h"

namespace zenith::atmosphere::reference {

/// What a tracker needs: the medium and its majorants. Both must outlive it.
struct TrackingMedium {
  const AtmosphereMedium* medium;
  const MajorantGrid* majorants;
};

struct FreeFlight {
  enum class Event { Scattering, Ground, Escape };
  Event event = Event::Escape;
  double t_m = 0.0;                ///< where the collision or the ground hit is (unused for Escape)
  LocalCoefficients coefficients;  ///< at a Scattering collision: the medium there (unstretched)
};

/// Samples the first real collision along `ray` from t_begin (inside the
/// atmosphere) at wavelength index i, for attenuation s·β_ext. Returns the
/// ground hit or an escape through the top when there is none before them.
/// Increments `majorant_violations` whenever β_ext exceeds the majorant.
FreeFlight sample_free_flight(const TrackingMedium& tracking, const Ray& ray, double t_begin_m, double stretch,
                              std::size_t wavelength, Pcg32& rng, std::size_t& majorant_violations);

/// Unbiased estimate of T_s along `ray` from t_begin to where it leaves the top
/// of the atmosphere, at wavelength index i, by residual ratio tracking; 0 if the
/// ray hits the ground. Once the running product falls below 1e-6 the walk is
/// cut short by Russian roulette (survival probability T̂/1e-6, then T̂ = 1e-6),
/// which keeps it unbiased. (Thanks to the analytic control, a walk through a
/// thick region costs only its residual optical depth in steps, so the threshold
/// can be this low.)
double ratio_tracking_transmittance(const TrackingMedium& tracking, const Ray& ray, double t_begin_m, double stretch,
                                    std::size_t wavelength, Pcg32& rng, std::size_t& majorant_violations);

}  // namespace zenith::atmosphere::reference
