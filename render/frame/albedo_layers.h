#pragma once
// The bodies' albedo maps as the layers of one array texture (the render
// passes' albedo_maps, shaders/render/surface_albedo.glsl): body b's map is
// layer b, every layer at the largest width and height among the maps. No GL:
// the renderer uploads the layers (render/renderer.cpp).
#include <cstddef>
#include <string>
#include <vector>

#include "image/image_io.h"
#include "scene/albedo_map.h"

namespace zenith::render {

/// The layers of the array, RGBA floats, x fastest, then y, then the layer.
struct AlbedoLayers {
  int width = 1, height = 1;
  std::size_t layers = 1;   ///< at least one (white) when there is no map
  std::vector<float> rgba;  ///< width · height · 4 per layer; alpha 1
};

/// Each map resampled bilinearly to the largest width and height among them:
/// texel centres map to texel centres, x wraps (longitude), y clamps (the poles).
AlbedoLayers resample_albedo_layers(const std::vector<const image::LinearImage*>& maps);

}  // namespace zenith::render
