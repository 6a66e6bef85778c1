#version 450
// Last pass of a wavelength group: what lies behind every atmosphere — an
// airless body's sunlit surface or the sun's disc — seen through the running
// transmittance T, added to the in-scattered radiance L of the atmosphere
// passes; then the group's radiance is turned into linear sRGB
// (image/colour.h: rgb = Σ weights · L per wavelength), multiplied by the
// exposure and added to the frame (the first group writes it).
//
// Defines: SUN_DISC (0: no disc), LIMB_DARKENING (0: a uniform disc), ECLIPSES.
#include "frame.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(binding = 0, rgba32f) uniform readonly image2D gbuffer_hit;
layout(binding = 1, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(binding = 2, rgba32f) uniform readonly image2D radiance_sum;
layout(binding = 3, rgba32f) uniform readonly image2D transmittance_product;
layout(binding = 4, rgba32f) uniform image2D frame_rgb;

uniform bool first_group;
uniform float exposure;
uniform vec4 sun_irradiance;       // E_sun per wavelength of the group [W m^-2 nm^-1]
uniform vec4 sun_centre_radiance;  // at the drawn disc's centre [W m^-2 sr^-1 nm^-1] (render/scene/sun_disc.h)
uniform vec4 limb_exponent;        // α(λ) of I(μ)/I(1) = μ^α
uniform float sun_draw_radius;     // the disc's radius [rad]
uniform float sun_point_sigma;     // > 0: the sun is smaller than the pixels; drawn as a Gaussian of this σ [rad]
uniform vec4 albedo_from_r;
uniform vec4 albedo_from_g;
uniform vec4 albedo_from_b;
uniform vec4 rgb_from_lanes_r;     // R = dot(rgb_from_lanes_r, L), etc.
uniform vec4 rgb_from_lanes_g;
uniform vec4 rgb_from_lanes_b;

/// The sun's limb-darkened disc along `ray`, antialiased over one pixel;
/// sun_centre_radiance is its centre radiance (render/scene/sun_disc.h), so the
/// disc integrates to the sun's irradiance. μ at angle θ from the centre is √(1 − sin²θ / sin²θ_disc),
/// the cosine at the sun's surface (exact, not the small-angle form).
vec4 sun_disc(vec3 ray) {
#if SUN_DISC
  const float theta = angle_between(ray, sun_direction);
  if (sun_point_sigma > 0.0) {
    // A sun under 1.5 pixels in radius: a Gaussian splat of σ = 0.7 pixel whose
    // pixel-sampled sum keeps the irradiance to 1e-3 (a disc would alias).
    const float x = theta / sun_point_sigma;
    return x < 6.0 ? sun_centre_radiance * exp(-0.5 * x * x) : vec4(0.0);
  }
  const float R = sun_draw_radius;
  if (theta >= R + pixel_angle) return vec4(0.0);
  const float coverage = clamp((R - theta) / pixel_angle + 0.5, 0.0, 1.0);
  const float s = min(sin(theta) / sin(R), 1.0);
  const float mu = sqrt(max(1.0 - s * s, 0.0));
#if LIMB_DARKENING
  const vec4 profile = pow(vec4(max(mu, 1e-4)), limb_exponent);
#else
  const vec4 profile = vec4(1.0);
#endif
  return sun_centre_radiance * profile * coverage;
#else
  return vec4(0.0);
#endif
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, band_size))) return;
  const vec4 hit = imageLoad(gbuffer_hit, p);
  vec3 rgb = vec3(0.0);
  vec3 ray;
  if (hit.z != 0.0 && pixel_ray(p, ray)) {
    vec4 L = imageLoad(radiance_sum, p);
    const vec4 T = imageLoad(transmittance_product, p);
    if (any(greaterThan(T, vec4(0.0)))) {
      if (hit.x >= 0.0) {
        // A body no atmosphere pass has shaded: lit by the direct sun only (ρ/π E cos i V).
        const int b = int(hit.y);
        const vec3 n = body_normal(b, ray, hit.x);
        const vec3 albedo = imageLoad(gbuffer_albedo, p).rgb;
        const vec4 rho = albedo_from_r * albedo.r + albedo_from_g * albedo.g + albedo_from_b * albedo.b;
        const float cos_i = max(dot(n, sun_direction), 0.0);
        L += T * rho * (1.0 / 3.14159265) * sun_irradiance * (cos_i * sun_visibility(ray * hit.x, b));
      } else {
        L += T * sun_disc(ray);
      }
    }
    rgb = vec3(dot(rgb_from_lanes_r, L), dot(rgb_from_lanes_g, L), dot(rgb_from_lanes_b, L)) * exposure;
  }
  if (first_group) imageStore(frame_rgb, p, vec4(rgb, 1.0));
  else imageStore(frame_rgb, p, imageLoad(frame_rgb, p) + vec4(rgb, 0.0));
}
