#pragma once
// An AtmosphereDefinition (docs/protocol.md) turned back into an atmosphere:
// the parameters the master sent, resolved at the receiver's scene
// wavelengths and checked against the table hash they must give. Nodes use it
// for every version the master defines, a standby master for every version it
// follows (docs/cluster.md, "Standby master").
#include "atmosphere/parameters.h"
#include "cluster/protocol/messages.h"
#include "scene/scene.h"

namespace zenith::cluster {

/// Whether `loaded` can be `body`'s atmosphere: its ground radius is the body's radius (within 1 m).
bool fits_body(const atmosphere::LoadedAtmosphere& loaded, const scene::Body& body);

/// The atmosphere `definition` describes, resolved at `scene`'s wavelengths.
/// Throws std::runtime_error naming the body when the scene has no such body
/// with an atmosphere, the JSON does not parse or resolve, the ground radius
/// is not the body's, or the parameters hash to another table set than
/// `definition.table_hash` (master and receiver read different scenes).
atmosphere::LoadedAtmosphere resolve_definition(const AtmosphereDefinition& definition, const scene::Scene& scene);

}  // namespace zenith::cluster
