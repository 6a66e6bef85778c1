#pragma once
// Projections from JSON: the "projection" object of a viewport, a dome or the
// command line. docs/projections.md lists every key.
//
//   {"type": "planar", "fov_deg": 60}                                  symmetric, square pixels
//   {"type": "planar", "left_deg": -40, "right_deg": 40, "down_deg": -25, "up_deg": 25,
//    "yaw_deg": 0, "pitch_deg": 0, "roll_deg": 0}                      asymmetric frustum
//   {"type": "fisheye", "fov_deg": 180, "tilt_deg": 0}                 dome master
//   {"type": "cylindrical", "horizontal_fov_deg": 360, "down_deg": -30, "up_deg": 30}
//   {"type": "equirectangular"}                                        360° × 180°
//   {"type": "cube", "face": "+x"}                                     one cube-map face
//
// Keys are strict (an unknown or misspelt key is an error); every parameter has
// the name, unit and range of the C++ parameter struct it fills. Errors are
// zenith::ConfigError naming `source`, the key as a JSON pointer, the value and
// the allowed range, e.g.
//   dome.json: /viewports/0/projection/fov_deg = 400: must be in [1, 360] degrees
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "warp/projection.h"

namespace zenith::warp {

/// The projection `spec` describes, for an image width_px × height_px.
/// `source` names where the spec came from (a file) and `pointer` is the JSON
/// pointer of `spec` inside it ("" for the top level); both only enter messages.
/// Throws zenith::ConfigError (core/json_reader.h) for any invalid spec,
/// including an image size out of range for the projection.
std::unique_ptr<Projection> make_projection(const nlohmann::json& spec, int width_px, int height_px,
                                            const std::string& source, const std::string& pointer = "");

}  // namespace zenith::warp
