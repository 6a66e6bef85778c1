#pragma once
// Reading scenes: JSON (schema "zenith_scene": 1, docs/scenes.md) → Scene.
//
// Reading is strict, as for atmospheres (core/json_reader.h): every key
// has a unit and a range, unknown keys are errors, and every error is a
// zenith::ConfigError naming the file, the key as a JSON pointer, the value and
// what is allowed, e.g.
//   earth-sunset.json: /camera/exposure = -1: must be in (0, 1e+06]
//   earth-moon.json: /bodies/1: body "Moon" intersects body "Earth" (/bodies/0): ...
// Every convenience form (a camera standing on a body at a latitude and
// longitude, a view or a sun given by azimuth and elevation in the camera's
// local sky, a named atmosphere preset) is resolved here into the plain
// world-frame values of scene.h; atmospheres are resolved at the scene's
// wavelengths. Albedo images are checked to exist, not read (load_albedo_map
// reads them).
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.h"

namespace zenith::scene {

/// Reads and resolves a scene file; relative paths in it (albedo images,
/// atmosphere files) are resolved against the file's folder. Throws ConfigError.
Scene load_scene(const std::filesystem::path& path);

/// Resolves a parsed scene. `source` names it in errors and becomes
/// Scene::source; relative paths resolve against `base_dir`. Throws ConfigError.
Scene parse_scene(const nlohmann::json& scene, const std::string& source, const std::filesystem::path& base_dir);

// ---- the parts of a scene file that shows key over time (docs/shows.md)

/// Where a camera object (docs/scenes.md, "camera") puts the camera: the
/// resolved Camera, and what a show needs to interpolate between such objects.
struct CameraPlacement {
  /// With "surface": the coordinates as written, in radians and metres.
  struct Surface {
    double latitude_rad = 0.0, longitude_rad = 0.0, altitude_m = 0.0;
  };
  Camera camera;
  /// Index into the bodies of the body whose local horizon azimuths and
  /// elevations refer to: the one the camera stands on ("surface"), else the
  /// one whose surface is nearest (nearest_body).
  std::size_t reference_body = 0;
  std::optional<Surface> surface;  ///< given with "surface"
};

/// Reads one camera object, as the "camera" of a scene file, among the bodies
/// of `scene` (and its wavelengths). `pointer` is the object's JSON pointer in
/// `source` for error messages ("/camera/3"). Throws ConfigError.
CameraPlacement parse_camera(const nlohmann::json& camera, const Scene& scene, const std::string& source,
                             const std::string& pointer);

/// Reads one sun object, as the "sun" of a scene file; "sky" directions are in
/// the local horizon of `camera`, "position_m" is seen from it, irradiances are
/// at the scene's wavelengths. Throws ConfigError.
Sun parse_sun(const nlohmann::json& sun, const Scene& scene, const CameraPlacement& camera, const std::string& source,
              const std::string& pointer);

/// The body whose surface is nearest to a world point (bodies not empty).
std::size_t nearest_body(const std::vector<Body>& bodies, const glm::dvec3& point_m);

}  // namespace zenith::scene
