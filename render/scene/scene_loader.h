#pragma once
// Reading scenes: JSON (schema "zenith_scene": 1, docs/scenes.md) → Scene.
//
// Reading is strict, as for atmospheres (atmosphere/json_reader.h): every key
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
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "render/scene/scene.h"

namespace zenith::scene {

/// Reads and resolves a scene file; relative paths in it (albedo images,
/// atmosphere files) are resolved against the file's folder. Throws ConfigError.
Scene load_scene(const std::filesystem::path& path);

/// Resolves a parsed scene. `source` names it in errors and becomes
/// Scene::source; relative paths resolve against `base_dir`. Throws ConfigError.
Scene parse_scene(const nlohmann::json& scene, const std::string& source, const std::filesystem::path& base_dir);

}  // namespace zenith::scene
