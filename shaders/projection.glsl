// The ray of an output pixel on the GPU: the twin of warp/planar_projection.cpp
// and warp/fisheye_projection.cpp, evaluated from the 16 floats their gpu()
// returns (the layouts are documented there and in docs/projections.md).
// Include with #include "projection.glsl"; the C++ side sets
//   projection_kind      = int(GpuProjection::kind)
//   projection_params[i] = GpuProjection::params[i]
//
// `pixel` is a continuous position in the CPU's convention: x right, y DOWN,
// (0, 0) the image's top-left corner, pixel (i, j) centred at (i + 0.5, j + 0.5).
// A compute shader passes vec2(gl_GlobalInvocationID.xy) + 0.5; a fragment
// shader drawing into a framebuffer (origin bottom-left) passes
// vec2(gl_FragCoord.x, float(height) - gl_FragCoord.y).
// `direction` is the unit ray in the camera frame (+x right, +y up, −z forward).

#define PROJECTION_KIND_PLANAR 0
#define PROJECTION_KIND_FISHEYE 1

uniform int projection_kind;
uniform vec4 projection_params[4];

// False (and direction = 0) where the pixel has no ray: outside a fisheye's circle.
bool projection_ray(vec2 pixel, out vec3 direction) {
  if (projection_kind == PROJECTION_KIND_PLANAR) {
    // The unnormalized ray is affine in the pixel, taken about the image centre
    // (x_c, y_c) = params[0].w, params[1].w: (x − x_c) · ∂d/∂x + (y − y_c) · ∂d/∂y + d(x_c, y_c).
    vec2 from_centre = pixel - vec2(projection_params[0].w, projection_params[1].w);
    direction = normalize(from_centre.x * projection_params[0].xyz + from_centre.y * projection_params[1].xyz +
                          projection_params[2].xyz);
    return true;
  }
  // Fisheye: params[0] = (centre x, centre y, radians per pixel, fov / 2);
  // params[1..3] = image right, image up and the optical axis in the camera frame.
  vec4 circle = projection_params[0];
  vec2 offset = vec2(pixel.x - circle.x, circle.y - pixel.y);  // image y points down
  float r = length(offset);
  float theta = r * circle.z;  // angle from the optical axis
  if (theta > circle.w) {
    direction = vec3(0.0);
    return false;
  }
  // sin θ / r tends to radians-per-pixel at the centre, where the azimuth is undefined.
  float sin_theta_over_r = r > 0.0 ? sin(theta) / r : circle.z;
  direction = normalize(sin_theta_over_r * (offset.x * projection_params[1].xyz + offset.y * projection_params[2].xyz) +
                        cos(theta) * projection_params[3].xyz);
  return true;
}
