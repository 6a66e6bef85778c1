#include "atmosphere/reference/medium.h"

namespace zenith::atmosphere::reference {

double AtmosphereMedium::extinction_m1(double altitude_m, std::size_t i) const {
  const AtmosphereModel& m = *model_;
  double beta = m.rayleigh_scattering_m1[i] * m.rayleigh_density(altitude_m);
  if (m.mie_extinction_m1[i] > 0.0) beta += m.mie_extinction_m1[i] * m.mie_density(altitude_m);
  for (const Absorber& a : m.absorbers)
    if (a.absorption_m1[i] > 0.0) beta += a.absorption_m1[i] * a.profile(altitude_m);
  return beta;
}

void AtmosphereMedium::extinction_m1(double altitude_m, std::span<double> out) const {
  const AtmosphereModel& m = *model_;
  const double rho_r = m.rayleigh_density(altitude_m);
  const double rho_m = m.has_mie() ? m.mie_density(altitude_m) : 0.0;
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = m.rayleigh_scattering_m1[i] * rho_r + m.mie_extinction_m1[i] * rho_m;
  for (const Absorber& a : m.absorbers) {
    const double rho_a = a.profile(altitude_m);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] += a.absorption_m1[i] * rho_a;
  }
}

LocalCoefficients AtmosphereMedium::coefficients(double altitude_m, std::size_t i) const {
  const AtmosphereModel& m = *model_;
  LocalCoefficients c;
  c.rayleigh_scattering_m1 = m.rayleigh_scattering_m1[i] * m.rayleigh_density(altitude_m);
  c.extinction_m1 = c.rayleigh_scattering_m1;
  if (m.mie_extinction_m1[i] > 0.0) {
    const double rho_m = m.mie_density(altitude_m);
    c.mie_scattering_m1 = m.mie_scattering_m1[i] * rho_m;
    c.extinction_m1 += m.mie_extinction_m1[i] * rho_m;
  }
  for (const Absorber& a : m.absorbers)
    if (a.absorption_m1[i] > 0.0) c.extinction_m1 += a.absorption_m1[i] * a.profile(altitude_m);
  return c;
}

void AtmosphereMedium::coefficients(double altitude_m, std::span<LocalCoefficients> out) const {
  const AtmosphereModel& m = *model_;
  const double rho_r = m.rayleigh_density(altitude_m);
  const double rho_m = m.has_mie() ? m.mie_density(altitude_m) : 0.0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].rayleigh_scattering_m1 = m.rayleigh_scattering_m1[i] * rho_r;
    out[i].mie_scattering_m1 = m.mie_scattering_m1[i] * rho_m;
    out[i].extinction_m1 = out[i].rayleigh_scattering_m1 + m.mie_extinction_m1[i] * rho_m;
  }
  for (const Absorber& a : m.absorbers) {
    const double rho_a = a.profile(altitude_m);
    for (std::size_t i = 0; i < out.size(); ++i) out[i].extinction_m1 += a.absorption_m1[i] * rho_a;
  }
}

double AtmosphereMedium::mixture_phase(const LocalCoefficients& c, std::size_t i, double cos_scattering) const {
  const double scattering = c.scattering_m1();
  if (!(scattering > 0.0)) return 0.0;
  double weighted = c.rayleigh_scattering_m1 * model_->rayleigh_phase_function(cos_scattering);
  if (c.mie_scattering_m1 > 0.0) weighted += c.mie_scattering_m1 * model_->mie_phase(i, cos_scattering);
  return weighted / scattering;
}

}  // namespace zenith::atmosphere::reference
