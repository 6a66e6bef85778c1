#include "render/frame/refraction_cache.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <stdexcept>

namespace zenith::render {

const astro::Refraction* RefractionCache::get(const scene::BodyAtmosphere& air, double altitude_m) {
  const atmosphere::AtmosphereModel& model = air.loaded.model;
  altitude_m = std::max(0.0, altitude_m);
  if (!(altitude_m < model.top_radius_m - model.ground_radius_m)) return nullptr;
  const std::string key =
      fmt::format("{} {} {:.0f}", air.source, std::hash<std::string>{}(air.loaded.parameters.dump()), altitude_m);
  if (key == key_) return refraction_.get();
  key_ = key;
  refraction_.reset();
  double refractivity = 0.0;
  try {
    refractivity = astro::ground_refractivity(air.loaded, 550.0);
  } catch (const std::invalid_argument&) {
    return nullptr;  // no Rayleigh scattering to derive a refractivity from: straight rays
  }
  // (A gas so dense that it traps horizontal rays throws here, naming the cause.)
  if (refractivity > 0.0)
    refraction_ = std::make_unique<astro::Refraction>(model.ground_radius_m, model.top_radius_m, model.rayleigh_density,
                                                      refractivity, altitude_m);
  return refraction_.get();
}

}  // namespace zenith::render
