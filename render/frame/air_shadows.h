#pragma once
// A body's shadow through its own air on another body of the scene: the Moon
// in the Earth's shadow seen from space in a lunar eclipse, red in the umbra,
// where a solid sphere's geometric shadow would leave it black. The sunlight
// left at each distance from the shadow's axis, refracted and extinguished
// through the occluder's atmosphere, with the Sun's limb-darkened disc, is
// astro/lunar_eclipse.h's EarthShadow — the model the sky's Moon takes
// (render/night/moon_in_shadow.h) — built at the receiver's distance behind
// the occluder and tabulated for the frame's passes (frame.glsl's
// sunlight_left and sunlit_rgb). No GL.
//
// One table per receiver: across a receiver of radius R_r the distance behind
// the occluder varies by ±R_r, which moves the shadow's edges by ±R_r r_s
// (r_s the Sun's angular radius; 8 km across the Moon, against its 1 737 km).
#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "astro/lunar_eclipse.h"
#include "render/frame/frame_constants.h"
#include "scene/scene.h"

namespace zenith::render {

/// Entries of an air shadow's table, evenly from the axis to its reach: 16 km
/// apart for the Earth's shadow at the Moon (AIR_SHADOW_ENTRIES).
inline constexpr std::size_t kAirShadowEntries = 512;
/// Air shadows a frame draws at most (MAX_AIR_SHADOWS): a lunar eclipse seen
/// from space is one; beyond, the solid bodies' geometric shadows stay.
inline constexpr std::size_t kMaxAirShadows = 4;

/// One body's shadow through its air on another body.
struct AirShadow {
  std::size_t occluder = 0, receiver = 0;  ///< indices into the scene's bodies
  /// From the shadow's axis, beyond which the whole Sun shines: the top of
  /// the occluder's air plus the penumbra's spread, r_top + D tan r_s [m].
  double reach_m = 0.0;
  /// E / E_sun per wavelength at kAirShadowEntries distances from the axis,
  /// evenly over [0, reach_m]: [entry][wavelength].
  std::vector<std::vector<double>> light_left;
};

class AirShadows {
 public:
  /// The scene's air shadows for this frame: every ordered pair of bodies whose
  /// first has an atmosphere at the scene's wavelengths and whose shadow
  /// reaches the second, at least ten times the air's top radius behind the
  /// first (nearer, frame.glsl keeps the solid body's geometric shadow), the
  /// first kMaxAirShadows of them. A pair's EarthShadow (0.1–0.6 s on 2 cores)
  /// is kept while its distance and the Sun's radius move by under 1e-3.
  void update(const scene::Scene& scene);
  const std::vector<AirShadow>& shadows() const { return shadows_; }

 private:
  struct Built {
    std::size_t occluder = 0, receiver = 0;
    std::string atmosphere;  // the occluder's table hash
    double distance_m = 0.0, sun_radius_rad = 0.0;
    std::unique_ptr<astro::EarthShadow> shadow;
  };
  std::vector<Built> built_;
  std::vector<AirShadow> shadows_;
  bool warned_ = false;  // of shadows beyond kMaxAirShadows, once
};

/// Values per entry of frame.glsl's AirShadows buffer: the three columns of
/// direct_light.comp's colour matrix, then one vec4 per wavelength group.
std::size_t air_shadow_values_per_entry(const FrameConstants& frame);

/// frame.glsl's AirShadows buffer, in vec4s: shadow s from index s ×
/// kAirShadowEntries × air_shadow_values_per_entry, per entry the three
/// columns of direct_light.comp's colour matrix summed with the light left
/// (direct_light_colour_matrix's) and the light left per lane of each
/// wavelength group. One zero vec4 where there is no shadow.
std::vector<std::array<float, 4>> air_shadow_buffer(const std::vector<AirShadow>& shadows, const FrameConstants& frame,
                                                    const scene::Scene& scene);

}  // namespace zenith::render
