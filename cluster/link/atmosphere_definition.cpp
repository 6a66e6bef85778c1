#include "cluster/link/atmosphere_definition.h"

#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "atmosphere/model_hash.h"
#include "core/json_reader.h"
#include "core/strings.h"

namespace zenith::cluster {

using core::cat;

bool fits_body(const atmosphere::LoadedAtmosphere& loaded, const scene::Body& body) {
  return std::abs(loaded.model.ground_radius_m - body.radius_m) <= 1.0;
}

atmosphere::LoadedAtmosphere resolve_definition(const AtmosphereDefinition& d, const scene::Scene& scene) {
  const scene::Body* body = scene.find_body(d.body_name);
  if (body == nullptr || !body->atmosphere)
    throw std::runtime_error(
        cat("AtmosphereDefinition for body '", d.body_name, "', which has no atmosphere in ", scene.source.string()));
  nlohmann::json parameters;
  try {
    parameters = nlohmann::json::parse(d.parameters_json);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(cat("AtmosphereDefinition of '", d.body_name, "': not JSON: ", e.what()));
  }
  atmosphere::LoadedAtmosphere loaded = atmosphere::resolve_atmosphere(
      parameters, cat("the master's definition of the atmosphere of '", d.body_name, "'"),
      atmosphere::LoadOptions{scene.wavelengths_nm});
  if (!fits_body(loaded, *body))
    throw std::runtime_error(cat("AtmosphereDefinition of '", d.body_name, "': ground radius ",
                                 loaded.model.ground_radius_m, " m, the body's radius is ", body->radius_m, " m"));
  const Digest hash = digest_from_hex(atmosphere::lookup_table_hash(loaded.model));
  if (hash != d.table_hash)
    throw std::runtime_error(cat("AtmosphereDefinition of '", d.body_name, "': the parameters hash to ",
                                 short_hex(hash), " here, the master says ", short_hex(d.table_hash),
                                 " (do master and node read the same scene, with the same wavelengths?)"));
  return loaded;
}

}  // namespace zenith::cluster
