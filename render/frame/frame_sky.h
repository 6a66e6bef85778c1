#pragma once
// The sky clock's ephemeris for one frame (astro/sky_positions.h), made on
// first use and shared by the frame's readers: the Sun's occulter
// (render/frame/sun_occulter.h), the Earth's shadow on the Moon
// (render/night/moon_in_shadow.h), the moonlight test (render/night/moon_light.h)
// and the Moon's disc among the stars (render/night/star_pass.h). All of them
// ask for the Moon at the clock's time and site; each ERFA set-up
// (precession–nutation, the Earth's ephemeris, for the site and the geocentre)
// costs about 0.1 ms of CPU (bench/astro_bench.cpp), and a night frame made four.
#include <optional>

#include "astro/sky_positions.h"
#include "scene/scene.h"

namespace zenith::render {

class FrameSky {
 public:
  /// The sky of `scene`'s clock; the scene must outlive this.
  explicit FrameSky(const scene::Scene& scene) : clock_(scene.sky_clock ? &*scene.sky_clock : nullptr) {}

  /// The positions at the clock's time (UTC, DUT1 = 0) and site, made on the
  /// first call. Throws std::logic_error where the scene has no sky clock.
  const astro::SkyPositions& positions() const;

 private:
  const scene::SkyClock* clock_;
  mutable std::optional<astro::SkyPositions> positions_;
};

}  // namespace zenith::render
