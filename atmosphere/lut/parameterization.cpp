#include "atmosphere/lut/parameterization.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "atmosphere/constants.h"

namespace zenith::atmosphere::lut {

namespace {

/// r from ρ, the inverse of horizon_distance: exactly rb at ρ = 0 (what a
/// correctly rounded sqrt gives; the shaders spell it out for GPUs whose fp64
/// sqrt is not correctly rounded, atmosphere_common.glsl), and at most rt: at
/// ρ = H a sqrt 1 ulp high gave r = rt + 1 ulp, so d_min = rt − r < 0 and the
/// μ = 1 ray of the top row came out μ ≈ 0 (transmittance_r_mu, mu_sky_from_unit).
double radius_from_horizon_distance(const ShellGeometry& g, double rho) {
  if (rho == 0.0) return g.bottom_radius_m;
  return std::min(std::sqrt(rho * rho + g.bottom_radius_m * g.bottom_radius_m), g.top_radius_m);
}

double clamp_cosine(double mu) { return std::clamp(mu, -1.0, 1.0); }
double safe_sqrt(double a) { return std::sqrt(std::max(a, 0.0)); }

/// a² − b² as (a − b)(a + b). Near the ground r² − rb² cancels: 1 m above
/// Mars' ground it is 6 ulp of r² in float (r² − rb² = 6.8e6 m², one ulp of
/// r² = 1.05e6 m²), and a discriminant r²μ² − r² + rb² that should be 0 at
/// the horizon comes out anywhere in ±1e6 m², i.e. ±1000 m of distance to the
/// ground out of 2600 m (u_μ off by 0.2 in the fp32 shaders). r − rb is exact
/// (Sterbenz: r within a factor 2 of rb), so the product keeps the precision
/// of its factors: ±1 m² there, ±1 m of distance. The shaders compute the same.
double difference_of_squares(double a, double b) { return (a - b) * (a + b); }
}  // namespace

void TableSizes::check() const {
  auto in = [](std::size_t v, std::size_t lo, std::size_t hi, const char* name) {
    if (v < lo || v > hi) {
      std::ostringstream m;
      m << "table size " << name << " = " << v << ": must be in [" << lo << ", " << hi << "]";
      throw std::invalid_argument(m.str());
    }
  };
  in(transmittance_mu, 4, 4096, "transmittance_mu");
  in(transmittance_r, 4, 4096, "transmittance_r");
  in(irradiance_mu_s, 4, 4096, "irradiance_mu_s");
  in(irradiance_r, 4, 4096, "irradiance_r");
  in(scattering_r, 4, 512, "scattering_r");
  in(scattering_mu, 8, 1024, "scattering_mu");
  in(scattering_mu_s, 4, 512, "scattering_mu_s");
  in(scattering_nu, 2, 256, "scattering_nu");
  if (scattering_mu % 2 != 0) throw std::invalid_argument("table size scattering_mu must be even");
}

std::string TableSizes::describe() const {
  std::ostringstream out;  // (GCC 12 warns falsely on chained std::string +)
  out << 'T' << transmittance_mu << 'x' << transmittance_r << " E" << irradiance_mu_s << 'x' << irradiance_r << " S"
      << scattering_r << 'x' << scattering_mu << 'x' << scattering_mu_s << 'x' << scattering_nu;
  return out.str();
}

TableSizes TableSizes::small() { return TableSizes{64, 16, 32, 8, 8, 32, 32, 8}; }

double ShellGeometry::horizon_distance_at_top_m() const {
  return safe_sqrt(difference_of_squares(top_radius_m, bottom_radius_m));
}

double ShellGeometry::horizon_distance_m(double r_m) const {
  return safe_sqrt(difference_of_squares(r_m, bottom_radius_m));
}

double ShellGeometry::min_sun_cosine() const {
  // The lowest sun at which any point of any ray in the shell can be sunlit.
  // Let α = acos(rb/rt), the dip of the horizon seen from the top. Along a ray
  // inside the shell, the angle at the planet's centre between its start x (at
  // r) and any later point y is at most acos(r_p/r) + acos(r_p/rt) ≤ 2α (r_p ≥ rb
  // its closest approach, or the ground point it hits), so y's sun zenith is at
  // least θs(x) − 2α; and y (at r_y ≤ rt) sees the sun above its horizon only if
  // its sun zenith is below 90° + acos(rb/r_y) ≤ 90° + α. For θs(x) > 90° + 3α
  // no point of the ray is lit: single scattering is exactly 0 (the higher
  // orders may carry light scattered up to 2α further toward the sun, but it is
  // negligible: ≤ 1.3e-7 sr^-1 on dusty Mars, docs/lookup-tables.md). The bound
  // is reached (x and y at the top, the ray grazing the ground), so the tables
  // must cover μs down to cos(90° + 3α) and may clamp below it. With sin α = H/rt:
  //   μs_min = −sin 3α = −(3 sin α − 4 sin³α)   for 3α < 90° (sin α < ½),
  //   μs_min = −1                               otherwise (Titan: α = 35.8°).
  // (The former μs_min = −H/rt = cos(90° + α) covered only rays from the
  // ground; high cameras and rays entering from space were clamped to lit values.)
  const double s = horizon_distance_at_top_m() / top_radius_m;
  return s >= 0.5 ? -1.0 : -(3.0 * s - 4.0 * s * s * s);
}

double ShellGeometry::distance_to_top_m(double r_m, double mu) const {
  // Solve |x + d v| = rt: d = −rμ + √(r²μ² − (r² − rt²)).
  const double r_mu = r_m * mu;
  const double disc = r_mu * r_mu - difference_of_squares(r_m, top_radius_m);
  return std::max(0.0, -r_mu + safe_sqrt(disc));
}

double ShellGeometry::distance_to_bottom_m(double r_m, double mu) const {
  const double r_mu = r_m * mu;
  const double disc = r_mu * r_mu - difference_of_squares(r_m, bottom_radius_m);
  return std::max(0.0, -r_mu - safe_sqrt(disc));
}

bool ShellGeometry::ray_hits_ground(double r_m, double mu) const {
  const double r_mu = r_m * mu;
  return mu < 0.0 && r_mu * r_mu - difference_of_squares(r_m, bottom_radius_m) >= 0.0;
}

double ShellGeometry::distance_to_nearest_boundary_m(double r_m, double mu, bool hits_ground) const {
  return hits_ground ? distance_to_bottom_m(r_m, mu) : distance_to_top_m(r_m, mu);
}

double texture_coord_from_unit(double x, std::size_t n) { return 0.5 / double(n) + x * (1.0 - 1.0 / double(n)); }
double unit_from_texture_coord(double u, std::size_t n) { return (u - 0.5 / double(n)) / (1.0 - 1.0 / double(n)); }

TransmittanceUV transmittance_uv(const ShellGeometry& g, const TableSizes& s, double r_m, double mu) {
  const double H = g.horizon_distance_at_top_m();
  const double rho = g.horizon_distance_m(r_m);
  const double d = g.distance_to_top_m(r_m, mu);
  const double d_min = g.top_radius_m - r_m, d_max = rho + H;
  const double x_mu = d_max > d_min ? (d - d_min) / (d_max - d_min) : 0.0;
  return {texture_coord_from_unit(std::clamp(x_mu, 0.0, 1.0), s.transmittance_mu),
          texture_coord_from_unit(std::clamp(rho / H, 0.0, 1.0), s.transmittance_r)};
}

void transmittance_r_mu(const ShellGeometry& g, const TableSizes& s, double u_mu, double v_r, double* r_m, double* mu) {
  const double H = g.horizon_distance_at_top_m();
  const double rho = H * unit_from_texture_coord(v_r, s.transmittance_r);
  const double r = radius_from_horizon_distance(g, rho);
  const double d_min = g.top_radius_m - r, d_max = rho + H;
  const double d = d_min + unit_from_texture_coord(u_mu, s.transmittance_mu) * (d_max - d_min);
  // Law of cosines in the triangle (centre, x, exit point): rt² = r² + d² + 2 r d μ.
  *r_m = r;
  *mu = d == 0.0 ? 1.0 : clamp_cosine((H * H - rho * rho - d * d) / (2.0 * r * d));
}

IrradianceUV irradiance_uv(const ShellGeometry& g, const TableSizes& s, double r_m, double mu_s) {
  const double x_r = (r_m - g.bottom_radius_m) / (g.top_radius_m - g.bottom_radius_m);
  return {texture_coord_from_unit(std::clamp(0.5 * mu_s + 0.5, 0.0, 1.0), s.irradiance_mu_s),
          texture_coord_from_unit(std::clamp(x_r, 0.0, 1.0), s.irradiance_r)};
}

void irradiance_r_mu_s(const ShellGeometry& g, const TableSizes& s, double u_mu_s, double v_r, double* r_m,
                       double* mu_s) {
  *r_m = g.bottom_radius_m + unit_from_texture_coord(v_r, s.irradiance_r) * (g.top_radius_m - g.bottom_radius_m);
  *mu_s = clamp_cosine(2.0 * unit_from_texture_coord(u_mu_s, s.irradiance_mu_s) - 1.0);
}

namespace {

/// Bruneton's μs ↔ [0, 1]: a = normalised distance to the top from the ground
/// toward the sun; x = max(1 − a/A, 0)/(1 + a) with A the value of a at μs_min.
/// x = 1 at the zenith, 0 at μs_min and below; most resolution near the horizon.
/// (Below the horizon the "distance" is that of the line through the planet,
/// −rb μs + √(rb² μs² − rb² + rt²), still monotone down to μs = −1.)
double distance_mapping_mu_s(const ShellGeometry& g, double mu_s) {
  const double rb = g.bottom_radius_m;
  const double d_min = g.top_radius_m - rb, d_max = g.horizon_distance_at_top_m();
  const double a = (g.distance_to_top_m(rb, mu_s) - d_min) / (d_max - d_min);
  const double A = (g.distance_to_top_m(rb, g.min_sun_cosine()) - d_min) / (d_max - d_min);
  return std::max(1.0 - a / A, 0.0) / (1.0 + a);
}

/// μs ↔ [0, 1] for a table. Blended: the average of the distance mapping (fine
/// steps through twilight) and a mapping uniform in the sun's zenith angle down
/// to μs_min. The distance mapping alone spends one texel in 32 on the top 40°
/// of sun elevation; multiple scattering with a forward-peaked aerosol phase
/// varies sharply there (the second order's aureole follows the sun) and linear
/// interpolation across 40° inflated Earth's hazy zenith sky 3×. The blend keeps
/// half the twilight resolution and gives ≤ 2·θs_max/n per texel everywhere.
double unit_from_mu_s(const ShellGeometry& g, double mu_s, AngleMapping mapping) {
  if (mapping == AngleMapping::Distance) return distance_mapping_mu_s(g, mu_s);
  const double theta_max = std::acos(g.min_sun_cosine());
  const double theta = std::acos(std::clamp(mu_s, -1.0, 1.0));
  const double uniform = std::max(0.0, 1.0 - theta / theta_max);
  return 0.5 * distance_mapping_mu_s(g, mu_s) + 0.5 * uniform;
}

/// Inverse of unit_from_mu_s (monotone in μs) by bisection on μs ∈ [μs_min, 1].
double mu_s_from_unit(const ShellGeometry& g, double x, AngleMapping mapping) {
  double lo = g.min_sun_cosine(), hi = 1.0;
  if (x <= 0.0) return lo;
  if (x >= 1.0) return 1.0;
  for (int i = 0; i < 64; ++i) {
    const double mid = 0.5 * (lo + hi);
    (unit_from_mu_s(g, mid, mapping) < x ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// sin θv · sin θs = √((1 − μ²)(1 − μs²)): the half-width of the range of ν
/// that μ and μs allow, ν = μ μs + spread · cos φ with φ ∈ [0, π] the azimuth
/// between the view and the sun.
double nu_spread(double mu, double mu_s) { return std::sqrt(std::max(0.0, (1.0 - mu * mu) * (1.0 - mu_s * mu_s))); }

}  // namespace

/// ν ↔ [0, 1] uniform in the azimuth φ between the view and the sun at this μ
/// and μs: every ν slice lies inside the range of ν that μ and μs allow. The
/// paper's mapping (uniform in ν, or, as this table had it, uniform in the
/// scattering angle over [0°, 180°]) gives a view near the horizon under a high
/// sun one or two of the 8 slices for the whole azimuth circle (sun 20° from the
/// zenith: scattering angles 70°–110°), and the second order came out 9–20 %
/// dark toward the sun's azimuth. Across μ and μs texels the same u is the same
/// azimuth, along which the radiance varies smoothly; in the scattering angle
/// the slices are never farther apart than the paper's (dΘ/dφ ≤ 1).
double scattering_u_nu(double mu, double mu_s, double nu) {
  const double spread = nu_spread(mu, mu_s);
  if (!(spread > kNuSpreadMin)) return 0.0;  // view or sun at the zenith: every azimuth is the same ν
  const double cos_phi = std::clamp((nu - mu * mu_s) / spread, -1.0, 1.0);
  return std::acos(cos_phi) / kPi;
}

/// Inverse of scattering_u_nu at this μ and μs.
double scattering_nu_from_unit(double mu, double mu_s, double x) {
  return std::clamp(mu * mu_s + nu_spread(mu, mu_s) * std::cos(kPi * x), -1.0, 1.0);
}

/// μ ↔ [0, 1] for rays that do not hit the ground (see AngleMapping).
double unit_from_mu_sky(const ShellGeometry& g, double r_m, double mu, AngleMapping mapping) {
  const double H = g.horizon_distance_at_top_m(), rho = g.horizon_distance_m(r_m);
  const double r_mu = r_m * mu;
  const double d = -r_mu + safe_sqrt(r_mu * r_mu - difference_of_squares(r_m, g.top_radius_m));
  const double d_min = g.top_radius_m - r_m, d_max = rho + H;
  const double distance = d_max == d_min ? 0.0 : std::clamp((d - d_min) / (d_max - d_min), 0.0, 1.0);
  if (mapping == AngleMapping::Distance) return distance;
  const double theta_horizon = std::acos(std::clamp(-rho / r_m, -1.0, 1.0));  // zenith angle of the horizon
  const double angle = std::clamp(std::acos(std::clamp(mu, -1.0, 1.0)) / theta_horizon, 0.0, 1.0);
  return 0.5 * distance + 0.5 * angle;
}

/// Inverse of unit_from_mu_sky: closed form for Distance, bisection for Blended.
double mu_sky_from_unit(const ShellGeometry& g, double r_m, double x, AngleMapping mapping) {
  const double H = g.horizon_distance_at_top_m(), rho = g.horizon_distance_m(r_m);
  if (mapping == AngleMapping::Distance) {
    const double d_min = g.top_radius_m - r_m, d_max = rho + H;
    const double d = d_min + (d_max - d_min) * x;
    return d == 0.0 ? 1.0 : clamp_cosine((H * H - rho * rho - d * d) / (2.0 * r_m * d));
  }
  double lo = -rho / r_m, hi = 1.0;  // x decreases as μ increases
  for (int i = 0; i < 64; ++i) {
    const double mid = 0.5 * (lo + hi);
    (unit_from_mu_sky(g, r_m, mid, mapping) > x ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

ScatteringUVWZ scattering_uvwz(const ShellGeometry& g, const TableSizes& s, double r_m, double mu, double mu_s,
                               double nu, bool ray_hits_ground, AngleMapping mapping) {
  const double H = g.horizon_distance_at_top_m();
  const double rho = g.horizon_distance_m(r_m);
  const double u_r = texture_coord_from_unit(std::clamp(rho / H, 0.0, 1.0), s.scattering_r);

  const double r_mu = r_m * mu;
  const double disc = r_mu * r_mu - difference_of_squares(r_m, g.bottom_radius_m);
  const std::size_t half = s.scattering_mu / 2;
  double u_mu;
  if (ray_hits_ground) {
    // Distance to the ground, between r − rb (straight down) and ρ (tangent).
    const double d = -r_mu - safe_sqrt(disc);
    const double d_min = r_m - g.bottom_radius_m, d_max = rho;
    const double x = d_max == d_min ? 0.0 : std::clamp((d - d_min) / (d_max - d_min), 0.0, 1.0);
    u_mu = 0.5 - 0.5 * texture_coord_from_unit(x, half);
  } else {
    // Distance to the top, between rt − r (straight up) and ρ + H (tangent to the
    // ground), blended with the zenith angle for AngleMapping::Blended.
    u_mu = 0.5 + 0.5 * texture_coord_from_unit(unit_from_mu_sky(g, r_m, mu, mapping), half);
  }
  return {scattering_u_nu(mu, mu_s, nu), scattering_u_mu_s(g, s, mu_s, mapping), u_mu, u_r};
}

double scattering_u_mu_s(const ShellGeometry& g, const TableSizes& s, double mu_s, AngleMapping mapping) {
  return texture_coord_from_unit(unit_from_mu_s(g, mu_s, mapping), s.scattering_mu_s);
}

ScatteringCoordinates scattering_texel_coordinates(const ShellGeometry& g, const TableSizes& s, std::size_t x,
                                                   std::size_t y, std::size_t z, AngleMapping mapping) {
  const std::size_t nu_index = x / s.scattering_mu_s, mu_s_index = x % s.scattering_mu_s;
  const double u_r = (double(z) + 0.5) / double(s.scattering_r);
  const double u_mu = (double(y) + 0.5) / double(s.scattering_mu);
  const double u_mu_s = (double(mu_s_index) + 0.5) / double(s.scattering_mu_s);
  const double x_nu = double(nu_index) / double(s.scattering_nu - 1);

  ScatteringCoordinates c{};
  const double H = g.horizon_distance_at_top_m();
  const double rho = H * unit_from_texture_coord(u_r, s.scattering_r);
  c.r_m = radius_from_horizon_distance(g, rho);
  const std::size_t half = s.scattering_mu / 2;
  if (u_mu < 0.5) {
    const double d_min = c.r_m - g.bottom_radius_m, d_max = rho;
    const double d = d_min + (d_max - d_min) * unit_from_texture_coord(1.0 - 2.0 * u_mu, half);
    c.mu = d == 0.0 ? -1.0 : clamp_cosine(-(rho * rho + d * d) / (2.0 * c.r_m * d));
    c.ray_hits_ground = true;
  } else {
    c.mu = mu_sky_from_unit(g, c.r_m, unit_from_texture_coord(2.0 * u_mu - 1.0, half), mapping);
    c.ray_hits_ground = false;
  }
  c.mu_s = mu_s_from_unit(g, unit_from_texture_coord(u_mu_s, s.scattering_mu_s), mapping);
  c.nu = scattering_nu_from_unit(c.mu, c.mu_s, x_nu);
  return c;
}

}  // namespace zenith::atmosphere::lut
