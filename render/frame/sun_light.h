#pragma once
// Whether the sun lights an atmosphere visibly this frame (docs/night-sky.md,
// "Moonlight", "The sun below the night"): by night the sun can stand so far
// below the horizon that no point any pixel reads is lit — for the Earth below
// μs_min = −sin 3α, about 24° down, where the tables hold their vanishing
// values — and its passes draw a black sky at the full cost of the day's.
// The test is the Moon's (render/night/moon_light.h): the tables' bound for the
// sun's cosine over every point a pixel reads (atmosphere/lut/sky_radiance_bound.h),
// times the sun's irradiance, the colour weights and the exposure, against half
// an 8-bit code step at black (kInvisibleDisplayStep). Where it cannot reach
// that, the renderer leaves the atmosphere's one-pass tiles that hold nothing
// but its sky and ground at zero (the band's output cleared first, one buffer
// clear) instead of running the sun's pass over them; tiles where another body or the sun's disc can be,
// and the G-buffer path's, are drawn as before (what lies beyond the shell is
// lit by the sun whatever the atmosphere's night). No GL.
#include <vector>

#include "render/frame/frame_in_progress.h"
#include "render/frame/tile_classification.h"

namespace zenith::render {

/// Whether `pass`'s one-pass tiles of `variant` are left black this frame:
/// the sun's light through the atmosphere is invisible (AtmospherePass::sunlit
/// false) and the tiles hold only its sky and ground (no other body, not the
/// sun's disc).
inline bool sky_and_ground_unlit(const AtmospherePass& pass, const TileVariant& variant) {
  return !pass.sunlit && variant.others == 0 && !variant.sun;
}

/// Per frame.passes: the largest linear display value the sun's light could add
/// through that atmosphere's passes (0 where none is resident).
std::vector<double> sunlight_bounds(const FrameInProgress& frame);

/// The largest linear display value a source at infinity in `direction`
/// (world, unit) with `irradiance_W_m2_nm` at the top of the atmosphere can add
/// through `pass`'s atmosphere (its sky, the aerial perspective, the ground it
/// lights; seen through T ≤ 1 of any atmosphere in front), for the frame's
/// exposure and colour weights: the Moon's test and the sun's.
double light_display_bound(const FrameInProgress& frame, const AtmospherePass& pass, const glm::dvec3& direction,
                           const std::vector<double>& irradiance_W_m2_nm);

}  // namespace zenith::render
