#pragma once
// The lunar eclipses of `zenith validate eclipse` (docs/validation.md, "Lunar
// eclipses"): the Moon's brightness in the Earth's shadow (astro/lunar_eclipse.h,
// the earth-advanced preset at 31 wavelengths from 380 to 780 nm, the Moon's
// face of uniform albedo, the Kurucz sun in the V band) against photometry of
// real eclipses, each with its source and tolerance:
//   * the drop at mid-totality of 2003-05-16, 2004-10-28 and 2022-11-08,
//     within a magnitude, each with the Danjon class observers gave it and
//     the one the model implies (astro/danjon_scale.h);
//   * the light curve of 2019-01-21 through totality (V photometry), each
//     measured change within half a magnitude;
//   * the umbra's edge beyond the solid planet's, as crater timings find it;
//   * the umbra red at its centre and bluer at its rim (the ozone's band).
// Writes lunar_eclipse_2019.csv (and its plot) to the output directory.
#include <filesystem>
#include <vector>

#include "validate/validation_check.h"

namespace zenith::validate {

std::vector<ValidationCheck> lunar_eclipse_checks(const std::filesystem::path& out_dir, bool plots);

}  // namespace zenith::validate
