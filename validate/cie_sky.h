#pragma once
// The CIE standard general sky (ISO 15469:2004(E) / CIE S 011/E:2003, "Spatial
// distribution of daylight — CIE standard general sky"): 15 relative sky
// luminance distributions, from heavily overcast to cloudless, each given by a
// gradation function φ(Z) of the view zenith angle Z and an indicatrix
// (scattering) function f(χ) of the angular distance χ to the sun. Type 12 is
// the "CIE standard clear sky, low luminance turbidity" that the paper compares
// its Earth atmosphere with (section 6, Figure 10; docs/validation.md).
//
// Equations (numbered as in docs/validation.md, "CIE validation"):
//   (V1) L(Z, α)/L_z = f(χ)·φ(Z) / ( f(Z_s)·φ(0) )
//   (V2) φ(Z) = 1 + a·exp(b / cos Z)   for 0 ≤ Z < π/2,   φ(π/2) = 1
//   (V3) f(χ) = 1 + c·( exp(d·χ) − exp(d·π/2) ) + e·cos²χ
//   (V4) cos χ = cos Z·cos Z_s + sin Z·sin Z_s·cos α
// with α the azimuth of the view measured from the sun's azimuth. f(Z_s) is the
// indicatrix at the zenith (whose distance to the sun is Z_s) and φ(0) = 1 + a·e^b
// the gradation at the zenith, so (V1) is 1 at the zenith by construction.
// All angles in radians. The parameters are dimensionless.
#include <string>
#include <string_view>
#include <vector>

namespace zenith::validate {

/// One CIE standard general sky type: gradation parameters a, b and
/// indicatrix parameters c, d, e.
struct CieSkyType {
  int number = 0;  ///< 1..15 in the standard
  double a = 0.0, b = 0.0;
  double c = 0.0, d = 0.0, e = 0.0;
  std::string description;
};

/// The 15 types of the standard, in order, from the CSV compiled into the
/// binary (validate/data/cie_general_sky_types.csv).
std::vector<CieSkyType> cie_general_sky_types();
/// Parses a table with '#' comment lines, the header
/// "type,a,b,c,d,e,description" and one row per type. Throws
/// std::invalid_argument naming the line on malformed input.
std::vector<CieSkyType> parse_cie_sky_types(std::string_view csv_text);
/// One type by number (1..15); throws std::out_of_range otherwise.
CieSkyType cie_general_sky_type(int number);
/// The paper's validation case: type 12, CIE standard clear sky, low luminance turbidity.
inline constexpr int kCieStandardClearSkyType = 12;

/// Gradation φ(Z), eq. (V2); 1 at and below the horizon (Z ≥ π/2), where
/// exp(b / cos Z) → 0 for the standard's b < 0.
double cie_gradation(const CieSkyType& type, double zenith_rad);
/// Indicatrix f(χ), eq. (V3), for an angular distance χ ∈ [0, π] from the sun.
double cie_indicatrix(const CieSkyType& type, double sun_distance_rad);
/// Angular distance χ ∈ [0, π] between a view direction (zenith Z, azimuth α
/// from the sun's azimuth) and the sun (zenith Z_s), eq. (V4).
double cie_sun_distance_rad(double view_zenith_rad, double azimuth_from_sun_rad, double sun_zenith_rad);
/// Relative luminance L/L_z of the sky element at (Z, α) for the sun at Z_s, eq. (V1).
double cie_relative_luminance(const CieSkyType& type, double view_zenith_rad, double azimuth_from_sun_rad,
                              double sun_zenith_rad);

}  // namespace zenith::validate
