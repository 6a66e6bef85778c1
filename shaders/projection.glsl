// The ray of an output pixel on the GPU: the twin of warp/planar_projection.cpp,
// warp/fisheye_projection.cpp, warp/cylindrical_projection.cpp,
// warp/equirectangular_projection.cpp and warp/cube_face_projection.cpp,
// evaluated from the 16 floats their gpu() returns (the layouts are documented
// there and in docs/projections.md).
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

// PROJECTION_KIND_PLANAR, _FISHEYE, _CYLINDRICAL, _EQUIRECTANGULAR, _CUBE_FACE
// and _RAY_TABLE are warp/projection.h's ProjectionKind, defined by the C++
// side in every shader (render/shader_bindings.h's shader_interface_defines()).

#ifdef PROJECTION_KIND
// Specialised for one kind (render/renderer.cpp compiles its passes per kind
// in use): the other kinds' code is not in the program. Mesa's llvmpipe turns
// small branches into selects, so with a uniform kind every pixel would pay
// for every kind's rays (sines and cosines included).
const int projection_kind = PROJECTION_KIND;
#else
uniform int projection_kind;
#endif
uniform vec4 projection_params[4];
/// PROJECTION_KIND_RAY_TABLE: the rays of the current band's pixels, computed on
/// the CPU (xyz: the camera-frame ray, w: 1 where there is one, 0 where not);
/// texel (0, 0) is pixel projection_table_origin of the image.
layout(binding = RAY_TABLE_UNIT) uniform sampler2D projection_ray_table;
uniform ivec2 projection_table_origin;

// False (and direction = 0) where the pixel has no ray: outside a fisheye's
// circle, beyond half a turn of a cylinder or an equirectangular range, past
// an equirectangular pole.
bool projection_ray(vec2 pixel, out vec3 direction) {
  if (projection_kind == PROJECTION_KIND_RAY_TABLE) {
    const vec4 t = texelFetch(projection_ray_table, ivec2(floor(pixel)) - projection_table_origin, 0);
    direction = t.xyz;
    return t.w > 0.0;
  }
  if (projection_kind == PROJECTION_KIND_PLANAR || projection_kind == PROJECTION_KIND_CUBE_FACE) {
    // The unnormalized ray is affine in the pixel, taken about the image centre
    // (x_c, y_c) = params[0].w, params[1].w: (x − x_c) · ∂d/∂x + (y − y_c) · ∂d/∂y + d(x_c, y_c).
    // A cube face is the same map (a signed permutation instead of a rotation).
    vec2 from_centre = pixel - vec2(projection_params[0].w, projection_params[1].w);
    direction = normalize(from_centre.x * projection_params[0].xyz + from_centre.y * projection_params[1].xyz +
                          projection_params[2].xyz);
    return true;
  }
  if (projection_kind == PROJECTION_KIND_CYLINDRICAL) {
    // params[0] = (x_c, radians per pixel across, y_c, tangent per pixel down);
    // params[1..3].xyz = the cylinder frame's right, axis and backward;
    // params[1].w = tangent at y_c, params[2].w = half a turn in pixels.
    vec4 grid = projection_params[0];
    float from_centre_x = pixel.x - grid.x;
    if (abs(from_centre_x) > projection_params[2].w) {
      direction = vec3(0.0);
      return false;
    }
    float phi = from_centre_x * grid.y;                                // azimuth from forward, toward right
    float v = projection_params[1].w + (pixel.y - grid.z) * grid.w;  // height on the unit cylinder
    direction = normalize(sin(phi) * projection_params[1].xyz + v * projection_params[2].xyz -
                          cos(phi) * projection_params[3].xyz);
    return true;
  }
  if (projection_kind == PROJECTION_KIND_EQUIRECTANGULAR) {
    // params[0] = (x_c, radians of longitude per pixel, y_c, radians of latitude per pixel, negative);
    // params[1] = (longitude at x_c, latitude at y_c, half a turn in pixels, π/2).
    vec4 grid = projection_params[0];
    vec4 centre = projection_params[1];
    float from_centre_x = pixel.x - grid.x;
    float latitude = centre.y + (pixel.y - grid.z) * grid.w;
    if (abs(from_centre_x) > centre.z || abs(latitude) > centre.w) {
      direction = vec3(0.0);
      return false;
    }
    float longitude = centre.x + from_centre_x * grid.y;
    float cos_latitude = cos(latitude);
    direction = normalize(vec3(cos_latitude * sin(longitude), sin(latitude), -cos_latitude * cos(longitude)));
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
