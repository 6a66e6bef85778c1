#pragma once
// The sky of a solar eclipse from an atmosphere's lookup tables and the
// Moon's shadow (astro/moon_shadow.h; docs/validation.md, "Eclipses"): what
// `zenith validate eclipse` holds against the path tracer with the Moon in
// front of the disc, and the sum the renderer's sky-view fill is to run (it
// does not yet: docs/rendering.md, "Sun, shadows, eclipses").
//
// Along the view ray from x to its end e, cut at x = p_0, p_1, …, p_N = e,
// each table term S (single Rayleigh, single Mie, multiple) splits by the
// tables' own identity S(x → p_N) = Σ_k [T(x, p_k) S(p_k) − T(x, p_k+1) S(p_k+1)]
// (S(p_N) = 0: nothing scatters beyond the ray's end), and each segment's
// share is weighted by the shadow at its middle:
//   L = Σ_k V(m_k) [single R P_R + single M P_M]_k + V̄(m_k) [multiple]_k
//       + T(x, e) ρ/π (E_sun(e) V(e) + E_sky(e) V̄(e))     on the ground,
// with V the direct light the Moon leaves and V̄ the scattered light. Without
// a Moon (V = V̄ = 1) the sum telescopes to the tables' sky exactly. Segment
// k ends at t_k = d (k/N)²: short near the camera, where the air is densest
// along rays that climb, and each ≤ 2d/N. The sum runs from the far end back
// to the camera, so that V̄(m_k) has the light arriving at m_k from straight
// behind — the segments beyond and the far half of segment k, eclipsed over
// daylight — for the aerosols' forward share (astro/moon_shadow.h): in
// totality the sunlit air far beyond the umbra, which lights the horizon
// (the ring 10° up, three eclipses: 3–13 % under the path tracer before,
// −6 to +8 % since; docs/validation.md, "Eclipses").
#include <array>

#include <glm/vec3.hpp>

#include "astro/moon_shadow.h"
#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"

namespace zenith::astro {

/// Segments along each ray.
inline constexpr int kEclipsedSkySegments = 24;

/// Radiance per unit solar irradiance [sr⁻¹] seen from `camera_m`
/// (planet-centred) along the unit `view`, the Sun toward
/// shadow.geometry().sun_direction, the sun's disc excluded; a camera outside
/// the atmosphere looks from where the ray enters it (as
/// TableQueries::sky_radiance).
atmosphere::Spectrum eclipsed_sky_radiance(const atmosphere::lut::TableQueries& tables,
                                           const atmosphere::AtmosphereModel& model, const MoonShadow& shadow,
                                           const glm::dvec3& camera_m, const glm::dvec3& view,
                                           int segments = kEclipsedSkySegments);

/// Which light arriving_light sums.
enum class ArrivingOrders {
  once_scattered,      ///< the single scattering and the direct sun the ground reflects
  multiply_scattered,  ///< the multiple scattering and the skylight the ground reflects
  all,                 ///< both
};

/// The light arriving at `point_m` (inside the atmosphere) from the
/// direction `direction` (travelling along −direction), with the shadow's V
/// and V̄ (eclipsed) and without (daylight): the single scattering along the
/// ray and, where it ends on the ground, the direct sun the ground reflects
/// (V); the multiple scattering (weighted by the shadow's V̄ so far) and the
/// skylight the ground reflects. For MoonShadow's V̄. Of the once-scattered
/// light, the gas's (Rayleigh's) part is also given apart: the only light
/// arriving polarized (across the plane of the Sun and the ray) in the
/// model's terms — the aerosols scatter the unpolarized sun unpolarized and
/// the ground reflects it so. The multiply scattered light's polarization,
/// which varies along the ray, is summed apart where asked for
/// (ArrivingPolarization).
struct ArrivingLight {
  std::array<double, atmosphere::lut::kMaxChannels> eclipsed{}, daylight{};
  std::array<double, atmosphere::lut::kMaxChannels> rayleigh_single_eclipsed{}, rayleigh_single_daylight{};
};
/// Of the multiply scattered light arriving eclipsed, Σ L (Π − 2N) along the
/// ray, in the shadow's basis: each segment's light times its excess
/// (MoonShadow::ScatteredLight). The skylight the ground reflects arrives
/// unpolarized.
struct ArrivingPolarization {
  std::array<ShadowTensor, atmosphere::lut::kMaxChannels> eclipsed{};
};
/// `multiple_polarization`, where given, has the multiply scattered light's
/// polarization added to it (the orders must include that light).
ArrivingLight arriving_light(const atmosphere::lut::TableQueries& tables, const atmosphere::AtmosphereModel& model,
                             const MoonShadow& shadow, const glm::dvec3& point_m, const glm::dvec3& direction,
                             int segments, ArrivingOrders orders,
                             ArrivingPolarization* multiple_polarization = nullptr);

}  // namespace zenith::astro
