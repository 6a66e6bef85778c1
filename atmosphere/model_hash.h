#pragma once
// Identity of a lookup-table set.
//
// The hash covers exactly the quantities that shape the precomputed tables:
// wavelengths, radii, ground albedo, every coefficient, density profile and
// phase function in use (the aerosol profile and phase only when there is an
// aerosol), and the air-mass mode. It does not cover what only the render
// pass uses (exposure, sun irradiance and angular size, tone mapping, camera)
// nor the model's name, so changing those never triggers a precompute.
//
// Numbers enter as decimal text rounded to 12 significant digits, so the same
// parameters give the same hash on every machine even if a libm differs in the
// last bit of a derived coefficient.
#include <cstddef>
#include <string>

#include "atmosphere/atmosphere_model.h"

namespace zenith::atmosphere {

/// Bumped whenever the meaning of a table changes (parameterization, layout).
/// 6: the sun-angle axis of the scattering tables extends to μs_min = −sin 3α
/// (was −H/rt), parameterization.h.
inline constexpr int kLookupTableFormatVersion = 6;

/// The canonical text that is hashed (one "key: values" line per quantity).
std::string canonical_description(const AtmosphereModel& model);

/// SHA-256 of canonical_description(), as 64 lowercase hex digits.
std::string lookup_table_hash(const AtmosphereModel& model);

}  // namespace zenith::atmosphere
