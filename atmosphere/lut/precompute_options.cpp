// Validation of PrecomputeOptions, shared by the CPU and GPU precomputes.
#include "atmosphere/lut/precompute_options.h"

#include <stdexcept>
#include <string>

namespace zenith::atmosphere::lut {

void check_precompute_options(const PrecomputeOptions& o) {
  if (o.max_orders < 1) throw std::invalid_argument("max_orders must be >= 1");
  if (o.transmittance_samples < 1 || o.scattering_samples < 1 || o.sphere_zenith_samples < 1)
    throw std::invalid_argument("transmittance_samples, scattering_samples and sphere_zenith_samples must be >= 1");
  if (o.coarse_ray_first_order < 2)
    throw std::invalid_argument("coarse_ray_first_order is " + std::to_string(o.coarse_ray_first_order) +
                                ": must be >= 2 (single scattering keeps every sample)");
  if (o.coarse_ray_stride < 1 || o.coarse_ray_stride > o.scattering_samples)
    throw std::invalid_argument("coarse_ray_stride is " + std::to_string(o.coarse_ray_stride) +
                                ": must be in [1, scattering_samples = " + std::to_string(o.scattering_samples) + "]");
}

}  // namespace zenith::atmosphere::lut
