#pragma once
// Between a scene and the frame description that travels each frame
// (scene/frame_description.h): the cluster's master builds frame N of its
// default show from the scene (here: the configured scene with the sun turning
// slowly), every node applies each frame to its copy of the scene, a show
// applies its frames with their atmosphere versions (show::apply_state).
// Everything that varies per frame is in the frame description; the static
// parts (bodies, albedo, atmospheres' parameters) come from the scene file.
#include <cstdint>
#include <vector>

#include "scene/frame_description.h"
#include "scene/scene.h"

namespace zenith::scene {

/// The default show without a show file: frame N is the scene as configured
/// with the sun turned by N · sun_step_deg about the polar axis of the body
/// nearest the camera (world +z without bodies), westward as the day advances;
/// with sun_step_deg = 0 every frame has the configured sun direction exactly.
FrameDescription default_show_frame(const Scene& scene, std::uint64_t frame, double sun_step_deg,
                                    const std::vector<AtmosphereTableRef>& atmospheres, std::uint32_t render_flags);

/// Throws std::invalid_argument when `frame` does not fit `scene`: its
/// irradiance must hold one value per scene wavelength (else master and node
/// read different scenes).
void check_frame(const FrameDescription& frame, const Scene& scene);

/// A frame's sky fields for the instant `time` (has_time set) and a star
/// catalogue's identity (all zero: not checked).
SkyFrame sky_frame(const astro::AstroTime& time, const core::Sha256Digest& star_catalogue = {});

/// Copies the per-frame parts of `frame` (camera, exposure, sun, the sky
/// clock's instant where both have one) into `scene`;
/// the atmospheres stay (a node replaces them by table version itself, a show
/// by its versions). Throws as check_frame, and then changes nothing.
void apply_frame(const FrameDescription& frame, Scene& scene);

}  // namespace zenith::scene
