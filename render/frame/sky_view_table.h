#pragma once
// The sky-view table of one atmosphere (after Hillaire 2020, "A Scalable and
// Production Ready Sky and Atmosphere Rendering Technique", section 5.3): for
// a camera inside the atmosphere, the in-scattered radiance along every view
// direction and, for directions that end on the ground, the ground's lighting
// per unit albedo (transmittance to it included), filled once per frame from
// the 4D tables at the camera's position (shaders/render/sky_view.comp) and
// read with a few bilinear lookups per pixel by atmosphere_tile.comp's
// SKY_VIEW variant instead of the 4D lookups (three 4D samples of two
// trilinear fetches each, the ground's irradiance and transmittance lookups).
//
// 128 azimuth × 64 zenith texels per half (sky, ground), 6 RGBA32F layers per
// group of 4 wavelengths (shaders/render/sky_view_mapping.glsl): 0.8 MB per
// group, 2·128·64 = 16 384 directions filled per group and frame. Its error
// against the per-pixel 4D lookups is measured in tests/render/renderer_test.cpp
// (RendererSkyView) and docs/rendering-performance.md.
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "render/gl/program_builds.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"

namespace zenith::render {

class SkyViewTable {
 public:
  static constexpr int kAzimuthTexels = 128;  ///< SKY_VIEW_AZIMUTH_TEXELS
  static constexpr int kZenithTexels = 64;    ///< SKY_VIEW_ZENITH_TEXELS, per half
  static constexpr int kLayersPerGroup = 6;   ///< SKY_VIEW_LAYERS
  /// Tables per atmosphere: one per light of the passes (0 the sun, 1 the
  /// Moon: render/night/moon_light.h); the Moon's is allocated on its first fill.
  static constexpr std::size_t kLights = 2;
  /// The smallest frame the renderer fills the table for (SkyViewTableUse::
  /// automatic): four pixels per direction of the table, a 256² dome master.
  /// Measured on llvmpipe (docs/rendering-performance.md, "The sky-view
  /// table"), a dome master with the sun moving each frame took 4.5–5.4 ms with
  /// the table and 1.1–1.2 ms without at 32², 6.2–8.2 against 2.7–3.5 at 128²,
  /// and about as long either way at 256² (9.1–10.6 against 8.1–10.4).
  static constexpr std::size_t kMinFramePixels = 4 * 2 * kAzimuthTexels * kZenithTexels;

  /// SKY_VIEW_AZIMUTH_TEXELS, SKY_VIEW_ZENITH_TEXELS and SKY_VIEW_LAYERS from the
  /// constants above, for the shaders that include render/sky_view_mapping.glsl.
  static std::vector<gl::ShaderDefine> defines();

  /// Allocates the table for `groups` wavelength groups; its fill shader,
  /// with the atmosphere's defines, is one of `builds` (which outlives this),
  /// built when first started or used. Needs a current GL context.
  SkyViewTable(gl::ProgramBuilds& builds, std::span<const gl::ShaderDefine> atmosphere_defines, std::size_t groups);

  /// Starts building the fill program (with the frame's other programs).
  void start_program() const;
  /// The fill program (finished or built now): its tables (texture units
  /// 0–4), storage buffers and `wavelength_group` are bound by the caller for
  /// each group (GpuAtmosphere::fill_sky_view).
  const gl::ShaderProgram& fill_program() const;

  /// Sets the camera's radius [m] (in [RB, RT)), its ground radius, the sun's
  /// cosine at the camera and the sun's angular radius (the fading of the direct
  /// sun at the horizon) for the following fill_group calls.
  void set_camera(double camera_radius_m, double ground_radius_m, double sun_cosine, double sun_angular_radius_rad);
  /// Whether light `light`'s table was last filled, every group, with the
  /// values set_camera() has just set: the fill reads nothing else that
  /// changes (its atmosphere's tables and model are fixed), so filling it
  /// again would write the same texels. A dome node's outputs share their
  /// camera, and a still sky (a hold, a paused show) its sun.
  bool holds(std::size_t light) const { return filled_.at(light) == camera_; }
  /// Fills the layers of wavelength group g of light `light`'s table (the group's tables must be bound).
  void fill_group(std::size_t group, std::size_t light = 0);

  /// Zenith angle of the geometric horizon at the camera, π − asin(RB / r) [rad].
  double theta_horizon_rad() const { return theta_horizon_rad_; }
  /// Binds light `light`'s table for sampling (sampler2DArray) on texture unit `unit`.
  void bind(unsigned unit, std::size_t light = 0) const { tables_.at(light).bind(unit); }
  /// What bind() and the fill's output image bind (every light's table is alike).
  gl::TextureShape shape() const { return tables_[0].shape(); }

 private:
  gl::ProgramBuilds* builds_;
  std::vector<gl::ShaderDefine> defines_;  // the fill program's
  std::size_t groups_ = 1;
  std::array<gl::Texture, kLights> tables_;
  double theta_horizon_rad_ = 0.0;
  /// The fill's uniforms, as the shader receives them.
  struct FillCamera {
    float camera_r = 0.0f, camera_ground_power = 0.0f, camera_mu_s = 0.0f, theta_horizon = 0.0f,
          sun_angular_radius = 0.0f;
    bool operator==(const FillCamera&) const = default;
  };
  FillCamera camera_;                                      // set_camera()'s
  std::array<std::optional<FillCamera>, kLights> filled_;  // each light's table's, once filled
};

}  // namespace zenith::render
