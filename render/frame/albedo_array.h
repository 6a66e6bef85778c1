#pragma once
// The bodies' albedo maps on the GPU: each source's map loaded once and kept
// (by scene::albedo_key), and the frame's maps as the layers of one array texture
// (render/frame/albedo_layers.h: body b's map is layer b), rebuilt only when
// the frame's list of maps changes. The render passes read it as albedo_maps
// (shaders/render/surface_albedo.glsl).
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "image/image_io.h"
#include "render/gl/texture.h"
#include "scene/albedo_map.h"
#include "scene/albedo_map_cache.h"

namespace zenith::render {

class AlbedoArray {
 public:
  /// With a `cache_directory`, generated maps are read from it and stored in
  /// it (scene/albedo_map_cache.h); empty: generated each time.
  explicit AlbedoArray(std::filesystem::path cache_directory = {});

  /// Where maps not held come from instead (Renderer::set_albedo_source).
  void set_source(std::function<image::LinearImage(const scene::AlbedoSource&)> source) { source_ = std::move(source); }

  /// Loads `source`'s map unless it is held already (the source, else the
  /// cache or scene::load_albedo_map, which throws for a missing or unreadable
  /// image); returns its key.
  std::string load(const scene::AlbedoSource& source);
  /// The array of the maps of `keys` (each loaded before), layer b the map of
  /// keys[b]; x repeats (longitude). Kept while the list stays the same.
  void ensure(const std::vector<std::string>& keys);
  /// The array texture (empty before the first ensure()).
  const gl::Texture& texture() const { return array_; }

 private:
  std::filesystem::path cache_directory_;  // empty: no cache
  std::function<image::LinearImage(const scene::AlbedoSource&)> source_;
  std::map<std::string, image::LinearImage> images_;  // by scene::albedo_key
  std::string keys_;                                  // the array's keys, one a line
  gl::Texture array_;                                 // one layer per body, all at the largest map's size
};

}  // namespace zenith::render
