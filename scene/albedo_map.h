#pragma once
// Surface reflectance maps of bodies: procedural generators and the loading of
// an AlbedoSource into an image.
//
// Every map is equirectangular in the body frame of scene.h: column 0 starts at
// longitude −180°, row 0 at the north pole (+z), pixel (i, j) is sampled at its
// centre, longitude −180° + (i + ½)·360°/w, latitude 90° − (j + ½)·180°/h.
// Values are linear sRGB reflectances clamped to [0, 1].
//
// The generators evaluate 3D fields (gradient-noise fBm, cellular craters) at
// the pixel's point on the unit sphere, never at (longitude, latitude): a
// 3D field restricted to the sphere has no seam at ±180° and no pinching at the
// poles, and the same seed gives the same planet at every map size (the
// thresholds that set e.g. the ocean fraction are quantiles over a fixed set of
// points on the sphere, not over the pixels).
#include <cstdint>
#include <string>
#include <vector>

#include "image/image_io.h"
#include "scene/scene.h"

namespace zenith::scene {

/// The procedural generators: "earth", "moon", "mars", "checker".
///  * earth   — oceans (~70 % of the area, dark blue, mean reflectance ~0.06,
///              lighter over continental shelves), continents whose cover follows
///              latitude and a moisture field (rain forest, grass and forest,
///              subtropical deserts, boreal forest and tundra, bare rock on high
///              ground), polar ice (~0.7) poleward of ~70° (Antarctic ~65°).
///  * moon    — highland grey 0.13–0.19, dark maria (~0.075, ~17 % of the area,
///              concentrated on the near side, the body's +x hemisphere), craters
///              at four scales with dark floors, bright rims and ejecta.
///  * mars    — rust (0.35, 0.18, 0.08) with dark Syrtis-like regions concentrated
///              in the southern low latitudes, brighter dusty regions and small
///              polar caps (poleward of ~82°).
///  * checker — 0.2/0.8 grey in 30° × 30° cells, 0.8 in the cell at
///              longitude [−180°, −150°), latitude (60°, 90°] (for tests).
std::vector<std::string> albedo_generators();

/// A map from a generator, deterministic for a seed. Throws std::invalid_argument
/// for an unknown generator (listing the generators) or a size outside
/// width [2, 16384], height [2, 8192].
image::LinearImage generate_albedo_map(const std::string& generator, std::uint32_t seed, int width_px, int height_px);

/// A fingerprint of a generator's planet for a seed: the SHA-256 (hex) of its
/// colours at the 4096 points of a Fibonacci lattice on the sphere (about 3°
/// apart), independent of any map size. A change to a generator that moves
/// its colours anywhere at the scale of its fields changes the fingerprint, so
/// a map stored under it (scene/albedo_map_cache.h) is never one an older
/// generator made. A few milliseconds. Throws as generate_albedo_map for an
/// unknown generator.
std::string procedural_albedo_fingerprint(const std::string& generator, std::uint32_t seed);

/// A key identifying an albedo source: the same key, the same map (the
/// renderer loads each source once and keeps it; the offline renderer reads
/// them ahead by it).
std::string albedo_key(const AlbedoSource& albedo);

/// The map of a body: a 1×1 image of the colour (Kind::constant), the image file
/// read by image::read_image (Kind::image; throws its std::runtime_error), or a
/// generated map (Kind::procedural). Values clamped to [0, 1].
image::LinearImage load_albedo_map(const AlbedoSource& source);

}  // namespace zenith::scene
