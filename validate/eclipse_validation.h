#pragma once
// `zenith validate eclipse`: the sky of a total solar eclipse against what
// observers measured (docs/validation.md, "Eclipses"). The case is NASA's
// point of greatest eclipse on 2017-08-21 (36.9667° N, 87.6667° W, the sun
// 64° up): the contacts are found from the ephemeris (astro/solar_eclipse.h),
// and at times from first to fourth contact the reference solver — the path
// tracer with the Moon in front of the limb-darkened disc, in vector transfer
// (atmosphere/reference/README.md, "Eclipses") — and the tables with the
// Moon's shadow over them (astro/eclipsed_sky.h, the sky the renderer is to
// read) each give the zenith's radiance with and without the Moon; the same
// at the mid-totality of Lowman, Idaho, where the SQM readings were taken
// with the sun 46° up. Checks, each with its source and tolerance, on both:
//   * Lowman's mid-totality: the zenith keeps ~1e-4 of its light (Dandekar &
//     Turtle 1971, Appl. Opt. 10(6), the sun 40–50° up) — within a factor 3
//     plus three standard errors;
//   * its V surface brightness within a magnitude of the SQM readings there
//     (12.4–13.3 mag/arcsec²);
//   * and turns bluer (measured ~11 000 K against ~9 000 K): 440 nm keeps
//     more of its light than 680 nm;
//   * the horizon (10° up) brighter and redder than the zenith at every
//     azimuth (the 360° sunset of totality);
//   * the partial phases follow the light the Moon leaves of the
//     limb-darkened disc (not its area), within 5 %;
//   * the zenith darkens monotonically from first to second contact and
//     brightens from third to fourth (no jump at any contact).
// and the tables against the reference: the zenith (at both places) and the
// horizon at mid-totality within 25 %, the zenith at 90 % obscuration within
// 5 % (each plus three standard errors of the reference).
#include <cstddef>
#include <string>

#include "validate/validation_tables.h"

namespace zenith::validate {

struct EclipseValidationOptions {
  std::string out_dir = "out/validate/eclipse";
  std::string tables =
      "paper";  ///< the sizes of the tables the eclipsed sky is read from (small ones are too coarse inside the umbra)
  std::size_t samples = 400000;  ///< paths per wavelength in totality (a tenth outside it)
  bool no_plots = false;
};

/// Runs the checks, prints the report, writes CSV, a gnuplot script and its
/// PNG to options.out_dir; throws std::runtime_error naming how many checks
/// fell outside their tolerance.
void validate_eclipse(const EclipseValidationOptions& options, const TablesFor& tables);

}  // namespace zenith::validate
