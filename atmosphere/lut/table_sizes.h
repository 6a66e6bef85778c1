#pragma once
// Sizes of the lookup tables. Defaults are the paper's (section 6.3):
// transmittance 256×64, in-scattering (32·8)×128×32, irradiance 64×16.
#include <cstddef>
#include <string>

namespace zenith::atmosphere::lut {

struct TableSizes {
  std::size_t transmittance_mu = 256;
  std::size_t transmittance_r = 64;
  std::size_t irradiance_mu_s = 64;
  std::size_t irradiance_r = 16;
  std::size_t scattering_r = 32;
  std::size_t scattering_mu = 128;  ///< even: half for ground-hitting rays, half for the rest
  std::size_t scattering_mu_s = 32;
  std::size_t scattering_nu = 8;

  std::size_t scattering_width() const { return scattering_nu * scattering_mu_s; }
  std::size_t scattering_texels() const { return scattering_width() * scattering_mu * scattering_r; }
  /// Throws std::invalid_argument naming the size if one is out of range.
  void check() const;
  /// "T256x64 E64x16 S32x128x32x8" — also part of cache keys.
  std::string describe() const;
  /// Small tables for tests: quick to compute, still every code path.
  static TableSizes small();
  friend bool operator==(const TableSizes&, const TableSizes&) = default;
};

}  // namespace zenith::atmosphere::lut
