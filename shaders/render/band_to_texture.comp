#version 450
// Renderer::render_to_texture's band output (render/renderer.h): the band's
// pixels, as the passes left them in the output buffer (frame_rgb.glsl), into
// their rows of the frame's texture, which stays on the GPU. One work group
// per 16 × 16 tile of the band; a tile nothing was dispatched for (black:
// neither a body, the sun nor an atmosphere can be in it) is written as 0, as
// the readback path writes its rows (Renderer::read_back_band).
layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

uniform ivec2 band_origin;  // the band's first pixel in the frame
uniform ivec2 band_size;
uniform int tile_columns;   // tiles per band row (TileCones::columns)

layout(std430, binding = FRAME_RGB_BINDING) readonly buffer FrameRgb { vec4 frame_rgb[]; };
/// Per tile of the band, row by row: 1 where nothing was drawn.
layout(std430, binding = BLACK_TILES_BINDING) readonly buffer BlackTiles { uint black_tiles[]; };
/// The frame: TARGET_FORMAT is rgba32f or rgba16f (the renderer's variants).
layout(binding = OUTPUT_IMAGE, TARGET_FORMAT) uniform writeonly image2D frame;

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= band_size.x || p.y >= band_size.y) return;
  vec3 rgb = vec3(0.0);
  if (black_tiles[gl_WorkGroupID.y * uint(tile_columns) + gl_WorkGroupID.x] == 0u)
    rgb = frame_rgb[uint(p.y) * uint(band_size.x) + uint(p.x)].rgb;
  imageStore(frame, band_origin + p, vec4(rgb, 1.0));
}
