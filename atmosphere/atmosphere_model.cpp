#include "atmosphere/atmosphere_model.h"

#include <cmath>
#include <stdexcept>

#include "atmosphere/phase_functions.h"

namespace zenith::atmosphere {

double MiePhase::operator()(std::size_t i, double cos_theta) const {
  switch (model) {
    case Model::HenyeyGreenstein: return henyey_greenstein(cos_theta, g1[i]);
    case Model::DoubleHenyeyGreenstein: return double_henyey_greenstein(cos_theta, g1[i], g2[i], alpha[i]);
    case Model::CornetteShanks: return cornette_shanks(cos_theta, g1[i]);
    case Model::Tabulated: return (*table)(i, cos_theta);
  }
  return 0.0;
}

const char* rayleigh_phase_name(RayleighPhaseModel model) {
  switch (model) {
    case RayleighPhaseModel::Classic: return "classic";
    case RayleighPhaseModel::Penndorf: return "penndorf";
    case RayleighPhaseModel::Depolarized: return "depolarized";
  }
  return "";
}

double AtmosphereModel::rayleigh_phase_function(double cos_theta) const {
  switch (rayleigh_phase) {
    case RayleighPhaseModel::Classic: return rayleigh_phase_classic(cos_theta);
    case RayleighPhaseModel::Penndorf: return rayleigh_phase_penndorf(cos_theta);
    case RayleighPhaseModel::Depolarized: return rayleigh_phase_depolarized(cos_theta, rayleigh_depolarization);
  }
  return 0.0;
}

Spectrum AtmosphereModel::extinction_m1(double altitude_m) const {
  Spectrum e = rayleigh_scattering_m1 * rayleigh_density(altitude_m);
  e += mie_extinction_m1 * mie_density(altitude_m);
  for (const Absorber& a : absorbers) e += a.absorption_m1 * a.profile(altitude_m);
  return e;
}

void AtmosphereModel::extinction_m1(double altitude_m, double* out) const {
  const double rayleigh = rayleigh_density(altitude_m), mie = mie_density(altitude_m);
  for (std::size_t i = 0; i < wavelength_count(); ++i)
    out[i] = rayleigh_scattering_m1[i] * rayleigh + mie_extinction_m1[i] * mie;
  for (const Absorber& a : absorbers) {
    const double density = a.profile(altitude_m);
    for (std::size_t i = 0; i < wavelength_count(); ++i) out[i] += a.absorption_m1[i] * density;
  }
}

AtmosphereModel::ZenithOpticalDepth AtmosphereModel::zenith_optical_depth() const {
  const double H = atmosphere_height_m();
  ZenithOpticalDepth d;
  d.rayleigh = rayleigh_scattering_m1 * rayleigh_density.column_m(0.0, H);
  const double mie_column = mie_density.column_m(0.0, H);
  d.mie_scattering = mie_scattering_m1 * mie_column;
  d.mie_absorption = Spectrum(wavelength_count());
  for (std::size_t i = 0; i < wavelength_count(); ++i)
    d.mie_absorption[i] = (mie_extinction_m1[i] - mie_scattering_m1[i]) * mie_column;
  d.total = d.rayleigh + d.mie_scattering + d.mie_absorption;
  for (const Absorber& a : absorbers) {
    Spectrum tau = a.absorption_m1 * a.profile.column_m(0.0, H);
    d.total += tau;
    d.absorbers.emplace_back(a.name, std::move(tau));
  }
  return d;
}

void AtmosphereModel::check() const {
  const std::size_t n = wavelengths_nm.size();
  auto fail = [&](const std::string& what) { throw std::invalid_argument("atmosphere '" + name + "': " + what); };
  if (n == 0) fail("no wavelengths");
  for (double w : wavelengths_nm)
    if (!(w >= 200.0 && w <= 2500.0)) fail("wavelength outside [200, 2500] nm");
  if (!(ground_radius_m > 0.0) || !std::isfinite(ground_radius_m)) fail("ground radius must be > 0");
  if (!(top_radius_m > ground_radius_m) || !std::isfinite(top_radius_m))
    fail("atmosphere top must be above the ground");
  auto check_spectrum = [&](const Spectrum& s, const std::string& what, double hi) {
    if (s.size() != n) fail(what + " has " + std::to_string(s.size()) + " values, expected " + std::to_string(n));
    for (double v : s)
      if (!std::isfinite(v) || v < 0.0 || v > hi) fail(what + " out of range [0, " + std::to_string(hi) + "]");
  };
  check_spectrum(ground_albedo, "ground albedo", 1.0);
  check_spectrum(rayleigh_scattering_m1, "Rayleigh scattering", 1.0);
  check_spectrum(mie_scattering_m1, "Mie scattering", 1.0);
  check_spectrum(mie_extinction_m1, "Mie extinction", 1.0);
  for (std::size_t i = 0; i < n; ++i)
    if (mie_scattering_m1[i] > mie_extinction_m1[i] * (1.0 + 1e-12)) fail("Mie scattering exceeds Mie extinction");
  for (const Absorber& a : absorbers) check_spectrum(a.absorption_m1, "absorption of " + a.name, 1.0);
  if (has_mie()) {
    auto check_asymmetry = [&](const Spectrum& g, const std::string& what) {
      if (g.size() != n) fail(what + " has the wrong number of values");
      for (double v : g)
        if (!(v > -1.0 && v < 1.0)) fail(what + " outside (-1, 1)");
    };
    check_asymmetry(mie_phase.g1, "Mie g1");
    if (mie_phase.model == MiePhase::Model::DoubleHenyeyGreenstein) {
      check_asymmetry(mie_phase.g2, "Mie g2");
      check_spectrum(mie_phase.alpha, "Mie alpha", 1.0);
    }
    if (mie_phase.model == MiePhase::Model::Tabulated && (!mie_phase.table || mie_phase.table->wavelength_count() != n))
      fail("Mie phase table missing or resampled at other wavelengths");
  }
}

}  // namespace zenith::atmosphere
