#include "render/frame/albedo_array.h"

#include <utility>

#include "render/frame/albedo_layers.h"

namespace zenith::render {

AlbedoArray::AlbedoArray(std::filesystem::path cache_directory) : cache_directory_(std::move(cache_directory)) {}

std::string AlbedoArray::load(const scene::AlbedoSource& source) {
  std::string key = scene::albedo_key(source);
  if (!images_.contains(key))
    images_.emplace(key, source_ ? source_(source) : scene::load_albedo_map(source, cache_directory_));
  return key;
}

void AlbedoArray::ensure(const std::vector<std::string>& keys) {
  std::string joined;
  for (const std::string& k : keys) joined += k + '\n';
  if (joined == keys_ && array_.id() != 0) return;
  std::vector<const image::LinearImage*> maps;
  for (const std::string& k : keys) maps.push_back(&images_.at(k));
  const AlbedoLayers layers = resample_albedo_layers(maps);
  array_ = gl::Texture::create_2d_array_mipmapped(gl::TextureFormat::rgba16f, layers.width, layers.height,
                                                  static_cast<int>(layers.layers), layers.rgba);
  array_.set_repeat_s(true);
  keys_ = joined;
}

}  // namespace zenith::render
