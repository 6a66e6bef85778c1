#pragma once
// How a validation obtains the lookup tables of an atmosphere: the command
// line decides (cache, GPU or CPU precompute, sizes, orders); the checks only
// ask. Keeps the checks free of the table provider and its GL.
#include <functional>
#include <string>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"

namespace zenith::validate {

struct ValidationTables {
  atmosphere::lut::LookupTables tables;
  std::string source;  ///< "cache" or "computed on <device>", for the report
};

/// The tables of `model`; throws what the provider throws.
using TablesFor = std::function<ValidationTables(const atmosphere::AtmosphereModel& model)>;

}  // namespace zenith::validate
