#pragma once
// `zenith validate cie`: the relative sky luminance L/L_z of the Earth presets,
// seen from the ground, against the CIE standard general sky (paper section 6,
// Figure 10: CIE type 12, "CIE standard clear sky, low luminance turbidity").
//
// For every preset and model variant (as is; classic Rayleigh phase instead of
// Penndorf's; geometric instead of Pickering's air mass) the lookup tables are
// obtained (cache, else GPU or CPU precompute), the sky radiance is queried from
// 1.5 m above the ground for each sun zenith angle and for view zenith angles
// 0…85° along five azimuths from the sun (0°, 45°, 90°, 135°, 180°), turned
// into luminance Y = Σ w_i·E_sun(λ_i)·L_i (atmosphere/photometry.h) and divided
// by the zenith luminance. Directions within a few degrees of the sun are left
// out (the CIE formula describes the sky, not the aureole and the disc).
// Per case (preset, variant, sun zenith, azimuth): RMS and max |ΔL/L_z| against
// type 12 and the best-fitting of the 15 types. Output: a table on stdout,
// CSV files, and per sun zenith a gnuplot script and PNG of the three vertical
// planes through the zenith (solar meridian 0°/180°, 45°/225°, 90°/270°), the
// layout of the paper's Figure 10 (docs/validation.md).
#include <string>
#include <vector>

#include "validate/validation_tables.h"

namespace zenith::validate {

struct CieValidationOptions {
  std::vector<std::string> presets;  ///< preset names or atmosphere files; empty: earth-advanced, earth-standard
  std::vector<double> sun_zeniths_deg = {20.0, 30.0, 45.0, 60.0, 70.0, 80.0};
  std::string out_dir = "out/validate/cie";
  std::string tables = "paper";  ///< the table sizes' name, for the report and the plots' titles
  double zenith_step_deg = 2.5;  ///< view zenith angles 0, step, …, 85°
  double exclude_sun_deg = 5.0;  ///< directions closer to the sun are left out of the statistics
  bool csv_stdout = false;       ///< the per-case table as CSV on stdout instead of the text summary
  bool no_variants = false;      ///< only the presets as given
  bool no_plots = false;         ///< the data, but no gnuplot scripts or PNG
};

/// Runs the comparison: tables from `tables_for`, the report on stdout, CSV
/// files, gnuplot scripts and PNG plots in options.out_dir.
void validate_cie(const CieValidationOptions& options, const TablesFor& tables_for);

}  // namespace zenith::validate
