#pragma once
// A scene whose sky is placed by date and place (docs/scenes.md, "Time and
// place"), for the sky-clock and time-track tests: the Earth, its sun by the
// ephemeris, the camera standing at the site.
#include <string>

#include <nlohmann/json.hpp>

namespace zenith::scene::testing {

struct Site {
  std::string scene_name;
  std::string time;  ///< UTC, ISO 8601
  double latitude_deg = 0.0, longitude_deg = 0.0, altitude_m = 0.0;
  double look_azimuth_deg = 0.0, look_elevation_deg = 0.0;
};

/// The scene file (zenith_scene 1) of the Earth (earth-standard, albedo 0.3)
/// at `site.time`, the sun placed by the ephemeris ("sun": {}), the camera 2 m
/// above the ground at the site, looking along the site's azimuth and elevation.
inline nlohmann::json site_scene(const Site& site) {
  using nlohmann::json;
  return {
      {"zenith_scene", 1},
      {"name", site.scene_name},
      {"bodies", json::array({{{"name", "Earth"}, {"atmosphere", "earth-standard"}, {"albedo", 0.3}}})},
      {"time", site.time},
      {"site",
       {{"latitude_deg", site.latitude_deg}, {"longitude_deg", site.longitude_deg}, {"altitude_m", site.altitude_m}}},
      {"sun", json::object()},
      {"camera",
       {{"surface",
         {{"body", "Earth"},
          {"latitude_deg", site.latitude_deg},
          {"longitude_deg", site.longitude_deg},
          {"altitude_m", 2}}},
        {"look", {{"azimuth_deg", site.look_azimuth_deg}, {"elevation_deg", site.look_elevation_deg}}}}}};
}

}  // namespace zenith::scene::testing
