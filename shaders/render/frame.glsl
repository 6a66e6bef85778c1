// Frame data shared by the render passes (gbuffer.comp, atmosphere_pass.comp,
// resolve.comp, direct_light.comp, atmosphere_tile.comp), filled by render/renderer.cpp.
//
// Precision: every position is camera-relative and was computed in double on
// the CPU; the GPU sees directions (unit vectors), distances from the camera
// and, for each body, |c|² − R² computed in double, so a ray from 1 m above the
// ground and one from 40 AU away are intersected equally well in float.
//
// The frame is rendered in horizontal bands; `band_origin` is the band's first
// pixel in the full image, so every pass computes the same ray for a pixel
// whichever band it falls in (projection.glsl).

#include "projection.glsl"

#include "body.glsl"  // struct Body (render/frame/gpu_body.h's GpuBody)

layout(std430, binding = BODIES_BINDING) readonly buffer Bodies { Body bodies[]; };
/// The one body a pass is about, as plain uniforms (render/renderer.cpp sets
/// it to bodies[i]): the planet of an atmosphere's passes, the only body of a
/// direct-light tile list. llvmpipe reads storage buffers lane by lane inside
/// branches, uniforms once per SIMD vector.
uniform Body the_body;

uniform int body_count;
uniform mat3 camera_to_world;
uniform ivec2 band_origin;  // first pixel of this band in the full image
uniform ivec2 band_size;
uniform vec3 sun_direction;        // world, unit
uniform float sun_angular_radius;  // [rad]
uniform float pixel_angle;         // upper bound of one pixel's angular size [rad] (Projection::max_pixel_angle_rad)
/// The footprint of the pixel pixel_ray() last gave a ray for [rad]: what is
/// sized per pixel (the albedo's level of detail) uses it, not the bound over
/// the image. pixel_angle for the closed-form projections (uniform enough); for
/// a ray table (a warp mesh, whose bound can be tens of degrees where it parks
/// unused nodes) the local value from the neighbouring rays.
float pixel_footprint = 0.0;

/// The TILE_SIZE² tiles (kTileSize of render/frame/tile_culling.h) of band
/// pixels a pass covers, one work group per tile:
/// tiles[tile_offset + i] for i < tile_count, packed as column | row <<
/// TILE_ROW_SHIFT (render/frame/tile_culling.h's pack_tile, which also defines
/// TILE_COLUMN_MASK). The renderer classifies tiles on the CPU
/// (one atmosphere, several, surface or sun only, empty) and dispatches each
/// pass over its own list, so a pass holds only the code its tiles need: on a
/// CPU rasterizer (llvmpipe runs 8 invocations per SIMD vector under a mask) a
/// branch skipped by every pixel still costs, a tile not dispatched does not.
layout(std430, binding = TILES_BINDING) readonly buffer Tiles { uint tiles[]; };
uniform int tile_offset;
uniform int tile_count;

/// This invocation's band pixel: false past the end of the list or the band.
/// A pass may give each work group TILES_PER_GROUP tiles (default 1), one per
/// z of its local size, the renderer dispatching that many fewer groups.
#ifndef TILES_PER_GROUP
#define TILES_PER_GROUP 1
#endif
bool tile_pixel(out ivec2 p) {
  const uint tile_index = (gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x) * TILES_PER_GROUP + gl_LocalInvocationID.z;
  p = ivec2(0);
  if (tile_index >= uint(tile_count)) return false;
  const uint tile = tiles[uint(tile_offset) + tile_index];
  p = ivec2(int(tile & TILE_COLUMN_MASK), int(tile >> TILE_ROW_SHIFT)) * TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
  return all(lessThan(p, band_size));
}

/// The world-space unit ray of band pixel `p` (integer, band-local), or false
/// where the projection has no ray.
#if defined(PROJECTION_KIND) && (PROJECTION_KIND == PROJECTION_KIND_PLANAR || PROJECTION_KIND == PROJECTION_KIND_CUBE_FACE)
/// projection_params[0..2].xyz turned into the world frame (camera_to_world ×,
/// in double on the CPU): the affine ray of a planar projection straight in
/// world coordinates, one normalization instead of two and no rotation per pixel.
uniform vec3 world_ray_x, world_ray_y, world_ray_centre;
#endif

/// A ray-table pixel's footprint from the table's rays of its neighbours: with
/// Δx, Δy the differences to the next pixel across and down (the one before
/// where the next has no ray or lies past the band), the longer diagonal of
/// the parallelogram they span, max(|Δx + Δy|, |Δx − Δy|) (chords, within
/// 1e-4 of the angles at a few degrees). The image's bound where a pixel has no
/// neighbour with a ray on either side, and never more than the bound.
float ray_table_footprint(ivec2 image_pixel, vec3 d) {
  const ivec2 q = image_pixel - projection_table_origin, size = textureSize(projection_ray_table, 0);
  vec3 delta[2];
  for (int axis = 0; axis < 2; ++axis) {
    const ivec2 step = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
    bool found = false;
    for (int side = 1; side >= -1 && !found; side -= 2) {
      const ivec2 n = q + side * step;
      if (any(lessThan(n, ivec2(0))) || any(greaterThanEqual(n, size))) continue;
      const vec4 t = texelFetch(projection_ray_table, n, 0);
      if (t.w > 0.0) {
        delta[axis] = float(side) * (t.xyz - d);
        found = true;
      }
    }
    if (!found) return pixel_angle;
  }
  return min(pixel_angle, max(length(delta[0] + delta[1]), length(delta[0] - delta[1])));
}

bool pixel_ray(ivec2 p, out vec3 ray) {
  pixel_footprint = pixel_angle;
#if defined(PROJECTION_KIND) && (PROJECTION_KIND == PROJECTION_KIND_PLANAR || PROJECTION_KIND == PROJECTION_KIND_CUBE_FACE)
  const vec2 from_centre = vec2(band_origin + p) + vec2(0.5) - vec2(projection_params[0].w, projection_params[1].w);
  ray = normalize(from_centre.x * world_ray_x + from_centre.y * world_ray_y + world_ray_centre);
  return true;
#else
  vec3 d;
  if (!projection_ray(vec2(band_origin + p) + vec2(0.5), d)) return false;
  if (projection_kind == PROJECTION_KIND_RAY_TABLE) pixel_footprint = ray_table_footprint(band_origin + p, d);
  ray = normalize(camera_to_world * d);
  return true;
#endif
}

vec3 body_centre(Body body) { return body.centre.xyz * body.centre.w; }
vec3 body_centre(int b) { return body_centre(bodies[b]); }

/// Where a ray meets a sphere of radius R centred at distance D along unit
/// direction c from the camera: q = D (ray·c) is the distance to the point of
/// closest approach and disc = R² − p² (p the ray's distance from the centre)
/// the square of half the chord. disc is formed as q² − C, with C = D² − R²
/// computed in double on the CPU, while the camera is near the sphere (no
/// cancellation from 1 m above the ground), and as R² − (D sin θ)² from further
/// away (q² − C would lose everything to rounding at 40 AU). False: no intersection.
bool sphere_chord(vec3 ray, vec3 centre_dir, float centre_distance, float R, float C, out float q, out float disc) {
  const float cos_theta = dot(ray, centre_dir);
  q = centre_distance * cos_theta;
  if (C < R * R) {
    disc = q * q - C;
  } else {
    const float p = centre_distance * length(cross(ray, centre_dir));
    disc = (R - p) * (R + p);
  }
  return disc >= 0.0;
}

/// Distance along unit `ray` to the first intersection with a body (front face),
/// or −1: t = C / (q + √disc), the stable root.
float intersect_body(Body body, vec3 ray) {
  const float C = body.shape.y;
  if (C <= 0.0) return -1.0;  // inside the body: the scene loader forbids it
  float q, disc;
  if (!sphere_chord(ray, body.centre.xyz, body.centre.w, body.shape.x, C, q, disc)) return -1.0;
  if (q <= 0.0) return -1.0;
  return C / (q + sqrt(disc));
}
float intersect_body(int b, vec3 ray) { return intersect_body(bodies[b], ray); }

/// The nearest body along `ray` and the distance to it [m]; −1 where none.
int nearest_body(vec3 ray, out float distance_m) {
  distance_m = 3.4e38;
  int hit_body = -1;
  for (int b = 0; b < body_count; ++b) {
    const float t = intersect_body(b, ray);
    if (t >= 0.0 && t < distance_m) {
      distance_m = t;
      hit_body = b;
    }
  }
  return hit_body;
}

/// Outward unit normal of a body at distance t along `ray` (world frame).
vec3 body_normal(Body body, vec3 ray, float t) { return normalize(ray * t - body_centre(body)); }
vec3 body_normal(int b, vec3 ray, float t) { return body_normal(bodies[b], ray, t); }

/// The normal in the body frame (for its albedo map).
vec3 to_body_frame(Body body, vec3 n) {
  return vec3(dot(body.world_to_body0.xyz, n), dot(body.world_to_body1.xyz, n), dot(body.world_to_body2.xyz, n));
}

/// Angle between two unit vectors, accurate for small angles too (acos is not).
float angle_between(vec3 a, vec3 b) {
  return 2.0 * asin(clamp(0.5 * length(a - b), 0.0, 1.0));
}

/// Area of the intersection of two discs of radii a and b whose centres are d
/// apart (all angles in radians, small-angle plane geometry).
float disc_overlap_area(float a, float b, float d) {
  if (d >= a + b) return 0.0;
  if (d <= abs(a - b)) return PI_F * min(a, b) * min(a, b);
  const float ca = clamp((d * d + a * a - b * b) / (2.0 * d * a), -1.0, 1.0);
  const float cb = clamp((d * d + b * b - a * a) / (2.0 * d * b), -1.0, 1.0);
  const float k = max(0.0, (-d + a + b) * (d + a - b) * (d - a + b) * (d + a + b));
  return a * a * acos(ca) + b * b * acos(cb) - 0.5 * sqrt(k);
}

#ifndef AIR_SHADOWS
#define AIR_SHADOWS 0
#endif
#if ECLIPSES && AIR_SHADOWS
/// Other bodies' shadows through their own air (render/frame/air_shadows.h),
/// at most MAX_AIR_SHADOWS: shadow s is cast by the body whose centre lies at
/// air_shadow_occluder[s].xyz from the camera [m] on body air_shadow_bodies[s].y,
/// out to air_shadow_occluder[s].w [m] from its axis, its AIR_SHADOW_ENTRIES
/// entries evenly over [0, reach] in air_shadow_data from index
/// air_shadow_bodies[s].z, air_shadow_bodies[s].w values each: the colour
/// matrix of direct_light.comp with the sunlight left (three columns), then the
/// sunlight left E / E_sun per lane of each wavelength group. Where the shadows
/// are (uniforms) is read once per SIMD vector on a CPU rasterizer; only the
/// values are read per pixel.
layout(std430, binding = AIR_SHADOWS_BINDING) readonly buffer AirShadows { vec4 air_shadow_data[]; };
uniform int air_shadow_count;  // 0 while a light other than the sun draws (the Moon's)
uniform vec4 air_shadow_occluder[MAX_AIR_SHADOWS];
uniform ivec4 air_shadow_bodies[MAX_AIR_SHADOWS];  // occluder, receiver, first value, values per entry
#ifndef WAVELENGTH_GROUP_DECLARED  // atmosphere/physics.glsl's, where a pass includes it
uniform int wavelength_group;     // the group a per-group pass draws
#endif

/// Whether body b's air casts one of the frame's shadows on body `self`: then
/// that shadow's table replaces b's geometric one.
bool casts_air_shadow(int b, int self) {
  for (int s = 0; s < air_shadow_count; ++s)
    if (air_shadow_bodies[s].x == b && air_shadow_bodies[s].y == self) return true;
  return false;
}

/// Where the point at camera-relative p on body `self` lies in an air shadow:
/// the index of the values of the entry below it, the values per entry and the
/// weight of the next entry; false outside every air shadow on `self`. The
/// distance from the axis is |(p − c) + ((p − c)·s) s| for the occluder's
/// centre c, the sunlight parallel to s = −sun_direction.
bool air_shadow_entry(vec3 p, int self, out int value, out int stride, out float next) {
  value = 0;
  stride = 0;
  next = 0.0;
  for (int s = 0; s < air_shadow_count; ++s) {
    if (air_shadow_bodies[s].y != self) continue;
    const vec3 from_occluder = p - air_shadow_occluder[s].xyz;
    const float behind = -dot(from_occluder, sun_direction);
    if (behind <= 0.0) continue;  // on the sun's side of the occluder
    const float f = length(from_occluder + behind * sun_direction) / air_shadow_occluder[s].w *
                    float(AIR_SHADOW_ENTRIES - 1);
    if (!(f < float(AIR_SHADOW_ENTRIES - 1))) continue;  // beyond its reach: the whole sun
    const int k = int(f);
    stride = air_shadow_bodies[s].w;
    value = air_shadow_bodies[s].z + k * stride;
    next = f - float(k);
    return true;
  }
  return false;
}
#endif

#if ECLIPSES
/// The sun's limb darkening behind the bodies' shadows over its disc's mean,
/// b_k = a_k / m (I(μ)/I(1) = Σ a_k μ^k, m = Σ a_k 2/(k + 2):
/// atmosphere/solar_limb_darkening.h), per lane of the group, and per channel
/// of direct_light.comp's colour (Σ_λ w_c E b_k / Σ_λ w_c E:
/// render/frame/frame_constants.h's shadow_limb_rgb). A uniform disc: (1, 0, …).
uniform vec4 shadow_limb_lanes[LIMB_COEFFICIENTS];
uniform vec4 shadow_limb_rgb[LIMB_COEFFICIENTS];  // .w unused

/// Adds to J the moments of the sun's disc (angular radius r) that a disc of
/// angular radius a covers, its centre d from the sun's (radians, small-angle
/// plane geometry): J_k = (1/π r²) ∫_covered μ^k dA, μ = √(1 − ρ²/r²) at
/// distance ρ from the disc's centre, so that the covered share of the light
/// is Σ_k b_k J_k (Σ_k b_k · 2/(k + 2) = 1). J_0 is the overlap's area
/// (disc_overlap_area: a uniform disc's share, exact). For k ≥ 1: the rings
/// wholly behind the occluder (ρ < a − d) give ∫_μ1^1 μ^k 2μ dμ =
/// 2(1 − μ1^(k+2))/(k + 2); a ring partly behind it (|a − d| < ρ < a + d) is
/// covered over c(ρ) = acos((ρ² + d² − a²) / 2ρd) / π, integrated as
/// ∫ μ^k c 2ρ dρ / r² with ρ = lo + (hi − lo)(1 − cos θ)/2, which leaves the
/// square-root ends of c(ρ) and μ(ρ) smooth, by 8-point Gauss–Legendre in θ.
void add_covered_moments(float r, float a, float d, inout float J[LIMB_COEFFICIENTS]) {
  const float area = disc_overlap_area(r, a, d);
  if (area <= 0.0) return;
  J[0] += area / (PI_F * r * r);
  const float full = clamp(a - d, 0.0, r) / r;
  if (full > 0.0) {
    const float mu1 = sqrt(max(0.0, 1.0 - full * full));
    float power = mu1 * mu1;  // μ1^(k+2)
    for (int k = 1; k < LIMB_COEFFICIENTS; ++k) {
      power *= mu1;
      J[k] += 2.0 * (1.0 - power) / float(k + 2);
    }
  }
  const float lo = abs(a - d), hi = min(a + d, r);
  if (hi <= lo) return;
  // 8-point Gauss–Legendre in θ (nodes ±x_i, weights w_i on [−1, 1]).
  const float x[4] = float[4](0.1834346425, 0.5255324099, 0.7966664774, 0.9602898565);
  const float w[4] = float[4](0.3626837834, 0.3137066459, 0.2223810345, 0.1012285363);
  for (int j = 0; j < 8; ++j) {
    const float node = j < 4 ? -x[j] : x[j - 4];
    const float theta = 0.5 * PI_F * (1.0 + node);
    const float rho = lo + (hi - lo) * 0.5 * (1.0 - cos(theta));
    const float covered = acos(clamp((rho * rho + d * d - a * a) / (2.0 * rho * d), -1.0, 1.0)) / PI_F;
    const float mu = sqrt(max(0.0, 1.0 - (rho / r) * (rho / r)));
    // c 2ρ dρ / r², dρ = (hi − lo) sin θ / 2 dθ, dθ = π/2 dx.
    float weight = w[j < 4 ? j : j - 4] * covered * rho * (hi - lo) * sin(theta) * (0.5 * PI_F) / (r * r);
    for (int k = 1; k < LIMB_COEFFICIENTS; ++k) {
      weight *= mu;
      J[k] += weight;
    }
  }
}

/// The moments of the sun's disc that every body but `self` covers, seen from
/// the point at camera-relative position p (eclipses: the Moon's shadow on
/// the Earth, the Earth's on the Moon), summed over the bodies. A body whose
/// air shadows `self` (the Earth the Moon, where the Earth has its atmosphere)
/// is left to the air shadow's table (sunlight_left, sunlit_rgb).
void covered_moments(vec3 p, int self, out float J[LIMB_COEFFICIENTS]) {
  for (int k = 0; k < LIMB_COEFFICIENTS; ++k) J[k] = 0.0;
  for (int b = 0; b < body_count; ++b) {
    if (b == self) continue;
#if AIR_SHADOWS
    if (casts_air_shadow(b, self)) continue;
#endif
    const vec3 to_centre = body_centre(b) - p;
    const float distance = length(to_centre);
    const float R = bodies[b].shape.x;
    if (distance <= R) continue;
    const vec3 dir = to_centre / distance;
    if (dot(dir, sun_direction) <= 0.0) continue;  // behind the point
    const float radius = asin(min(R / distance, 1.0));
    add_covered_moments(sun_angular_radius, radius, angle_between(dir, sun_direction), J);
  }
}

/// What the bodies leave of the limb-darkened disc seen from the point at
/// camera-relative p on body `self`, 1 − Σ_k b_k J_k, for the four values of
/// `b` at once (the lanes of a group, or the channels of an RGB colour).
vec4 disc_left(vec4 b[LIMB_COEFFICIENTS], vec3 p, int self) {
  float J[LIMB_COEFFICIENTS];
  covered_moments(p, self, J);
  vec4 covered = vec4(0.0);
  for (int k = 0; k < LIMB_COEFFICIENTS; ++k) covered += b[k] * J[k];
  return clamp(vec4(1.0) - covered, 0.0, 1.0);
}
#endif

/// The share of the sun's light reaching the point at camera-relative p on
/// body `self`, per lane of the group `wavelength_group`: what the bodies
/// leave of the limb-darkened disc times the sunlight an air shadow leaves there.
vec4 sunlight_left(vec3 p, int self) {
#if ECLIPSES
  vec4 left = disc_left(shadow_limb_lanes, p, self);
#if AIR_SHADOWS
  int value, stride;
  float next;
  if (air_shadow_entry(p, self, value, stride, next)) {
    const int lanes = value + 3 + wavelength_group;
    left *= mix(air_shadow_data[lanes], air_shadow_data[lanes + stride], next);
  }
#endif
  return left;
#else
  return vec4(1.0);
#endif
}

/// sunlight_left per channel of direct_light.comp's colour (an air shadow's
/// light is in sunlit_rgb's matrix instead).
vec3 sunlight_left_rgb(vec3 p, int self) {
#if ECLIPSES
  return disc_left(shadow_limb_rgb, p, self).rgb;
#else
  return vec3(1.0);
#endif
}

/// direct_light.comp's M a (rgb = (cos i V / π) M a) at the point at
/// camera-relative p on body `self` of albedo a: M `rgb_from_albedo` (the whole
/// sun's), or in an air shadow the matrix summed over the wavelengths with the
/// sunlight left there, which no single factor of M could give (the umbra's
/// light is red).
vec3 sunlit_rgb(vec3 p, int self, mat3 rgb_from_albedo, vec3 albedo) {
#if ECLIPSES && AIR_SHADOWS
  int value, stride;
  float next;
  if (air_shadow_entry(p, self, value, stride, next)) {
    vec3 rgb = vec3(0.0);
    for (int column = 0; column < 3; ++column)
      rgb += mix(air_shadow_data[value + column], air_shadow_data[value + column + stride], next).xyz * albedo[column];
    return rgb;
  }
#endif
  return rgb_from_albedo * albedo;
}
