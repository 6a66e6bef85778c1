#pragma once
// CPU implementation of the incremental multiple-scattering precomputation
// (paper section 5.1; Bruneton & Neyret 2008). Multi-threaded C++; produces the
// same tables as the GPU path for the same options.
#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/lut/precompute_options.h"

namespace zenith::atmosphere::lut {

/// Computes transmittance, single scattering, then orders 2..n of multiple
/// scattering and the sky irradiance, one order at a time from the previous one.
LookupTables precompute_tables_cpu(const AtmosphereModel& model, const PrecomputeOptions& options,
                                   PrecomputeReport* report = nullptr);

}  // namespace zenith::atmosphere::lut
