#version 450
// The tiles no atmosphere touches, in one pass straight to the band's output
// (frame_rgb.glsl): no G-buffer, no per-wavelength-group passes, no resolve.
// What such a pixel shows is lit by the sun alone:
//
//   a body:    L(λ) = ρ(λ)/π · E(λ) · cos i · V(λ), ρ(λ) = a_r f_r(λ) + a_g f_g(λ) + a_b f_b(λ)
//              from the linear sRGB albedo a (colour.md), so its colour is
//              rgb = exposure · Σ_λ w(λ) L(λ) = (cos i / π) · V_rgb ⊙ M a, V the
//              share of the limb-darkened disc other bodies leave (per channel,
//              exact for a grey albedo: frame.glsl's sunlight_left_rgb),
//              M = exposure · Σ_λ w(λ) E(λ) f(λ)ᵀ, a 3×3 matrix summed over
//              every wavelength on the CPU in double (rgb_from_albedo); in
//              another body's shadow through its air, E(λ) the light left
//              there, M from the frame's table (frame.glsl's sunlit_rgb);
//   the sun:   rgb = Σ_λ exposure · w(λ) I_centre(λ) · I_λ(μ)/I_λ(1) · coverage;
//              with the limb darkening Σ_k a_k(λ) μ^k (atmosphere/solar_limb_darkening.h)
//              the sum over λ is a polynomial in μ whose coefficients
//              sun_rgb_limb[k] = Σ_λ exposure · w(λ) I_centre(λ) a_k(λ) are
//              summed on the CPU in double, and the corona's Σ_λ … m(λ), m
//              the disc's mean over its centre, likewise (sun_rgb_mean; the
//              CPU gives a uniform law to a sun drawn without limb darkening
//              or as a Gaussian point, render/frame/frame_constants.h); only
//              in the variant for the sun's tiles (SUN = 1);
//   otherwise black: tiles with neither a body nor the sun are not dispatched
//              (the band's output starts at 0).
//
// The same physics as resolve.comp with T = 1 and L = 0, summed over every
// wavelength group at once (equal to float rounding; RendererFusedPass tests).
//
// Defines: SUN (1: the sun's disc can be in the tile), ONE_BODY (1: only the
// body `one_body` can be in the tiles: no search over the bodies, its data
// from uniforms), LIMB_DARKENING, ECLIPSES, TILES_PER_GROUP (tiles per work
// group, one per z of the local size: frame.glsl's tile_pixel).
#include "frame.glsl"
#include "frame_rgb.glsl"
#include "sun_disc.glsl"
#include "surface_albedo.glsl"

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE, local_size_z = TILES_PER_GROUP) in;

uniform mat3 rgb_from_albedo;  // M above, exposure included
#if SUN
uniform vec3 sun_rgb_limb[LIMB_COEFFICIENTS];  // Σ_λ exposure · w(λ) · I_centre(λ) · a_k(λ)
uniform vec3 sun_rgb_mean;     // Σ_λ exposure · w(λ) · I_centre(λ) · m(λ)
#endif

#if ONE_BODY
uniform int one_body;  // the only body these tiles can hold (its data: the_body, frame.glsl)
#endif

void main() {
  ivec2 p;
  if (!tile_pixel(p)) return;
  vec3 rgb = vec3(0.0);
  vec3 ray;
  if (pixel_ray(p, ray)) {
#if ONE_BODY
    const float t = intersect_body(the_body, ray);
    const int b = t >= 0.0 ? one_body : -1;
    if (b >= 0) {
      const vec3 n = body_normal(the_body, ray, t);
      const float cos_i = max(dot(n, sun_direction), 0.0);
      rgb = sunlit_rgb(ray * t, one_body, rgb_from_albedo, surface_albedo(the_body, ray, t, n)) *
            sunlight_left_rgb(ray * t, one_body) * (cos_i * (1.0 / PI_F));
    }
#else
    float t;
    const int b = nearest_body(ray, t);
    if (b >= 0) {
      const vec3 n = body_normal(b, ray, t);
      const float cos_i = max(dot(n, sun_direction), 0.0);
      rgb = sunlit_rgb(ray * t, b, rgb_from_albedo, surface_albedo(b, ray, t, n)) * sunlight_left_rgb(ray * t, b) *
            (cos_i * (1.0 / PI_F));
    }
#endif
#if SUN
    else {
      const SunSample s = sun_sample(ray);
      if (s.weight > 0.0 || s.corona > 0.0) {
#if LIMB_DARKENING
        const float mu = clamp(s.mu, 0.0, 1.0);
        vec3 disc = sun_rgb_limb[LIMB_COEFFICIENTS - 1];  // Horner: Σ_k sun_rgb_limb[k] μ^k
        for (int k = LIMB_COEFFICIENTS - 2; k >= 0; --k) disc = sun_rgb_limb[k] + mu * disc;
        // The corona over the limb-darkened disc's mean radiance.
        rgb = disc * s.weight + sun_rgb_mean * s.corona;
#else
        rgb = sun_rgb_mean * (s.weight + s.corona);  // a uniform disc: its mean is its centre
#endif
      }
    }
#endif
  }
  store_frame_rgb(p, clip_negative(rgb));
}
