#pragma once
// The Moon's shadow on the air during a solar eclipse (docs/validation.md,
// "Eclipses"): for any point of the air, the share of the Sun's light that
// still reaches it directly, and the share of the light that reaches it after
// more than one scattering.
//
// Direct light, V(p, λ). A point p sees the Moon's centre m at the angle
//   σ(p) = atan2(|w⊥|, w·s)   from the Sun's centre,  w = m − p,  w⊥ = w − (w·s) s,
// with s the unit vector toward the Sun, and the Moon's disc at the radius
// r_m(p) = asin(R_m / |w|); the Sun's radius r_s is the same everywhere.
//   V(p, λ) = 1 − limb_darkened_obscuration(σ, r_s, r_m, I_λ)
// (astro/solar_eclipse.h; I_λ the Sun's limb darkening, atmosphere/solar_limb_darkening.h). Across
// the air a camera can see (≲ 2 000 km) |w| changes by < 0.6 %, so V is
// tabulated once, at the camera's Moon radius r_m0, over the distance of the
// Moon's limb from the Sun's centre, x(p) = σ(p) − (r_m(p) − r_m0): near the
// contacts, where V changes fastest, the covered light depends on where the
// limbs meet, which x keeps exact (the umbra's cone narrows by r_s per metre
// along the axis, 4.7 km over 1 000 km).
//
// Scattered light, V̄(p, v, λ). In totality no sunlight reaches the air over
// the observer; the sky there is lit by light first scattered in the sunlit
// air outside the umbra, tens to hundreds of kilometres away. The multiple
// scattering that p sends along v is taken as the tables' (the uneclipsed
// sky's) times V̄(p, v), the share the Moon leaves of the light arriving at p,
// each direction weighted as p scatters it along v:
//   V̄(p, v) = ∫ P(ω·v) L_ecl(p, ω) dω / ∫ P(ω·v) L(p, ω) dω,
// L the light arriving at p from direction ω, computed from the tables along
// rays over a Fibonacci sphere (astro/eclipsed_sky.h, arriving_light): first
// the single scattering and the sunlit ground (V̄ the second order's share),
// then with the multiply scattered light under that V̄ added, the share of
// every order (MoonShadowOptions::iterations). P is the phase
// function of the air at p, Rayleigh's and the aerosols' by their scattering
// coefficients there, to its Legendre terms l ≤ 4 (Rayleigh's, l ≤ 2, exact):
//   ∫ P(ω·v) L dω = (1/4π) [a + 3 k₁ m·v + 5 k₂ (3 vᵀMv − a)/2
//                           + 4π Σ_{l=3,4} k_l Σ_m Y_lm(v) c_lm],
//   a = ∫ L dω,  m = ∫ L ω dω,  M = ∫ L ωωᵀ dω,  c_lm = ∫ L Y_lm dω,
// Y_lm the real spherical harmonics (core/spherical_harmonics.h: the addition
// theorem), so a node keeps a, m, M and the 7 + 9 coefficients c of l = 3, 4
// of the eclipsed light and all but a of the daylight, per unit a of
// daylight. An aerosol's forward peak is split off by delta-M (Wiscombe 1977,
// J. Atmos. Sci. 34, 1408): its share f = k₅ goes straight on, weighting the
// light from straight behind, and the rest has k_l' = (k_l − f)/(1 − f); each
// part is clipped at 0. The l ≤ 4 terms are still k_l, so where neither part
// is negative nothing changes; but the phase function of g = 0.85 cut at
// l ≤ 2 goes negative sideways (1 − 5g²/2 = −0.81 of isotropic at 90°, where
// Henyey–Greenstein has 0.123, delta-M at l ≤ 2 0.115 and at l ≤ 4 0.126),
// and that is where the zenith's air in totality scatters the light from
// around the umbra: clipped, the aerosols scattered none of it. The light
// from straight behind, along a camera's view ray, is that ray's own beyond
// the point (astro/eclipsed_sky.h: its share left, `behind_left`, times the
// daylight's L(v) below); elsewhere — the nodes' own rays — it is taken to
// l ≤ 2, L(v) = a + 3 m·v + 5 (3 vᵀMv − a)/2. In totality the light
// arriving at the air is a bright band low on its horizon: its terms l ≤ 2
// smear the band into the dark sky around it (low in the umbra, along a ray
// 10° up, V̄ 0.6–0.7 of the phase functions' own weighting, 0.75–0.9 with
// the ray's own light: tests/astro/eclipsed_sky_test.cpp), and its terms
// l ≤ 4 put light where the band is not — straight above the zenith's air
// (Lowman's mid-totality zenith then 24 % over the path tracer at 680 nm;
// docs/validation.md, "Eclipses"). With the nodes, rays and segments
// refined and four passes (nearer the method's limit) the scalar totality
// zenith of 2017 lay 9 % under the path tracer at 680 nm and 7 % over it at
// 440 nm with the terms l ≤ 2 and no delta-M; with delta-M 8 % over at both.
//
// The light's polarization. The gas's once-scattered light arriving at p is
// polarized across the plane of the Sun and its ray (94.6 % at 90° for air),
// and the gas at p, a dipole (atmosphere/rayleigh_polarization.h, eq. 1),
// scatters it along v by how much of its field lies across v: in totality the
// zenith's air is lit sideways and turns that light up by about 90°, where
// the scalar average misses most (docs/validation.md, "Eclipses": 7–10 % of
// the 430/680 nm ratio at the zenith in the 1970 study). With T the
// arriving light's coherency tensor (tr T = L), eq. (1) weights it by
// (1 + Δ/2) tr T − (3Δ/2) vᵀTv; the gas's once-scattered light has
// T = L₁ N(ω), N its eq. (1) shape of trace 1, the aerosols' scattering of
// the unpolarized sun and the ground's light T = L Π(ω)/2 (the multiply
// scattered light: below). So against the scalar weight the gas's gains
//   (3Δ/4) vᵀ P v,   P = ∫ L₁ (Π(ω) − 2 N(ω)) dω   (traceless, 0 for unpolarized light),
// added to its l ≤ 2 weight above; Δ = (1 − ρ)/(1 + ρ/2) the dipole's share of
// the gas's scattering. A node keeps P of the eclipsed light and of the
// daylight too: 63 numbers per wavelength.
// The multiply scattered light is polarized too: in totality it is the light
// that lights the zenith's air, and three quarters of it at 440 nm has been
// scattered three times or more. The coherency arriving at a node, summed over
// its rays, is 𝒯 = (a·1 − M − P)/2 (unpolarized light gives (aI − M)/2, the
// gas's once-scattered light L₁ N less L₁ (Π − 2N)/2), so the gas there
// scatters toward the next point the coherency eq. (1) of 𝒯. From the second
// pass on, P also sums the multiply scattered light's L (Π(ω) − 2 N(ω)) along
// each ray, weighted by the gas's share of what the air there scatters
// (MoonShadow::ScatteredLight; the aerosols scatter as if unpolarized), N from
// the coherency of all the light arriving at each point of the ray: the
// once-scattered light's, polarized, and the multiply scattered light's
// under the V̄ before, taken as unpolarized — a scalar pass before each
// (MoonShadowOptions::coherency_directions). The pass before alone would give
// all the multiply scattered light the second order's polarization, which
// each further scattering spends (the path tracer split by order,
// docs/validation.md: order 3 keeps a third to a half of order 2's gain,
// orders ≥ 4 little).
// The tables' multiple scattering stays scalar (by day its error is under 1 %
// at the zenith), so V̄ takes it to the vector transfer's eclipsed light: it
// divides the eclipsed light, weighted with its polarization, by the
// daylight weighted as scalar transfer weighs it — the tables' own. (Over
// the daylight weighted with its polarization V̄ would be the vector
// transfer's share, which takes the daylight's own gain off the tables'
// scalar light: at mid-totality 2017 from Hopkinsville, 10, 16 and 22 % of
// the twice-scattered zenith at 680, 550 and 440 nm, docs/validation.md.)
// So in the partial phases too V̄ gives the vector transfer's light, V times
// the daylight's own gain (at most 1) rather than V: the air the shadow
// reaches is vector transfer's, the day sky beyond it the tables'. The
// daylight's P is the build's: it gives the light beyond the shadow its
// polarization; the sky reads the first 57 numbers (kShadowSkyValues).
// The nodes lie over (q·e1, |q·e2|, altitude), q the offset of p from the
// axis and e1 the direction from the axis toward the planet's centre (the
// planet and the shadow are mirror images of themselves across the plane of
// the axis and e1: a point with q·e2 < 0 reads its mirror image's node with v
// mirrored), crowded toward the axis. Beyond the penumbra V = 1 and V̄ eases
// from the edge nodes' value to 1 over one more penumbra radius (smoothstep),
// so the shadow's first touch on the air a camera sees is no jump.
// docs/validation.md ("Eclipses") holds V̄ against the path tracer.
//
// Both tables depend on the eclipse only through r_s, r_m0, the wavelengths
// and where the axis passes the planet — its distance b from the planet's
// centre, as the zenith angle asin(b/R) of the Sun where the axis meets the
// ground: the planet is a sphere, so the air around the axis is the same
// wherever along the planet the shadow falls for the same b. A moving shadow
// reads the same tables while these hold (MoonShadow::still_fits).
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <stdexcept>
#include <stop_token>
#include <vector>

#include <glm/vec3.hpp>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/solar_limb_darkening.h"

namespace zenith::astro {

enum class ArrivingOrders;  // astro/eclipsed_sky.h

/// The Moon and the Sun of a solar eclipse, in a planet's frame (planet-centred, metres).
struct EclipseGeometry {
  glm::dvec3 moon_centre_m{0.0};
  double moon_radius_m = 0.0;
  glm::dvec3 sun_direction{0.0, 0.0, 1.0};  ///< unit, toward the Sun
  double sun_angular_radius_rad = 0.0;
  /// The Sun's limb darkening per wavelength of the model
  /// (atmosphere::solar_limb_darkening; all uniform: a uniform disc).
  std::vector<atmosphere::LimbDarkening> limb_darkening;
};

/// The tables' sizes and the rays behind V̄.
struct MoonShadowOptions {
  std::size_t profile_samples = 1024;  ///< V over x ∈ [0, r_s + r_m0]
  std::size_t field_across = 33;       ///< V̄ nodes along e1, −end … end
  std::size_t field_side = 17;         ///< V̄ nodes along e2, 0 … end
  /// V̄'s altitudes [m], increasing from 0.
  std::vector<double> field_altitudes_m = {0.0, 0.5e3, 1e3, 1.5e3, 2.5e3, 4e3, 6e3, 9e3, 13e3, 19e3, 28e3, 40e3, 60e3};
  /// Rays per V̄ node for the once-scattered light, a Fibonacci sphere in the
  /// node's own frame (its up, the sun's azimuth there): converged at 64
  /// (mid-totality 2017, 550 nm, one pass, small tables: the zenith −7.7 % of
  /// the path tracer with 64 rays, −8.8 % with 128, −11.2 % with 32).
  std::size_t directions = 64;
  /// Rays per node for the multiply scattered light (passes after the first),
  /// which comes from all around: at mid-totality 2017 (paper tables) 32 rays
  /// give the zenith within 1 % and the sky 10° up within 5 % of 64 rays (16: 11 %).
  std::size_t higher_order_directions = 32;
  /// Rays per node for the scalar pass before each later polarized one, which
  /// gives the coherency arriving at each point the multiply scattered light
  /// (the header): 8 give the mid-totality zenith of 2017 from Hopkinsville
  /// within 0.2 % of 32 at 680, 550 and 440 nm (paper tables), for 1 s of the
  /// build instead of 2.5 s on 2 cores.
  std::size_t coherency_directions = 8;
  int segments = 12;  ///< segments per ray
  /// 1: V̄ from the once-scattered light, given to every order. Each more
  /// pass adds to the light arriving at p the multiply scattered light under
  /// the V̄ before, so the higher orders — which come from farther, where more
  /// of the Sun is left, and make two thirds to three quarters of the totality
  /// sky at 440 nm — get their own share. At mid-totality on 2017-08-21, paper
  /// tables, against the path tracer (`zenith validate eclipse`): the zenith
  /// −16, −9, −3 % at 680, 550, 440 nm with two passes (1 M paths, σ 6–9 %),
  /// −27, −40, −44 % with one (400 000 paths). The small tables (8 radii)
  /// find 1.45× the paper tables' light in totality already with one pass,
  /// and two passes carry it on (+127, +36, +70 %): the eclipsed sky needs
  /// the paper tables (docs/validation.md, "Eclipses").
  int iterations = 2;
  /// Whether V̄ weights the gas's once-scattered light by its polarization (the
  /// header): as the path tracer's vector transfer (`--polarized`) does. Off:
  /// the scalar transfer of the tables and the scalar path tracer.
  bool polarized = true;
  unsigned threads = 0;  ///< 0: all
};

/// A symmetric tensor in the shadow's basis (e1, e2, s): xx, yy, zz, xy, xz, yz.
using ShadowTensor = std::array<double, 6>;

/// Numbers per node and wavelength of V̄'s table: a_e, m_e, M_e, m_d, M_d, P_e,
/// c_e, c_d, P_d, in the basis (e1, e2, s), m as x, y, z and M, P as xx, yy,
/// zz, xy, xz, yz, c the harmonics' coefficients (kShadowHigherMoments).
inline constexpr std::size_t kShadowFieldValues = 63;
/// The first of them, which V̄ reads (P_d only gives the light beyond the
/// shadow its polarization while the table is made).
inline constexpr std::size_t kShadowSkyValues = 57;
/// The light arriving at a node by its real spherical harmonics of degree 3
/// and 4, c_lm = ∫ L Y_lm dω in core::spherical_harmonics_3_4's order (Y_3,−3
/// … Y_3,3, Y_4,−4 … Y_4,4; shadow_harmonics in shaders/render/moon_shadow.glsl
/// the same).
inline constexpr std::size_t kShadowHigherMoments = 16;
/// Sums per node and wavelength while V̄'s table is made: L, L ω and L ωωᵀ
/// (10 numbers) of the eclipsed light, then of the daylight; then P's
/// integrand, L (Π(ω) − 2 N(ω)) (6), eclipsed and in daylight: of the gas's
/// once-scattered light and, from the second pass on, of the multiply
/// scattered light eclipsed (the daylight's stays the once-scattered light's,
/// as the coherency pass takes the multiply scattered light); then the
/// harmonics' coefficients (kShadowHigherMoments), eclipsed and in daylight.
inline constexpr std::size_t kLightSums = 64;

/// Thrown by MoonShadow's constructor when its `stop` was requested: a build
/// on a worker thread whose shadow no frame will use (the renderer going away).
class ShadowBuildStopped : public std::runtime_error {
 public:
  ShadowBuildStopped() : std::runtime_error("the Moon's shadow: build stopped") {}
};

class MoonShadow {
 public:
  /// For a sky seen from `camera_m` (planet-centred) at `model`'s wavelengths.
  /// Throws std::invalid_argument for a non-finite geometry, a Moon radius or
  /// Sun radius ≤ 0, a non-unit Sun direction, a camera inside the Moon or
  /// a limb darkening law not one per wavelength or invalid, or options out of range;
  /// ShadowBuildStopped soon after `stop` is requested (each V̄ node checks it:
  /// a millisecond or two of work, where a whole build takes seconds).
  MoonShadow(const EclipseGeometry& geometry, const atmosphere::lut::TableQueries& tables,
             const atmosphere::AtmosphereModel& model, const glm::dvec3& camera_m,
             const MoonShadowOptions& options = {}, std::stop_token stop = {});

  /// V(p, λ_i): the share of the Sun's limb-darkened light that reaches p directly.
  double direct_light(const glm::dvec3& point_m, std::size_t wavelength) const;
  /// V̄(p, v, λ_i): the share of the multiple scattering left that the air at
  /// p sends along v (unit; the light travels along −v, toward where v starts).
  double scattered_light(const glm::dvec3& point_m, const glm::dvec3& direction, std::size_t wavelength) const;
  /// The share of the skylight left on a horizontal surface of the ground at `ground_m`.
  double skylight_left(const glm::dvec3& ground_m, std::size_t wavelength) const;

  /// The place of a point relative to the shadow: the distance of the Moon's
  /// limb from the Sun's centre x [rad] (> profile_end_rad(): V = 1; no Moon
  /// ahead of the point: +∞), its offset q from the axis, q·e1 and q·e2 [m],
  /// and its altitude [m].
  struct Place {
    double limb_rad;
    double across_m[2];
    double altitude_m;
  };
  Place place(const glm::dvec3& point_m) const;
  /// direct_light and scattered_light at a point already placed (every
  /// wavelength of a point shares its place).
  double direct_light(const Place& place, std::size_t wavelength) const;
  /// `behind_left`, where the caller knows it, is the share the Moon leaves of
  /// the light arriving from straight behind (along v from beyond the point):
  /// the aerosols' forward share scatters that light on (the header); without
  /// it, that light is the node's terms l ≤ 2.
  double scattered_light(const Place& place, const glm::dvec3& direction, std::size_t wavelength,
                         std::optional<double> behind_left = std::nullopt) const;

  /// V̄ at a point and the polarization of the light its air scatters along v,
  /// eclipsed: per unit of that light, the gas's share of Π(v) − 2N, N the
  /// unit coherency the gas scatters by eq. (1) from the coherency arriving
  /// there, (a·1 − M − P)/2 from the field (while the table is made, from
  /// the coherency pass's: the header). Zero where the shadow is not polarized.
  struct ScatteredLight {
    double share_left = 1.0;
    ShadowTensor excess{};
  };
  ScatteredLight polarized_scattered_light(const Place& place, const glm::dvec3& direction, std::size_t wavelength,
                                           std::optional<double> behind_left = std::nullopt) const;

  /// The same shadow with `geometry` seen from `camera_m`: whether the tables
  /// still hold (the same limb darkening, r_m0 and r_s within 1e-3 relative,
  /// the axis' zenith angle within 0.3°). The caller then moves this one (move_to).
  bool still_fits(const EclipseGeometry& geometry, const glm::dvec3& camera_m) const;
  /// Takes the new geometry and camera keeping the tables (after still_fits).
  void move_to(const EclipseGeometry& geometry, const glm::dvec3& camera_m);

  // The tables. V at x_k = profile_end_rad() k / (n − 1), wavelength fastest.
  // V̄'s kShadowFieldValues per wavelength (fastest), wavelengths, then nodes:
  // q·e1 = end t|t|, t = −1 + 2j / (field_across − 1), fastest; |q·e2| = end t²,
  // t = k / (field_side − 1); the altitudes.
  const std::vector<float>& profile() const { return profile_; }
  const std::vector<float>& field() const { return field_; }
  const MoonShadowOptions& options() const { return options_; }
  double profile_end_rad() const { return profile_end_rad_; }
  double field_end_m() const { return field_end_m_; }
  std::size_t wavelengths() const { return wavelengths_; }
  const EclipseGeometry& geometry() const { return geometry_; }
  /// The shadow plane's axes: e1 from the axis toward the planet's centre, e2 = s × e1.
  const glm::dvec3& axis_1() const { return e1_; }
  const glm::dvec3& axis_2() const { return e2_; }
  double camera_moon_radius_rad() const { return moon_radius_0_rad_; }

  /// What scatters at a point: its scattering coefficient [m⁻¹], its phase
  /// function's Legendre k₁, k₂ (P = (1/4π) Σ (2l+1) k_l P_l) past its
  /// forward share (delta-M: the header), the weight of the arriving light's
  /// polarization P, 3Δ/4 for the gas (the header), 0 for what scatters all
  /// polarizations alike, the forward share f and the Legendre k₃, k₄ past it.
  struct Scatterer {
    double scattering_m1, k1, k2, dipole = 0.0, forward = 0.0, k3 = 0.0, k4 = 0.0;
  };
  /// The air's Rayleigh and aerosol scatterers at reference density, per wavelength.
  const std::vector<Scatterer>& rayleigh_scatterers() const { return rayleigh_; }
  const std::vector<Scatterer>& mie_scatterers() const { return mie_; }

 private:
  double profile_at(double limb_rad, std::size_t wavelength) const;
  /// The field's values at a place, the fade from the nodes' edge to daylight
  /// (1 beyond it) and v in the field's basis (mirrored where q·e2 < 0).
  struct FieldSample {
    double values[kShadowFieldValues] = {};
    double fade = 1.0;
    double v[3] = {};
    std::array<double, kShadowHigherMoments> harmonics{};  ///< of v: core::spherical_harmonics_3_4
    bool mirrored = false;
  };
  FieldSample field_at(const std::vector<float>& table, const Place& place, const glm::dvec3& direction,
                       std::size_t wavelength) const;
  /// The air's scatterers at a place: Rayleigh's and the aerosols'.
  std::array<Scatterer, 2> air_at(const Place& place, std::size_t wavelength) const;
  /// The point's distance from the axis in units of the field's end.
  double reach(const Place& place) const;
  /// V̄ from the field at a place for light scattered along its direction by `scatterers`.
  static double share_left(const FieldSample& field, std::span<const Scatterer> scatterers,
                           std::optional<double> behind_left);
  void set_frame(const glm::dvec3& camera_m);
  void fill_profile();
  void fill_field(const atmosphere::lut::TableQueries& tables, const atmosphere::AtmosphereModel& model,
                  const std::stop_token& stop);
  /// One pass over the nodes: the sums of the light of `orders` arriving
  /// at each (under this shadow's field so far), eclipsed and in daylight,
  /// of 1, ω and ωωᵀ, and with `polarization` of its P (kLightSums per
  /// wavelength, wavelengths, nodes), over `ray_count` rays per node.
  std::vector<double> light_sums(const atmosphere::lut::TableQueries& tables, const atmosphere::AtmosphereModel& model,
                                 ArrivingOrders orders, std::size_t ray_count, bool polarization,
                                 const std::stop_token& stop) const;
  /// V̄'s table from such sums.
  std::vector<float> field_from(const std::vector<double>& sums) const;

  EclipseGeometry geometry_;
  MoonShadowOptions options_;
  std::size_t wavelengths_ = 0;
  /// The zenith angle of the Sun where the axis meets the ground, asin(b/R), b
  /// the axis' distance from the planet's centre (past the edge π/2 + b/R − 1).
  double axis_zenith_rad(const EclipseGeometry& geometry) const;

  double moon_radius_0_rad_ = 0.0, axis_zenith_0_rad_ = 0.0, moon_distance_0_m_ = 0.0, ground_radius_m_ = 0.0;
  double profile_end_rad_ = 0.0, field_end_m_ = 0.0;
  glm::dvec3 e1_{1.0, 0.0, 0.0}, e2_{0.0, 1.0, 0.0};
  std::vector<float> profile_, field_;
  /// While a polarized pass runs: the field of the coherency arriving with
  /// the multiply scattered light in it (the header), which the light's
  /// polarization is read from. Empty otherwise.
  std::vector<float> coherency_;
  /// The air's scatterers at reference density per wavelength, and their density profiles.
  std::vector<Scatterer> rayleigh_, mie_;
  double dipole_share_ = 1.0;  ///< Δ of the gas
  atmosphere::DensityProfile rayleigh_density_, mie_density_;
};

}  // namespace zenith::astro
