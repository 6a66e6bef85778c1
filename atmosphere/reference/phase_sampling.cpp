#include "atmosphere/reference/phase_sampling.h"

#include <algorithm>
#include <cmath>

#include "atmosphere/constants.h"
#include "atmosphere/phase_functions.h"

namespace zenith::atmosphere::reference {

namespace {
constexpr double kIsotropicThreshold = 1e-6;
}

double sample_rayleigh_classic_cosine(double u) {
  const double z = 4.0 * u - 2.0;
  const double a = std::cbrt(z + std::sqrt(z * z + 1.0));
  return std::clamp(a - 1.0 / a, -1.0, 1.0);
}

double sample_henyey_greenstein_cosine(double g, double u) {
  if (std::abs(g) < kIsotropicThreshold) return 2.0 * u - 1.0;
  const double ratio = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
  return std::clamp((1.0 + g * g - ratio * ratio) / (2.0 * g), -1.0, 1.0);
}

double henyey_greenstein_proposal_pdf(double g, double cos_scattering) {
  if (std::abs(g) < kIsotropicThreshold) return 1.0 / (4.0 * kPi);
  return henyey_greenstein(cos_scattering, g);
}

double sample_mie_proposal_cosine(const MiePhase& phase, std::size_t i, double u_lobe, double u) {
  if (phase.model == MiePhase::Model::Tabulated) return phase.table->sample_cosine(i, u_lobe, u);
  if (phase.model == MiePhase::Model::DoubleHenyeyGreenstein && !(u_lobe < phase.alpha[i]))
    return sample_henyey_greenstein_cosine(phase.g2[i], u);
  return sample_henyey_greenstein_cosine(phase.g1[i], u);
}

double mie_proposal_pdf(const MiePhase& phase, std::size_t i, double cos_scattering) {
  if (phase.model == MiePhase::Model::Tabulated) return phase.table->proposal_pdf(i, cos_scattering);
  if (phase.model == MiePhase::Model::DoubleHenyeyGreenstein) {
    const double alpha = phase.alpha[i];
    double pdf = 0.0;
    if (alpha > 0.0) pdf += alpha * henyey_greenstein_proposal_pdf(phase.g1[i], cos_scattering);
    if (alpha < 1.0) pdf += (1.0 - alpha) * henyey_greenstein_proposal_pdf(phase.g2[i], cos_scattering);
    return pdf;
  }
  return henyey_greenstein_proposal_pdf(phase.g1[i], cos_scattering);
}

PhaseSample sample_scattering_cosine(const AtmosphereMedium& medium, const LocalCoefficients& c, std::size_t i,
                                     double u_component, double u_lobe, double u_cos) {
  const MiePhase& mie = medium.model().mie_phase;
  const double scattering = c.scattering_m1();
  const bool rayleigh = u_component * scattering < c.rayleigh_scattering_m1;
  PhaseSample sample;
  sample.cos_scattering =
      rayleigh ? sample_rayleigh_classic_cosine(u_cos) : sample_mie_proposal_cosine(mie, i, u_lobe, u_cos);
  sample.weight =
      medium.mixture_phase(c, i, sample.cos_scattering) / scattering_proposal_pdf(medium, c, i, sample.cos_scattering);
  return sample;
}

double scattering_proposal_pdf(const AtmosphereMedium& medium, const LocalCoefficients& c, std::size_t i,
                               double cos_scattering) {
  double proposal = c.rayleigh_scattering_m1 * rayleigh_phase_classic(cos_scattering);
  if (c.mie_scattering_m1 > 0.0)
    proposal += c.mie_scattering_m1 * mie_proposal_pdf(medium.model().mie_phase, i, cos_scattering);
  return proposal / c.scattering_m1();
}

}  // namespace zenith::atmosphere::reference
