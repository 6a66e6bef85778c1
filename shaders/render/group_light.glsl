// The light of one group of 4 wavelengths that does not come from an
// atmosphere — an airless body's sunlit surface, the sun's disc — and the
// group's share of a pixel's colour: spectral radiance → linear sRGB
// (image/colour.h: rgb = Σ weights · L per wavelength) × exposure, added to
// the band's output (frame_rgb.glsl; the first group writes it, the last
// clips negatives). Shared by resolve.comp and atmosphere_tile.comp.
//
// Include after frame.glsl. Defines: SUN_DISC (0: no disc), LIMB_DARKENING
// (0: a uniform disc), ECLIPSES.
#include "frame_rgb.glsl"
#include "sun_disc.glsl"

uniform bool first_group;
uniform bool last_group;
uniform float exposure;
uniform vec4 sun_irradiance;       // E_sun per wavelength of the group [W m^-2 nm^-1]
uniform vec4 sun_centre_radiance;  // at the drawn disc's centre [W m^-2 sr^-1 nm^-1] (scene/sun_disc.h)
uniform vec4 limb_polynomial[LIMB_COEFFICIENTS];  // a_k(λ) of I(μ)/I(1) = Σ a_k μ^k (atmosphere/solar_limb_darkening.h)
uniform vec4 albedo_from_r;        // reflectance of each wavelength from linear sRGB albedo
uniform vec4 albedo_from_g;
uniform vec4 albedo_from_b;
uniform vec4 rgb_from_lanes_r;     // R = dot(rgb_from_lanes_r, L), etc.
uniform vec4 rgb_from_lanes_g;
uniform vec4 rgb_from_lanes_b;

/// Reflectance per wavelength of the group from a linear sRGB albedo.
vec4 reflectance(vec3 albedo) { return albedo_from_r * albedo.r + albedo_from_g * albedo.g + albedo_from_b * albedo.b; }

/// The sun's limb-darkened disc along `ray` (sun_disc.glsl), and in an eclipse
/// its corona; sun_centre_radiance is the disc's centre radiance, so the disc
/// integrates to the sun's irradiance.
vec4 sun_disc(vec3 ray) {
#if SUN_DISC
  const SunSample s = sun_sample(ray);
  if (s.weight <= 0.0 && s.corona <= 0.0) return vec4(0.0);
#if LIMB_DARKENING
  const float mu = clamp(s.mu, 0.0, 1.0);
  vec4 profile = limb_polynomial[LIMB_COEFFICIENTS - 1];  // Horner: Σ a_k μ^k
  for (int k = LIMB_COEFFICIENTS - 2; k >= 0; --k) profile = limb_polynomial[k] + mu * profile;
  vec4 mean_over_centre = vec4(0.0);  // the limb-darkened disc's mean radiance over its centre's: 2 Σ a_k / (k + 2)
  for (int k = 0; k < LIMB_COEFFICIENTS; ++k) mean_over_centre += limb_polynomial[k] * (2.0 / float(k + 2));
#else
  const vec4 profile = vec4(1.0);
  const vec4 mean_over_centre = vec4(1.0);
#endif
  return sun_centre_radiance * (profile * s.weight + mean_over_centre * s.corona);
#else
  return vec4(0.0);
#endif
}

/// Body b, where the ray meets it at distance t, lit by the direct sun only: ρ/π E cos i V.
vec4 airless_surface(int b, vec3 ray, float t, vec3 albedo) {
  const vec3 n = body_normal(b, ray, t);
  const float cos_i = max(dot(n, sun_direction), 0.0);
  return reflectance(albedo) * (1.0 / PI_F) * sun_irradiance * (cos_i * sunlight_left(ray * t, b));
}

/// Adds the group's radiance L at band pixel p to the band's output.
void add_group_rgb(ivec2 p, vec4 L) {
  vec3 rgb = vec3(dot(rgb_from_lanes_r, L), dot(rgb_from_lanes_g, L), dot(rgb_from_lanes_b, L)) * exposure;
  if (!first_group) rgb += load_frame_rgb(p);
  store_frame_rgb(p, last_group ? clip_negative(rgb) : rgb);
}
