#include "astro/sky_positions.h"

#include <erfa.h>

#include <cmath>
#include <stdexcept>

#include "astro/range_check.h"
#include "core/units.h"

namespace zenith::astro {

struct SkyPositions::State {
  eraASTROM site{}, geocentre{};
  double eo_site = 0.0, eo_geocentre = 0.0;  ///< equation of the origins (CIO → equinox RA)
  double earth_bary_au[3]{}, sun_bary_au[3]{}, moon_geo_au[3]{};
};

namespace {

constexpr double kRadToArcsec = 180.0 / core::kPi * 3600.0;

Horizontal observed(double ri, double di, const eraASTROM& astrom) {
  double aob = 0.0, zob = 0.0, hob = 0.0, dob = 0.0, rob = 0.0;
  eraAtioq(ri, di, const_cast<eraASTROM*>(&astrom), &aob, &zob, &hob, &dob, &rob);
  return Horizontal{eraAnp(aob), core::kPi / 2.0 - zob};
}

/// A direction (BCRS/GCRS axes, any length) seen from an observer at rest in
/// those axes → CIRS, through light deflection, aberration and bias–precession–nutation.
void direction_to_cirs(const double v[3], const eraASTROM& astrom, double* ri, double* di) {
  double rc = 0.0, dc = 0.0;
  eraC2s(const_cast<double*>(v), &rc, &dc);
  eraAtciq(rc, dc, 0.0, 0.0, 0.0, 0.0, const_cast<eraASTROM*>(&astrom), ri, di);
}

/// A geometric geocentric/topocentric vector of a nearby body (GCRS) → CIRS: the
/// rotation only (the Moon shares the Earth's annual motion; its light time,
/// 1.3 s, moves it by < 1″).
void gcrs_vector_to_cirs(const double v[3], const eraASTROM& astrom, double* ri, double* di) {
  double c[3];
  eraRxp(const_cast<double(*)[3]>(astrom.bpn), const_cast<double*>(v), c);
  eraC2s(c, ri, di);
}

}  // namespace

void check_site(const Site& site) {
  require_in_range("site latitude_deg", site.latitude_deg, -90.0, 90.0, "deg");
  require_in_range("site longitude_deg", site.longitude_deg, -180.0, 360.0, "deg");
  require_in_range("site altitude_m", site.altitude_m, -500.0, 10000.0, "m");
}

glm::dvec3 Horizontal::east_north_up() const {
  const double c = std::cos(altitude_rad);
  return {c * std::sin(azimuth_rad), c * std::cos(azimuth_rad), std::sin(altitude_rad)};
}

SkyPositions::SkyPositions(const AstroTime& time, const Site& site) : time_(time), site_(site) {
  check_site(site);
  auto state = std::make_shared<State>();
  // What eraApco13 (the site) and eraApci13 (the geocentre) each compute
  // from the date — the Earth's ephemeris and the IAU 2006/2000A
  // precession–nutation, most of their cost — computed once for both, with
  // the times AstroTime took from the same ERFA calls.
  const JulianDate& tt = time.tt();  // TDB − TT < 2 ms: TT serves as TDB
  const JulianDate& ut1 = time.ut1();
  double ehpv[2][3], ebpv[2][3], bpn[3][3], x = 0.0, y = 0.0;
  eraEpv00(tt.day1, tt.day2, ehpv, ebpv);
  eraPnm06a(tt.day1, tt.day2, bpn);
  eraBpn2xy(bpn, &x, &y);
  const double s = eraS06(tt.day1, tt.day2, x, y);
  const double era = eraEra00(ut1.day1, ut1.day2), sp = eraSp00(tt.day1, tt.day2);
  // Polar motion 0 (< 0.3″); refraction off (ERFA's pressure 0: its constants 0), ours applies later.
  eraApco(tt.day1, tt.day2, ebpv, ehpv[0], x, y, s, era, site.longitude_deg * core::kDeg,
          site.latitude_deg * core::kDeg, site.altitude_m, 0.0, 0.0, sp, 0.0, 0.0, &state->site);
  eraApci(tt.day1, tt.day2, ebpv, ehpv[0], x, y, s, &state->geocentre);
  state->eo_site = state->eo_geocentre = eraEors(bpn, s);
  double moon[2][3];
  eraMoon98(tt.day1, tt.day2, moon);
  for (int k = 0; k < 3; ++k) {
    state->earth_bary_au[k] = ebpv[0][k];
    state->sun_bary_au[k] = ebpv[0][k] - ehpv[0][k];
    state->moon_geo_au[k] = moon[0][k];
  }
  state_ = std::move(state);
}

Horizontal SkyPositions::star(const CatalogueStar& s) const {
  double ri = 0.0, di = 0.0;
  // ERFA wants dα/dt, not μα* = cos δ dα/dt; parallax in arcseconds.
  const double pr = s.pm_ra_cosdec_mas_yr * 1e-3 / kRadToArcsec / std::cos(s.dec_rad);
  const double pd = s.pm_dec_mas_yr * 1e-3 / kRadToArcsec;
  eraAtciq(s.ra_rad, s.dec_rad, pr, pd, s.parallax_mas * 1e-3, 0.0, const_cast<eraASTROM*>(&state_->site), &ri, &di);
  return observed(ri, di, state_->site);
}

void SkyPositions::stars(const std::vector<CatalogueStar>& stars, std::vector<Horizontal>& out) const {
  out.resize(stars.size());
  for (std::size_t i = 0; i < stars.size(); ++i) out[i] = star(stars[i]);
}

SunPlace SkyPositions::sun() const {
  double v[3];
  for (int k = 0; k < 3; ++k) v[k] = state_->sun_bary_au[k] - state_->site.eb[k];
  double ri = 0.0, di = 0.0;
  direction_to_cirs(v, state_->site, &ri, &di);
  SunPlace p;
  p.horizontal = observed(ri, di, state_->site);
  p.distance_au = eraPm(v);
  p.angular_radius_rad = std::asin(kSunRadius_km / (p.distance_au * kAstronomicalUnit_km));
  return p;
}

MoonPlace SkyPositions::moon() const {
  const State& s = *state_;
  double observer_geo[3], topo[3], moon_bary[3], to_sun[3], to_observer[3];
  for (int k = 0; k < 3; ++k) {
    observer_geo[k] = s.site.eb[k] - s.earth_bary_au[k];
    topo[k] = s.moon_geo_au[k] - observer_geo[k];
    moon_bary[k] = s.earth_bary_au[k] + s.moon_geo_au[k];
    to_sun[k] = s.sun_bary_au[k] - moon_bary[k];
    to_observer[k] = s.site.eb[k] - moon_bary[k];
  }
  double ri = 0.0, di = 0.0;
  gcrs_vector_to_cirs(topo, s.site, &ri, &di);
  MoonPlace p;
  p.horizontal = observed(ri, di, s.site);
  p.distance_km = eraPm(topo) * kAstronomicalUnit_km;
  p.angular_radius_rad = std::asin(kMoonRadius_km / p.distance_km);
  p.phase_angle_rad = eraSepp(to_sun, to_observer);
  p.illuminated_fraction = 0.5 * (1.0 + std::cos(p.phase_angle_rad));
  p.sun_distance_au = eraPm(to_sun);
  return p;
}

Equatorial SkyPositions::apparent_geocentric(const CatalogueStar& s) const {
  double ri = 0.0, di = 0.0;
  const double pr = s.pm_ra_cosdec_mas_yr * 1e-3 / kRadToArcsec / std::cos(s.dec_rad);
  const double pd = s.pm_dec_mas_yr * 1e-3 / kRadToArcsec;
  eraAtciq(s.ra_rad, s.dec_rad, pr, pd, s.parallax_mas * 1e-3, 0.0, const_cast<eraASTROM*>(&state_->geocentre), &ri,
           &di);
  return Equatorial{eraAnp(ri - state_->eo_geocentre), di};
}

Equatorial SkyPositions::sun_apparent_geocentric() const {
  double v[3];
  for (int k = 0; k < 3; ++k) v[k] = state_->sun_bary_au[k] - state_->geocentre.eb[k];
  double ri = 0.0, di = 0.0;
  direction_to_cirs(v, state_->geocentre, &ri, &di);
  return Equatorial{eraAnp(ri - state_->eo_geocentre), di};
}

Equatorial SkyPositions::moon_apparent_geocentric() const {
  double ri = 0.0, di = 0.0;
  gcrs_vector_to_cirs(state_->moon_geo_au, state_->geocentre, &ri, &di);
  return Equatorial{eraAnp(ri - state_->eo_geocentre), di};
}

double SkyPositions::moon_geocentric_distance_km() const {
  double v[3] = {state_->moon_geo_au[0], state_->moon_geo_au[1], state_->moon_geo_au[2]};
  return eraPm(v) * kAstronomicalUnit_km;
}

}  // namespace zenith::astro

namespace zenith::astro {

double SkyPositions::moon_geocentric_phase_angle_rad() const {
  const State& s = *state_;
  double to_sun[3], to_earth[3];
  for (int k = 0; k < 3; ++k) {
    to_sun[k] = s.sun_bary_au[k] - (s.earth_bary_au[k] + s.moon_geo_au[k]);
    to_earth[k] = -s.moon_geo_au[k];
  }
  return eraSepp(to_sun, to_earth);
}

SkyPositions::MoonVectors SkyPositions::moon_vectors(bool geocentric) const {
  const State& s = *state_;
  MoonVectors v;
  for (int k = 0; k < 3; ++k) {
    const double observer_geo = geocentric ? 0.0 : s.site.eb[k] - s.earth_bary_au[k];
    v.moon_from_observer_au[k] = s.moon_geo_au[k] - observer_geo;
    v.sun_from_moon_au[k] = s.sun_bary_au[k] - (s.earth_bary_au[k] + s.moon_geo_au[k]);
  }
  return v;
}

glm::dvec3 SkyPositions::gcrs_direction_enu(const glm::dvec3& v) const {
  double ri = 0.0, di = 0.0;
  const double gcrs[3] = {v.x, v.y, v.z};
  gcrs_vector_to_cirs(gcrs, state_->site, &ri, &di);
  return observed(ri, di, state_->site).east_north_up();
}

}  // namespace zenith::astro
