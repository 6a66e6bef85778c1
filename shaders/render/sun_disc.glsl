// Where a ray sees the sun's disc (scene/sun_disc.h, docs/rendering.md):
// the disc's coverage of the pixel, antialiased over one pixel, and μ, the
// cosine at the sun's surface for the limb darkening I(μ)/I(1) = Σ a_k(λ) μ^k,
// √(1 − sin²θ / sin²θ_disc) at angle θ from the centre (exact, not the
// small-angle form). A sun under 1.5 pixels in radius is a Gaussian splat of
// σ = sun_point_sigma instead (its pixel-sampled sum keeps the irradiance to
// 1e-3; a disc would alias): weight exp(−θ²/2σ²), μ = 1 (no limb).
// Refraction (render/frame/sun_refraction.h): a ray arriving at apparent
// altitude h came from true altitude h − R(h); the ray is turned down by R(h)
// in its vertical plane before it is compared with the geometric disc, which
// lifts the disc and flattens it as the eye sees a low sun.
// A solar eclipse (render/frame/sun_occulter.h): the Moon's disc, placed as
// geometrically as the sun's and compared with the same unrefracted ray, masks
// the disc's pixels, antialiased as its edge (no rim in totality, where the
// edges lie within a pixel); a Gaussian sun carries the light the Moon leaves
// in sun_centre_radiance already.
// Include after frame.glsl.

uniform float sun_draw_radius;  // the disc's radius [rad]
uniform float sun_point_sigma;  // > 0: the sun is smaller than the pixels; drawn as a Gaussian of this σ [rad]
// The footprint of the pixels where the sun lands [rad]
// (Projection::pixel_angle_rad_at(sun)): the disc's edge is antialiased over it.
// Not frame.glsl's pixel_angle, the worst case over the image, which through a
// warp mesh can be tens of degrees.
uniform float sun_pixel_angle;
uniform vec3 sun_occulter_direction;  // world, unit: the Moon's centre
uniform float sun_occulter_radius;    // its angular radius [rad]; 0: nothing in front of the sun

// R(h) over the apparent altitudes the disc can cover; sun_lift_count 0: no refraction.
const int kSunLiftSamples = 32;  // render/frame/sun_refraction.h kSunLiftSamples
uniform int sun_lift_count;
uniform vec3 sun_lift_up;        // the camera's vertical, world
uniform float sun_lift_first;    // apparent altitude of sun_lift_rad[0] [rad]
uniform float sun_lift_step;     // between entries [rad]
uniform float sun_lift_rad[kSunLiftSamples];

/// The direction `ray` came from before the air bent it: turned toward the
/// ground by R at its apparent altitude, ray cos R − n sin R with n the unit
/// vector along the ray's vertical plane toward the zenith (the rotation form
/// keeps the angle to the sun exact near the zenith, where asin is not).
vec3 unrefracted(vec3 ray) {
  if (sun_lift_count < 2) return ray;
  const float s = clamp(dot(ray, sun_lift_up), -1.0, 1.0);
  const float x = clamp((asin(s) - sun_lift_first) / sun_lift_step, 0.0, float(sun_lift_count - 1));
  const int i = min(int(x), sun_lift_count - 2);
  const float R = mix(sun_lift_rad[i], sun_lift_rad[i + 1], x - float(i));
  const vec3 toward_zenith = sun_lift_up - s * ray;
  const float l = length(toward_zenith);
  if (l < 1e-6) return ray;
  return ray * cos(R) - toward_zenith * (sin(R) / l);
}

struct SunSample {
  float weight;  // coverage of the pixel by the disc, or the Gaussian's value; 0: no sun
  float mu;      // cosine at the sun's surface (limb darkening); 1 for the Gaussian
  float corona;  // the corona's radiance over the disc's mean radiance (an eclipse only); 0: none
};

// The corona, drawn in a solar eclipse (sun_occulter_radius > 0), where it can
// be seen: elsewhere it is ~1e-6 of the disc against an aureole of 1e-4 of it.
// Its K + F brightness over the disc's mean radiance at ρ solar radii from the
// centre (Baumbach 1937, Astron. Nachr. 263, 121):
//   1e-6 (0.0532 ρ^−2.5 + 1.425 ρ^−7 + 2.565 ρ^−17),
// ~1.1e-6 of the sun's light in all (half a full Moon), faded to nothing from
// 4 to kCoronaOuterRadii solar radii (smoothstep: no edge at any exposure;
// 10 % of the profile's light lies beyond 4). Spherically symmetric: no
// streamers. Behind the Moon as the disc is.
const float kCoronaOuterRadii = 6.0;  // render/frame/sun_occulter.h kCoronaOuterRadii

float corona_over_mean_disc(float rho) {
  if (rho >= kCoronaOuterRadii) return 0.0;
  const float fade = 1.0 - smoothstep(4.0, kCoronaOuterRadii, rho);
  return 1e-6 * (0.0532 * pow(rho, -2.5) + 1.425 * pow(rho, -7.0) + 2.565 * pow(rho, -17.0)) * fade;
}

SunSample sun_sample(vec3 ray) {
  const vec3 geometric = unrefracted(ray);
  const float theta = angle_between(geometric, sun_direction);
  if (sun_point_sigma > 0.0) {
    const float x = theta / sun_point_sigma;
    return SunSample(x < 6.0 ? exp(-0.5 * x * x) : 0.0, 1.0, 0.0);
  }
  const float R = sun_draw_radius;
  const bool eclipse = sun_occulter_radius > 0.0;
  if (theta >= (eclipse ? kCoronaOuterRadii * R : R) + sun_pixel_angle) return SunSample(0.0, 1.0, 0.0);
  // Signed distances from the pixel's centre to the edges, in pixels: inside the sun, outside the Moon.
  const float inside_sun = (R - theta) / sun_pixel_angle;
  float coverage = clamp(inside_sun + 0.5, 0.0, 1.0);
  float corona = 0.0;
  if (eclipse) {
    // What the Moon's disc leaves of the pixel: the strip between two near-parallel edges,
    // min(d_sun, ½) + min(d_moon, ½), so a Moon that holds the sun leaves no rim at its edge.
    const float outside_moon = (angle_between(geometric, sun_occulter_direction) - sun_occulter_radius) / sun_pixel_angle;
    coverage = clamp(min(inside_sun, 0.5) + min(outside_moon, 0.5), 0.0, 1.0);
    // The corona where neither disc covers the pixel.
    const float off_disc = clamp(0.5 - inside_sun, 0.0, 1.0);
    corona = corona_over_mean_disc(max(theta / R, 1.0)) * min(off_disc, clamp(outside_moon + 0.5, 0.0, 1.0));
  }
  const float s = min(sin(theta) / sin(R), 1.0);
  return SunSample(coverage, sqrt(max(1.0 - s * s, 0.0)), corona);
}
