#pragma once
// Per-wavelength quantities.
//
// zenith renders at a configurable list of wavelengths (default 680, 550, 440 nm,
// the paper's red, green and blue). Nothing in atmosphere/ assumes three: every
// spectral quantity is a Spectrum with one value per working wavelength.
#include <cstddef>
#include <initializer_list>
#include <span>
#include <utility>
#include <vector>

namespace zenith::atmosphere {

/// One value per working wavelength, in the order of the model's wavelength list.
class Spectrum {
 public:
  Spectrum() = default;
  explicit Spectrum(std::size_t count, double value = 0.0) : values_(count, value) {}
  Spectrum(std::initializer_list<double> values) : values_(values) {}
  explicit Spectrum(std::vector<double> values) : values_(std::move(values)) {}

  std::size_t size() const { return values_.size(); }
  double& operator[](std::size_t i) { return values_[i]; }
  double operator[](std::size_t i) const { return values_[i]; }
  std::span<const double> values() const { return values_; }
  auto begin() const { return values_.begin(); }
  auto end() const { return values_.end(); }

  Spectrum& operator+=(const Spectrum& o);
  Spectrum& operator*=(double s);
  friend Spectrum operator+(Spectrum a, const Spectrum& b) { return a += b; }
  friend Spectrum operator*(Spectrum a, double s) { return a *= s; }
  friend Spectrum operator*(double s, Spectrum a) { return a *= s; }
  friend bool operator==(const Spectrum&, const Spectrum&) = default;

  bool all_zero() const;
  double max() const;

 private:
  std::vector<double> values_;
};

/// A quantity sampled at a few wavelengths (e.g. Table 1's three values, or a
/// 10 nm binned cross-section table), evaluated at any wavelength by linear
/// interpolation in wavelength. Outside the sampled range the nearest sample is
/// used; `covers()` tells callers whether that happened so they can warn.
class SpectralTable {
 public:
  SpectralTable() = default;
  /// `samples` are (wavelength_nm, value) pairs; sorted internally; wavelengths must be distinct.
  explicit SpectralTable(std::vector<std::pair<double, double>> samples);
  static SpectralTable constant(double value);

  double operator()(double wavelength_nm) const;
  Spectrum sample(std::span<const double> wavelengths_nm) const;
  bool covers(double wavelength_nm) const;
  bool is_constant() const { return samples_.size() == 1; }
  const std::vector<std::pair<double, double>>& samples() const { return samples_; }

 private:
  std::vector<std::pair<double, double>> samples_;
};

}  // namespace zenith::atmosphere
