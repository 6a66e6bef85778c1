#pragma once
// Between a scene and the FrameState that travels each frame: the master
// builds the state of frame N from its show (here: the configured scene with
// the sun turning slowly), every node applies it to its copy of the scene.
// Everything that varies per frame is in the FrameState; the static parts
// (bodies, albedo, atmospheres' parameters) come from the scene file that
// master and nodes read from the same configuration.
#include <cstdint>
#include <vector>

#include "cluster/protocol/messages.h"
#include "scene/scene.h"

namespace zenith::cluster {

/// The default show without a show file: frame N is the scene as configured
/// with the sun turned by N · sun_step_deg about the polar axis of the body
/// nearest the camera (world +z without bodies), westward as the day advances;
/// with sun_step_deg = 0 every frame has the configured sun direction exactly.
FrameState default_show_frame(const scene::Scene& scene, std::uint64_t frame, double sun_step_deg,
                              const std::vector<AtmosphereTableRef>& atmospheres, std::uint32_t render_flags);

/// Copies the per-frame parts of `state` (camera, exposure, sun) into `scene`.
/// Throws std::invalid_argument when the state's irradiance does not hold one
/// value per scene wavelength (master and node read different scenes).
void apply_frame_state(const FrameState& state, scene::Scene& scene);

}  // namespace zenith::cluster
