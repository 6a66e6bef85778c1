#pragma once
// The Earth's shadow on the Moon in a lunar eclipse, as the frame's passes draw
// it (docs/night-sky.md, "The Moon in a lunar eclipse"): for a scene with a sky
// clock whose planet has an atmosphere, the sunlight left on each point of the
// Moon's face, refracted and extinguished through that atmosphere
// (astro/lunar_eclipse.h). The Moon's whole light (its disc smaller than a
// pixel, and the moonlight on the sky: render/night/moon_light.h) takes the
// face's mean per wavelength; a disc larger than a pixel takes each point's
// own, by its distance from the shadow's axis (shaders/render/night_sky.comp).
//
// The shadow is built where the Moon's face reaches the penumbra (0.1 s at 3
// wavelengths, 0.6 s at 31 on 2 cores) and kept while the Moon's distance and
// the Sun's radius change by less than 1e-3; elsewhere nothing changes.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "astro/civil_time.h"
#include "astro/lunar_eclipse.h"
#include "render/frame/frame_sky.h"
#include "scene/scene.h"

namespace zenith::render {

class MoonInShadow {
 public:
  /// For `scene`'s sky clock at its time: whether the Moon's face reaches the
  /// Earth's penumbra, and if so the shadow; `sky`: that clock's ephemeris for the frame.
  void update(const scene::Scene& scene, const FrameSky& sky);
  bool shadowed() const { return shadowed_; }
  /// Per wavelength: the mean of E / E_sun over the Moon's face (all 1 when not shadowed).
  const std::vector<double>& face() const { return face_; }
  /// E / E_sun at `axis_distance_m` from the shadow's axis, wavelength i (1 beyond reach_m()).
  double illumination(double axis_distance_m, std::size_t wavelength) const;
  /// The Moon's centre from the planet's centre [m] and the shadow's axis
  /// (unit, away from the Sun), world frame; beyond reach_m() from the axis E = 1.
  const glm::dvec3& moon_centre_m() const { return moon_centre_m_; }
  const glm::dvec3& axis() const { return axis_; }
  double reach_m() const { return reach_m_; }
  double moon_radius_m() const;

 private:
  bool shadowed_ = false;
  std::vector<double> face_;
  glm::dvec3 moon_centre_m_{0.0}, axis_{0.0, 0.0, -1.0};
  double reach_m_ = 0.0;
  std::unique_ptr<astro::EarthShadow> shadow_;
  std::string shadow_atmosphere_;
  double shadow_distance_m_ = 0.0, shadow_sun_radius_rad_ = 0.0;
};

}  // namespace zenith::render
