#pragma once
// Recorded frames and atmosphere versions as JSON (docs/shows.md,
// "Recordings"). Doubles are written by nlohmann::json, which prints the
// shortest decimal text that reads back as the same double, and read with
// strtod-exact parsing: every f64 of a FrameState survives the round trip bit
// for bit (the tests check 0.1, 1/3, 1e-300, denormals and −0).
#include <string>

#include <nlohmann/json.hpp>

#include "scene/frame_description.h"
#include "scene/scene.h"
#include "show/show.h"

namespace zenith::show {

nlohmann::json frame_to_json(const scene::FrameDescription& state);
/// Reads and checks one recorded frame at `pointer` of `file` against `scene`
/// (wavelength count, bodies with an atmosphere). Throws ConfigError.
scene::FrameDescription frame_from_json(const nlohmann::json& frame, const scene::Scene& scene, const std::string& file,
                                        const std::string& pointer);

nlohmann::json version_to_json(const AtmosphereVersion& version);

/// Checks that a frame state could be recorded (finite, unit vectors, limits);
/// throws std::invalid_argument naming the field.
void check_recordable(const scene::FrameDescription& state);

}  // namespace zenith::show
