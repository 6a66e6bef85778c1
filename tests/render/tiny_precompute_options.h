#pragma once
// Tiny table sizes and sample counts for the GPU precompute's tests
// (gpu_precompute_test.cpp, glsl_nvidia_rules_test.cpp): every code path, a
// fraction of a second on the CPU.
#include "atmosphere/lut/precompute_options.h"

namespace zenith::render::testing {

inline atmosphere::lut::PrecomputeOptions tiny_precompute_options() {
  atmosphere::lut::PrecomputeOptions o;
  o.sizes = atmosphere::lut::TableSizes{16, 8, 8, 4, 4, 16, 8, 4};
  o.max_orders = 3;
  o.sphere_zenith_samples = 4;
  o.transmittance_samples = 100;
  o.scattering_samples = 20;
  return o;
}

}  // namespace zenith::render::testing
