#pragma once
// A scene: bodies (analytic spheres, optionally with an atmosphere), a sun and
// a camera, in one world frame with positions in metres, in double. Read from
// JSON (configs/scenes/, schema in docs/scenes.md) by scene_loader.h, which
// resolves every convenience form (a camera standing on a body at a latitude
// and longitude, a sun given by its elevation and azimuth in the camera's local
// sky) into the plain world-frame values below. No GL here.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "atmosphere/parameters.h"
#include "scene/sky_clock.h"

namespace zenith::scene {

/// Where a body's surface reflectance comes from. Colours are linear sRGB
/// reflectances in [0, 1] (not display values); render/ turns them into a
/// reflectance at each working wavelength.
struct AlbedoSource {
  enum class Kind { constant, image, procedural };
  Kind kind = Kind::constant;
  glm::dvec3 colour_linear_rgb{0.3, 0.3, 0.3};  ///< Kind::constant
  std::filesystem::path image_path;             ///< Kind::image: absolute, equirectangular (PNG = sRGB, EXR = linear)
  std::string procedural;  ///< Kind::procedural: a generator of albedo_map.h ("earth", "moon", "mars", "checker")
  std::uint32_t seed = 1;  ///< Kind::procedural
  int width_px = 1024, height_px = 512;  ///< Kind::procedural: size of the generated map
};

/// An atmosphere around a body, with the parameter set it was resolved from.
struct BodyAtmosphere {
  std::string source;  ///< "preset:earth-advanced", a file path, or "inline" (for messages and reports)
  atmosphere::LoadedAtmosphere loaded;  ///< resolved at the scene's wavelengths
};

/// An analytic sphere. Body frame: +z the north pole, +x the equator at
/// longitude 0, +y the equator at longitude 90° E; albedo maps are
/// equirectangular in this frame (column 0 at longitude −180°, row 0 at the north pole).
struct Body {
  std::string name;
  double radius_m = 0.0;
  glm::dvec3 position_m{0.0};          ///< world frame
  glm::dquat orientation{1, 0, 0, 0};  ///< body frame → world frame (unit)
  AlbedoSource albedo;
  std::optional<BodyAtmosphere> atmosphere;  ///< its ground radius equals radius_m
};

/// The sun: a limb-darkened disc (render/ applies the limb darkening).
struct Sun {
  glm::dvec3 direction{0, 0, 1};    ///< unit, world frame, toward the sun (the sun is at infinity)
  double angular_radius_rad = 0.0;  ///< half the apparent diameter
  /// Spectral irradiance at the scene, per working wavelength [W m^-2 nm^-1]
  /// (e.g. the Kurucz spectrum at 1 AU scaled by (1 AU / distance)²).
  std::vector<double> irradiance_W_m2_nm;
};

/// The largest exposure of a scene, a show's exposure track, a recording or an
/// operator's command: exposure is in (0, kMaxExposure].
inline constexpr double kMaxExposure = 1e6;

struct Camera {
  glm::dvec3 position_m{0.0};          ///< world frame
  glm::dquat orientation{1, 0, 0, 0};  ///< camera frame (+x right, +y up, −z forward) → world (unit)
  /// Multiplies radiance [W m^-2 sr^-1 nm^-1] before tone mapping (paper's
  /// exponential operator 1 − exp(−exposure · L)); > 0.
  double exposure = 10.0;
};

/// The most bodies a scene may have (the scene loader's limit; the renderer's
/// body buffer holds this many).
inline constexpr std::size_t kMaxBodies = 64;

struct Scene {
  std::string name;
  std::filesystem::path source;  ///< the file it was read from (empty when built in code)
  std::vector<double>
      wavelengths_nm;  ///< working wavelengths of every atmosphere and of the output (default 680, 550, 440)
  std::vector<Body> bodies;
  Sun sun;
  Camera camera;
  /// The scene's "time" and "site" (the Earth only): then the sun above was
  /// placed by the ephemeris at that time (scene/sky_clock.h), and shows may move it.
  std::optional<SkyClock> sky_clock;
  /// The scene's "night_sky" and "light_pollution", when either is given.
  std::optional<NightSky> night_sky;

  /// The body named `name`, or null.
  const Body* find_body(const std::string& name) const;
};

/// The unit vector of the body frame at a latitude and longitude (radians):
/// (cos φ cos λ, cos φ sin λ, sin φ).
glm::dvec3 direction_from_latitude_longitude(double latitude_rad, double longitude_rad);

/// Checks the invariants every consumer may rely on (for scenes built in code;
/// load_scene checks them with messages naming the JSON keys): at least one
/// wavelength; bodies with distinct non-empty names, finite positions, radius
/// > 0, unit orientations, not intersecting one another, at most 8 with an
/// atmosphere, each atmosphere's ground radius within 1 m of the body's radius
/// and its wavelengths the scene's; a unit sun direction, angular radius in
/// (0, 15°], one finite irradiance ≥ 0 per wavelength; a camera with a finite
/// position at least 0.1 m outside every body, a unit orientation and
/// exposure in (0, 1e6]. Throws std::invalid_argument naming the first violation.
void check_scene(const Scene& scene);

}  // namespace zenith::scene
