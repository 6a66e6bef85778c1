#pragma once
// What a cluster's nodes compare of the sky data each reads from its own copy
// of stellarium-data (docs/protocol.md, FrameState's sky.star_catalogue): the
// star catalogue's identity (astro/star_catalogue.h) joined with the Moon's
// albedo map's (render/night/moon_albedo_map.h), so every node draws the same
// stars and the same Moon. The data never travel, only this digest.
#include <filesystem>
#include <string>

namespace zenith::astro {

/// stellarium-data's Moon texture (scripts/bootstrap installs it).
inline const std::filesystem::path kStellariumMoonMap = "/usr/share/stellarium/textures/moon.png";

/// SHA-256 of the map file's bytes (hex), "" when it cannot be read (the
/// renderer then draws a uniform Moon).
std::string moon_map_identity(const std::filesystem::path& path);

/// SHA-256 (hex) over "<catalogue>\nmoon_map <map>\n", or the catalogue's
/// identity unchanged when `moon_map_sha256` is "" (no map: a uniform Moon).
std::string sky_data_identity(const std::string& catalogue_sha256, const std::string& moon_map_sha256);

}  // namespace zenith::astro
