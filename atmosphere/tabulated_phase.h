#pragma once
// A phase function given as a table of the scattering angle, per wavelength:
// what a Mie code prints, or what AERONET retrieves from an almucantar scan of
// the real sky (aeronet_phase_file.h reads its export).
//
// The table is resampled once, per working wavelength, on a grid uniform in
//   u = sin(θ/2) = √((1 − cos θ)/2),   u_k = k/(K − 1), k = 0 … K − 1,
// and P is linear in u between the samples. The grid is fine where aerosol
// phase functions change fastest (θ ≈ 2u near the forward peak: 0.45° steps
// with K = 256) and needs no arccosine to evaluate: the shaders
// (shaders/atmosphere/physics.glsl, tabulated_mie_phase) read the same samples
// with the same interpolation. From the given angles, log P is interpolated
// linearly in θ (phase functions span decades); between the given wavelengths
// P is interpolated linearly in λ, and held at the nearest one outside them.
//
// Normalisation: the samples are scaled so that the interpolant integrates to
// exactly 1 over the sphere. With dω = 2π dcos θ and cos θ = 1 − 2u²,
//   ∫_{4π} P dω = 8π ∫_0^1 P(u) u du,
// and on a segment [u0, u0 + h] where P = P0 + ΔP t, u = u0 + h t:
//   ∫ P u du = h (P0 u0 + P0 h/2 + ΔP u0/2 + ΔP h/3).
// So a table of any scale (AERONET's integrates to 4π) is accepted; the
// integral as given is kept for reports.
#include <cstddef>
#include <vector>

namespace zenith::atmosphere {

class TabulatedPhase {
 public:
  /// Samples per wavelength on the u grid (also TABULATED_PHASE_SAMPLES' value in the shaders' defines).
  static constexpr std::size_t kSamples = 256;

  /// One column of the given table: P at every given angle (any positive
  /// scale), at one wavelength.
  struct Column {
    double wavelength_nm = 0.0;
    std::vector<double> values;
  };

  /// Resamples `columns` (given at `angles_deg`, strictly increasing from 0 to
  /// 180, every value > 0 and finite) at the working wavelengths. Throws
  /// std::invalid_argument naming what is wrong (the config reader checks the
  /// same first and names the file and key).
  TabulatedPhase(const std::vector<double>& angles_deg, const std::vector<Column>& columns,
                 const std::vector<double>& wavelengths_nm);

  std::size_t wavelength_count() const { return integral_as_given_.size(); }

  /// P(cos θ) at wavelength index i [sr^-1], normalised to 1 over the sphere.
  double operator()(std::size_t i, double cos_theta) const;

  /// The resampled, normalised samples P(u_k) [sr^-1], wavelength after
  /// wavelength (kSamples each): what the shaders read.
  const std::vector<double>& samples() const { return samples_; }

  /// ∫_{4π} P dω of the table as given at wavelength i (before normalisation).
  double integral_as_given(std::size_t i) const { return integral_as_given_[i]; }

  /// The asymmetry parameter g = ∫ P cos θ dω at wavelength i.
  double asymmetry(std::size_t i) const { return asymmetry_[i]; }

  /// A cosine drawn from a proposal close to P (importance sampling for the
  /// reference solver): a segment of the u grid with probability its share of
  /// ∫ P dω, then u² uniform within it (uniform in solid angle). From
  /// u_segment, u ∈ [0, 1).
  double sample_cosine(std::size_t i, double u_segment, double u) const;
  /// The pdf [sr^-1] of sample_cosine: the segment's share / its solid angle.
  double proposal_pdf(std::size_t i, double cos_theta) const;

 private:
  /// The segment k (u in [u_k, u_k+1]) and the fraction within it.
  static std::size_t segment(double cos_theta, double* fraction);

  std::vector<double> samples_;            ///< [i · kSamples + k]
  std::vector<double> segment_cdf_;        ///< [i · kSamples + k]: share of ∫ P dω below u_k (k = 0 … K − 1)
  std::vector<double> integral_as_given_;  ///< per wavelength
  std::vector<double> asymmetry_;          ///< per wavelength
};

}  // namespace zenith::atmosphere
