#include "render/frame/refraction_cache.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

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
  if (!(refractivity > 0.0)) return nullptr;
  // A gas so dense that n r falls with height above the camera traps the rays near the horizontal (a duct, as
  // in Venus' dense lower air): the refraction of a ray from below the duct's reach diverges, which a table of R
  // against the apparent altitude cannot hold. Such air keeps straight rays, said once per air and altitude.
  if (const auto duct_m = astro::ducting_altitude_m(model.ground_radius_m, model.top_radius_m, model.rayleigh_density,
                                                    refractivity, altitude_m)) {
    spdlog::warn(
        "{}: the air traps horizontal rays {:.2f} km up (d(nr)/dr <= 0, ground refractivity {:.3g}); its refraction "
        "is not drawn: stars, the Moon and the Sun's disc keep their geometric places",
        air.source, *duct_m / 1000.0, refractivity);
    return nullptr;
  }
  refraction_ = std::make_unique<astro::Refraction>(model.ground_radius_m, model.top_radius_m, model.rayleigh_density,
                                                    refractivity, altitude_m);
  return refraction_.get();
}

}  // namespace zenith::render
