// A band of a frame as Renderer::render_on_gpu hands it to a fragment pass
// (render/renderer.h, GpuBand): the output buffer the passes wrote
// (frame_rgb.glsl: one vec4 per pixel, rows of band_size.x pixels) and the
// band's black-tile flags (1 where nothing was dispatched: those pixels hold
// stale values and read as 0 here, as the readback path writes them).

uniform ivec2 band_origin;  // the band's first pixel in the frame
uniform ivec2 band_size;
uniform int tile_columns;   // tiles per band row (TileCones::columns)

layout(std430, binding = FRAME_RGB_BINDING) readonly buffer FrameRgb { vec4 frame_rgb[]; };
/// Per tile of the band, row by row: 1 where nothing was drawn.
layout(std430, binding = BLACK_TILES_BINDING) readonly buffer BlackTiles { uint black_tiles[]; };

/// The radiance × exposure of frame pixel p (a pixel of this band).
vec3 band_rgb(ivec2 frame_pixel) {
  const ivec2 p = frame_pixel - band_origin;
  if (black_tiles[uint(p.y / TILE_SIZE) * uint(tile_columns) + uint(p.x / TILE_SIZE)] != 0u) return vec3(0.0);
  return frame_rgb[uint(p.y) * uint(band_size.x) + uint(p.x)].rgb;
}
