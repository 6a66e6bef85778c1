#pragma once
// Mapping between the physical coordinates of the lookup tables and their
// texture coordinates (paper section 5.1, after Bruneton & Neyret 2008 and
// Bruneton 2017; Yusov 2013).
//
// Coordinates: r [m] distance from the planet centre, μ the cosine of the view
// zenith angle, μs the cosine of the sun zenith angle, ν the cosine of the angle
// between view and sun directions. rb, rt are the ground and top radii.
//
// Every mapping is derived from rb and rt only — no Earth-tuned constant:
//  * r is mapped through ρ = √(r² − rb²), the distance to the horizon, over
//    H = √(rt² − rb²), the horizon distance at the top: x_r = ρ/H;
//  * μ through the distance d to the boundary the ray hits (ground or top),
//    normalised between its extremes for that r, separately for rays that hit
//    the ground (lower half of the table) and rays that do not (upper half), so
//    the horizon falls exactly between two texels for every planet;
//  * μs down to μs_min = cos(90° + 3α) = −sin 3α (−1 when 3α ≥ 90°), with
//    α = acos(rb/rt): below that sun no point of any ray in the shell is lit,
//    whether the ray starts at the ground, at a high camera or where a ray from
//    space enters (ShellGeometry::min_sun_cosine), so clamping below it returns
//    the (vanishing) value at μs_min. Mapped by Bruneton's distance mapping for
//    single scattering and its average with a mapping uniform in angle for
//    multiple scattering (AngleMapping below);
//    OpenSpace clamps μ at −0.15, which cuts Mars' and Titan's horizons;
//  * ν uniform in the scattering angle.
// Texture coordinates keep samples at texel centres: u = ½/n + x (1 − 1/n).
#include <cstddef>

#include "atmosphere/lut/table_sizes.h"

namespace zenith::atmosphere::lut {

/// Shell geometry shared by all mappings.
struct ShellGeometry {
  double bottom_radius_m;
  double top_radius_m;

  double horizon_distance_at_top_m() const;     ///< H = √(rt² − rb²)
  double horizon_distance_m(double r_m) const;  ///< ρ = √(r² − rb²)
  double min_sun_cosine() const;                ///< μs_min = −sin 3α, α = acos(rb/rt) (≥ −1)
  double distance_to_top_m(double r_m, double mu) const;
  double distance_to_bottom_m(double r_m, double mu) const;
  bool ray_hits_ground(double r_m, double mu) const;
  /// Distance to the boundary the ray ends on (ground if it hits it, else top).
  double distance_to_nearest_boundary_m(double r_m, double mu, bool hits_ground) const;
};

/// Texel-centre mapping: [0, 1] ↔ [½/n, 1 − ½/n].
double texture_coord_from_unit(double x, std::size_t n);
double unit_from_texture_coord(double u, std::size_t n);

// ---- transmittance T(r, μ) to the top, rays that do not hit the ground
struct TransmittanceUV {
  double u_mu, v_r;
};
TransmittanceUV transmittance_uv(const ShellGeometry& g, const TableSizes& s, double r_m, double mu);
void transmittance_r_mu(const ShellGeometry& g, const TableSizes& s, double u_mu, double v_r, double* r_m, double* mu);

// ---- irradiance E(r, μs)
struct IrradianceUV {
  double u_mu_s, v_r;
};
IrradianceUV irradiance_uv(const ShellGeometry& g, const TableSizes& s, double r_m, double mu_s);
void irradiance_r_mu_s(const ShellGeometry& g, const TableSizes& s, double u_mu_s, double v_r, double* r_m,
                       double* mu_s);

/// How the view angle μ (rays that do not hit the ground) and the sun angle μs
/// are mapped in a 4D table.
///  * Distance (Bruneton): texels spaced in the distance to the boundary; most of
///    them near the horizon and through twilight, where single scattering varies
///    fastest. From the ground, the whole sky from the zenith to 70° gets 1/8 of
///    the μ texels and the top 40° of sun elevation 1/30 of the μs texels.
///  * Blended: the average of that mapping and one uniform in angle (zenith to
///    horizon for μ, zenith to μs_min for μs). Multiple scattering with a
///    forward-peaked aerosol phase baked in varies sharply with the angle between
///    view and sun everywhere in the sky (the aureole of the higher orders); with
///    the distance mapping alone, interpolation across 40°-wide texels put Mars'
///    and hazy Earth's order-2 sky 2–3× off. Used by the multiple-scattering
///    tables; the single-scattering tables keep Distance.
enum class AngleMapping { Distance, Blended };

// ---- scattering S(r, μ, μs, ν), 4D packed into 3D:
// x = ν index · mu_s_size + μs, y = μ, z = r (ν is interpolated by hand).
struct ScatteringUVWZ {
  double u_nu;    ///< [0, 1], linear in the azimuth between view and sun (scattering_u_nu)
  double u_mu_s;  ///< [0, 1], texel-centred
  double u_mu;    ///< [0, 1]; < 0.5 for rays that hit the ground
  double u_r;     ///< [0, 1], texel-centred
};
ScatteringUVWZ scattering_uvwz(const ShellGeometry& g, const TableSizes& s, double r_m, double mu, double mu_s,
                               double nu, bool ray_hits_ground, AngleMapping mapping);
/// The μs and ν parts of scattering_uvwz alone (equal to its u_mu_s and u_nu),
/// for integrators that compute the r and μ parts once per ray.
double scattering_u_mu_s(const ShellGeometry& g, const TableSizes& s, double mu_s, AngleMapping mapping);
/// u_ν = φ/π, φ ∈ [0, π] the azimuth between the view and the sun:
/// ν = μ μs + √((1 − μ²)(1 − μs²)) cos φ. 0 where that root is below kNuSpreadMin
/// (view or sun at the zenith, where ν = μ μs whatever the azimuth).
double scattering_u_nu(double mu, double mu_s, double nu);
/// ν at u_ν = x for this μ and μs (the inverse of scattering_u_nu).
double scattering_nu_from_unit(double mu, double mu_s, double x);
constexpr double kNuSpreadMin = 1e-9;

struct ScatteringCoordinates {
  double r_m, mu, mu_s, nu;
  bool ray_hits_ground;
};
/// Physical coordinates at the centre of texel (x, y, z) of the packed 3D table.
ScatteringCoordinates scattering_texel_coordinates(const ShellGeometry& g, const TableSizes& s, std::size_t x,
                                                   std::size_t y, std::size_t z, AngleMapping mapping);

}  // namespace zenith::atmosphere::lut
