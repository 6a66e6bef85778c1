#pragma once
// The Earth's sky by date and place (docs/scenes.md, "Time and place"): a scene
// that gives "time" and "site" has its sun placed by the ephemeris
// (astro/sky_positions.h) in the local horizon of the camera, instead of a
// hand-set "sky" direction; shows move that time at a rate (docs/shows.md,
// "Time track"). No GL.
#include <cstddef>
#include <optional>

#include <glm/vec3.hpp>

#include "astro/civil_time.h"
#include "astro/light_pollution.h"
#include "astro/night_sky_floor.h"
#include "astro/scintillation.h"
#include "astro/sky_positions.h"

namespace zenith::scene {

struct Scene;

/// The scene's "time" and "site".
struct SkyClock {
  astro::UtcTime time;   ///< UTC
  astro::Site site;      ///< on the body below
  std::size_t body = 0;  ///< index of the body the site is on (the Earth: the camera's reference body)
};

/// The night sky of the camera's body (docs/scenes.md, "Night sky"): the natural
/// floor's zenith brightness and the artificial glow, resolved to physical units
/// (a Bortle class becomes the zenith luminance it stands for over this
/// atmosphere's natural floor).
struct NightSky {
  astro::NightSkyFloorOptions floor;             ///< "night_sky": {"zenith_v_mag_arcsec2"}
  astro::LightPollutionOptions light_pollution;  ///< "light_pollution": zenith_mcd_m2 (0: none)
  /// "night_sky": {"scintillation": true | {c_y, pupil_mm, integration_s, turbulence_height_m}}:
  /// the stars twinkle (astro/scintillation.h); absent: steady stars.
  std::optional<astro::ScintillationOptions> scintillation;
  std::size_t body = 0;  ///< the body whose atmosphere they are seen through
};

/// Where the ephemeris puts the Sun at `time` for `clock`'s site.
struct EphemerisSun {
  glm::dvec3 direction{
      0, 0, 1};  ///< unit, world frame: the site's azimuth and geometric altitude in the camera's local horizon
  double azimuth_deg = 0.0, altitude_deg = 0.0;  ///< geometric (no refraction: the tables' rays are straight)
  double distance_au = 1.0;
  double angular_radius_rad = 0.0;
};

/// The Sun at `time` seen from `clock`'s site, as a direction in the local
/// horizon of a camera at `camera_position_m` above `scene`'s clock body.
EphemerisSun ephemeris_sun(const Scene& scene, const SkyClock& clock, const astro::AstroTime& time,
                           const glm::dvec3& camera_position_m);

}  // namespace zenith::scene
