#pragma once
// `zenith validate measured`: zenith's clear sky against measured skies
// (docs/validation.md, "Measured skies"). The measurements are Kider et al.
// 2014's spectral sky radiance at Cornell on 2013-05-27 (15 captures of 81
// directions, validate/measured_skies.h); the atmosphere is the one Bruneton
// 2017 inverted for that day (validate/data/cornell_2013-05-27.json), lit by
// the ASTM G173 extraterrestrial sun, with no parameter fitted to the
// captures. The score is that evaluation's: per capture the RMSE over every
// direction and every wavelength in [360, 720] nm of model minus measured
// spectral radiance, and over the day the RMS of the captures' RMSEs — so
// zenith stands in the same table as the eight models Bruneton scored. Beside
// it the same RMSE of luminance, and of the linear-sRGB chromaticity.
//
// The tables are checked against the reference solver (path tracer) at a
// subset of one capture's directions, so that what is measured is the
// physics, not the tables' resolution.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "validate/measured_skies.h"
#include "validate/validation_tables.h"

namespace zenith::validate {

/// The wavelengths the score counts (Bruneton 2017: his samples within [360, 720] nm).
inline constexpr double kScoreMinWavelength_nm = 360.0, kScoreMaxWavelength_nm = 720.0;

/// Total RMSE of the published models on the same 15 captures, mW m^-2 sr^-1 nm^-1,
/// measured with Bruneton's evaluation code (docs/validation.md, "Measured skies").
struct PeerScore {
  const char* model;
  double total_rmse_mW_m2_sr_nm;
};
inline constexpr PeerScore kPeerScores[] = {
    {"Bruneton 2017 (40 wavelengths, 4 orders)", 11.34},
    {"Nishita 1996", 18.1},
    {"Nishita 1993", 26.49},
    {"Hosek-Wilkie 2012 (turbidity 2.53)", 41.59},
    {"O'Neal 2005", 49.75},
    {"Preetham 1999 (turbidity 2.53)", 88.72},
};

/// A model's spectral radiance [W m^-2 sr^-1 nm^-1] at each direction of a
/// capture (in the capture's order), at the measurements' wavelengths.
using CaptureSky = std::function<std::vector<std::vector<double>>(const MeasuredCapture& capture)>;

struct CaptureScore {
  std::string time;
  double sun_zenith_deg = 0.0;
  double spectral_rmse_W_m2_sr_nm = 0.0;  ///< over directions × scored wavelengths
  double luminance_rmse_cd_m2 = 0.0;      ///< over directions
  double mean_measured_luminance_cd_m2 = 0.0;
  double chromaticity_rmse = 0.0;    ///< linear-sRGB (r, g, b) / (r + g + b), over directions × 3
  double model_over_measured = 0.0;  ///< Σ model / Σ measured over directions and scored wavelengths
};

/// One direction of one capture, for the plots and the CSV.
struct DirectionComparison {
  std::string time;
  MeasuredDirection measured;
  std::vector<double> model_W_m2_sr_nm;
  double measured_luminance_cd_m2 = 0.0, model_luminance_cd_m2 = 0.0;
};

/// The directions of every capture at angles from the sun in [from, to):
/// Σ model / Σ measured over them and the scored wavelengths. Where the error
/// lies around the sun says which physics makes it (the aerosol's phase
/// function near the sun, its amount and the molecules' away from it).
struct SunAngleBand {
  double from_deg = 0.0, to_deg = 0.0;
  std::size_t directions = 0;
  double model_over_measured = 0.0;
};
inline constexpr double kSunAngleBandEdges_deg[] = {0.0, 10.0, 20.0, 30.0, 45.0, 70.0, 100.0, 180.0};

struct MeasuredSkyScore {
  std::vector<double> wavelengths_nm;  ///< the scored ones
  std::vector<CaptureScore> captures;
  double spectral_rmse_W_m2_sr_nm = 0.0;  ///< RMS over the captures' RMSEs
  double luminance_rmse_cd_m2 = 0.0;
  double chromaticity_rmse = 0.0;
  std::vector<double> spectral_ratio;         ///< per scored wavelength: Σ model / Σ measured over every direction
  std::vector<SunAngleBand> sun_angle_bands;  ///< between kSunAngleBandEdges_deg (bands without directions kept)
  std::vector<DirectionComparison> directions;
};

/// Scores `model` against `skies` (the metric above). Throws
/// std::invalid_argument when the model gives a capture the wrong number of
/// directions or wavelengths, or when no measured wavelength is in the scored range.
MeasuredSkyScore score_measured_skies(const MeasuredSkies& skies, const CaptureSky& model);

struct MeasuredSkyOptions {
  std::string atmosphere;    ///< preset or file; empty: validate/data/cornell_2013-05-27.json (compiled in)
  std::string measurements;  ///< radiance CSV; empty: Kider 2014 (compiled in); needs `suns`
  std::string suns;          ///< the captures' sun CSV, with `measurements`
  std::string sun_spectrum;  ///< extraterrestrial sun CSV (lambda_nm, irradiance_W_m2_nm); empty: ASTM G173 in
                             ///< the evaluation's bins (compiled in)
  /// The Sun's distance at every capture [au], for the day's sun; 0: the
  /// captures' own (the ephemeris for the compiled-in ones, 1 au for files).
  /// Within the Earth's orbit, [0.983, 1.017].
  double sun_distance_au = 0.0;
  std::string out_dir = "out/validate/measured";
  std::string tables = "paper";             ///< the table sizes' name, for the report
  std::size_t reference_samples = 0;        ///< paths per wavelength of the reference check; 0: no reference check
  std::size_t reference_directions = 9;     ///< directions of the reference check, spread over the capture's
  std::string reference_capture = "11:45";  ///< also the capture of the rings plot
  bool no_plots = false;
};

/// Runs the comparison: the report on stdout, CSV files, gnuplot scripts and
/// PNG plots in options.out_dir. Throws on bad input (naming file, line, field).
void validate_measured(const MeasuredSkyOptions& options, const TablesFor& tables_for);

}  // namespace zenith::validate
