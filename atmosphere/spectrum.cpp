#include "atmosphere/spectrum.h"

#include <algorithm>
#include <stdexcept>

namespace zenith::atmosphere {

Spectrum& Spectrum::operator+=(const Spectrum& o) {
  if (o.size() != size()) throw std::invalid_argument("Spectrum: size mismatch in +=");
  for (std::size_t i = 0; i < size(); ++i) values_[i] += o.values_[i];
  return *this;
}

Spectrum& Spectrum::operator*=(double s) {
  for (double& v : values_) v *= s;
  return *this;
}

bool Spectrum::all_zero() const {
  return std::all_of(values_.begin(), values_.end(), [](double v) { return v == 0.0; });
}

double Spectrum::max() const { return values_.empty() ? 0.0 : *std::max_element(values_.begin(), values_.end()); }

SpectralTable::SpectralTable(std::vector<std::pair<double, double>> samples) : samples_(std::move(samples)) {
  if (samples_.empty()) throw std::invalid_argument("SpectralTable: no samples");
  std::sort(samples_.begin(), samples_.end());
  for (std::size_t i = 1; i < samples_.size(); ++i)
    if (samples_[i].first == samples_[i - 1].first) throw std::invalid_argument("SpectralTable: duplicate wavelength");
}

SpectralTable SpectralTable::constant(double value) { return SpectralTable({{550.0, value}}); }

double SpectralTable::operator()(double wavelength_nm) const {
  if (samples_.size() == 1 || wavelength_nm <= samples_.front().first) return samples_.front().second;
  if (wavelength_nm >= samples_.back().first) return samples_.back().second;
  auto hi = std::upper_bound(samples_.begin(), samples_.end(), wavelength_nm,
                             [](double w, const auto& s) { return w < s.first; });
  auto lo = hi - 1;
  const double t = (wavelength_nm - lo->first) / (hi->first - lo->first);
  return lo->second + t * (hi->second - lo->second);
}

Spectrum SpectralTable::sample(std::span<const double> wavelengths_nm) const {
  Spectrum s(wavelengths_nm.size());
  for (std::size_t i = 0; i < wavelengths_nm.size(); ++i) s[i] = (*this)(wavelengths_nm[i]);
  return s;
}

bool SpectralTable::covers(double wavelength_nm) const {
  return samples_.size() == 1 ||
         (wavelength_nm >= samples_.front().first - 1e-9 && wavelength_nm <= samples_.back().first + 1e-9);
}

}  // namespace zenith::atmosphere
