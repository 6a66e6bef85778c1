#pragma once
// `zenith validate night`: the night sky's physics against published figures
// (docs/night-sky.md). Prints each check — ours, the published value, the
// difference and the tolerance — and fails (exit 1) when one is outside:
//  1. positions: the Sun, the Moon and a star against almanac examples (NREL
//     SPA, Meeus' Astronomical Algorithms);
//  2. refraction through the model's air (and through the U.S. Standard
//     Atmosphere 1976's lapse rate) against Bennett and Sæmundsson;
//  3. extinction at 550 nm of earth-standard and earth-advanced against the
//     standard clear-sky ~0.2 mag per air mass, and its growth toward the
//     horizon against Pickering's (2002) air mass;
//  4. the zenith's V surface brightness through twilight (the tables'
//     scattered sunlight plus the natural night-sky floor) against Patat et
//     al. 2006's fit to Paranal's measurements;
//  5. Schaefer's naked-eye limiting magnitude at a dark zenith and through
//     twilight, and the number of catalogue stars a typical observer sees at
//     sun −6°, −12°, −18° (Greenwich, the 2026 winter solstice);
//  6. the moonlit zenith (the tables lit by a full Moon, as the renderer's
//     moonlight passes) against Krisciunas & Schaefer 1991's model, and the
//     limiting magnitude it leaves.
// Writes CSV, gnuplot scripts and PNG charts (twilight brightness, limiting
// magnitude, refraction, the moonlit zenith) to --out.
#include <string>

#include "validate/validation_tables.h"

namespace zenith::validate {

struct NightValidationOptions {
  std::string out_dir = "out/validate/night";
  std::string tables = "paper";           ///< the table sizes' name, for the report and the plots' titles
  std::string preset = "earth-advanced";  ///< the Earth atmosphere for twilight and stars
  bool no_plots = false;                  ///< the data, but no gnuplot scripts or PNG
};

/// Runs every check, prints the report, writes CSV, gnuplot scripts and PNG
/// charts to options.out_dir; throws std::runtime_error naming how many
/// checks fell outside their tolerance.
void validate_night(const NightValidationOptions& options, const TablesFor& tables_for);

}  // namespace zenith::validate
