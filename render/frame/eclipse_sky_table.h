#pragma once
// The sky of a solar eclipse as the renderer draws it (docs/rendering.md,
// "Sun, shadows, eclipses"): the Moon's shadow on one atmosphere
// (astro/moon_shadow.h, built on the CPU from the atmosphere's tables) and,
// once per frame, the eclipse-sky table filled from it on the GPU
// (shaders/render/eclipse_sky.comp): per direction from the camera, the share
// of the sky's light the shadow leaves, for the smooth part A and the single
// Mie part M of each wavelength. The one-pass tiles multiply by it
// (atmosphere_tile.comp's ECLIPSE_SKY variant: the sky-view table's terms for
// a camera inside the shell, the 4D tables' along the ray for one in orbit,
// whose table covers the shell's disc), and the ground's skylight by the
// share left there (a fifth layer); the ground's direct sun by the shadow's V
// per pixel (shaders/render/moon_shadow.glsl), sharp at the umbra's edge.
//
// The shares vary over tens of degrees, so the table is coarse: 64 azimuths
// all the way round (the shadow breaks the sky's symmetry about the sun's
// vertical) × 32 zenith angles per half, 5 RGBA32F layers per group of 4
// wavelengths; each texel sums 24 segments of its ray (astro/eclipsed_sky.h's
// count) with the shadow at each segment's middle. The shadow itself, 1–2 s
// of CPU, is kept while it still fits the eclipse (MoonShadow::still_fits:
// the axis' zenith angle within 0.3°) and moved with the Moon; a new one is
// built from a CPU copy of the tables, on a worker thread for live frames
// (RenderOptions::background_shadow_builds).
#include <array>
#include <cstddef>
#include <future>
#include <memory>
#include <optional>
#include <span>
#include <stop_token>
#include <vector>

#include <glm/vec3.hpp>

#include "astro/moon_shadow.h"
#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"
#include "render/gl/program_builds.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"

namespace zenith::render {

class EclipseSkyTable {
 public:
  static constexpr int kAzimuthTexels = 64;  ///< ECLIPSE_SKY_AZIMUTH_TEXELS, all the way round
  static constexpr int kZenithTexels = 32;   ///< ECLIPSE_SKY_ZENITH_TEXELS, per half
  static constexpr int kLayersPerGroup = 5;  ///< ECLIPSE_SKY_LAYERS
  static constexpr int kSegments = 24;       ///< ECLIPSE_SKY_SEGMENTS

  /// The defines of eclipse_sky_mapping.glsl and moon_shadow.glsl (the shadow's table sizes).
  static std::vector<gl::ShaderDefine> defines();

  /// For an atmosphere of `groups` wavelength groups between the radii
  /// `ground_radius_m` and `top_radius_m`; the fill program, with the
  /// atmosphere's defines, is one of `builds` (which outlives this). Needs a
  /// current GL context.
  EclipseSkyTable(gl::ProgramBuilds& builds, std::span<const gl::ShaderDefine> atmosphere_defines, std::size_t groups,
                  double ground_radius_m, double top_radius_m);
  /// Stops a shadow still being built on the worker thread and waits for it
  /// (milliseconds: MoonShadow checks its stop at every V̄ node), so a node
  /// at the end of a show or on SIGTERM exits at once instead of after the
  /// seconds a whole build takes.
  ~EclipseSkyTable();
  EclipseSkyTable(const EclipseSkyTable&) = delete;
  EclipseSkyTable& operator=(const EclipseSkyTable&) = delete;

  /// The tables (and their model) the shadows are built from, kept on the
  /// CPU while this exists: a TableSource may need the GL context, a worker
  /// thread may not call it.
  bool has_tables() const { return tables_ != nullptr; }
  const std::shared_ptr<const atmosphere::lut::LookupTables>& tables() const { return tables_; }
  void keep_tables(const atmosphere::AtmosphereModel& model,
                   std::shared_ptr<const atmosphere::lut::LookupTables> tables);

  /// What update() did.
  enum class ShadowUpdate {
    moved,     ///< the shadow held still fits: moved with the Moon
    built,     ///< a new one built and uploaded, the frame waiting for it
    swapped,   ///< one built on the worker thread is ready: uploaded
    building,  ///< a new one is being built on the worker thread; the one held (if any) moved meanwhile
  };
  /// A shadow for the eclipse `geometry` seen from `camera_m` (planet-centred),
  /// from the kept tables: the one held while it fits; else a new one, built
  /// now or, with `background`, on a worker thread while the one held is
  /// moved (MoonShadow::still_fits, docs/rendering.md): with none held yet,
  /// shadow() stays null until it is ready.
  ShadowUpdate update(const astro::EclipseGeometry& geometry, const glm::dvec3& camera_m, bool background);
  const astro::MoonShadow* shadow() const { return shadow_.get(); }

  /// Starts building the fill program (with the frame's other programs).
  void start_program() const;
  /// Fills every group's layers for a camera at `camera_m` (planet-centred,
  /// world-oriented; inside the shell or outside it) with the shadow held. `bind_group(g)`
  /// binds group g's atmosphere tables (GpuAtmosphere::bind_tables) and sets
  /// its `wavelength_group`.
  template <class BindGroup>
  void fill(const glm::dvec3& camera_m, BindGroup bind_group) {
    prepare_fill(camera_m);
    for (std::size_t g = 0; g < groups_; ++g) {
      bind_group(fill_program(), g);
      fill_group(g);
    }
  }

  /// The uniforms of moon_shadow.glsl and the tile pass's eclipse-sky
  /// lookups for wavelength group g, on `program`.
  void set_uniforms(const gl::ShaderProgram& program, std::size_t group) const;
  /// Binds the table (ECLIPSE_SKY_UNIT) and group g's shadow tables (SHADOW_PROFILE_UNIT, SHADOW_FIELD_UNIT).
  void bind(std::size_t group) const;

  const gl::ShaderProgram& fill_program() const;

 private:
  /// Stops the worker thread's build, if any, and waits for it.
  void stop_building();
  /// Takes a new shadow and uploads its tables.
  void set_shadow(std::unique_ptr<astro::MoonShadow> shadow);
  void prepare_fill(const glm::dvec3& camera_m);
  void fill_group(std::size_t group);
  /// The shadow's frame at the camera: its offset from the axis and distance along it.
  void set_shadow_frame(const gl::ShaderProgram& program) const;

  gl::ProgramBuilds* builds_;
  std::vector<gl::ShaderDefine> defines_;  // the fill program's
  std::size_t groups_ = 1;
  double ground_radius_m_ = 0.0, top_radius_m_ = 0.0;
  gl::Texture table_;
  std::unique_ptr<astro::MoonShadow> shadow_;
  std::optional<atmosphere::AtmosphereModel> model_;
  std::shared_ptr<const atmosphere::lut::LookupTables> tables_;
  std::unique_ptr<atmosphere::lut::TableQueries> queries_;
  std::future<std::unique_ptr<astro::MoonShadow>> next_;  // the one built on the worker thread
  std::stop_source next_stop_;                            // stops it
  std::vector<gl::Texture> profiles_, fields_;            // per group
  std::vector<std::array<float, 4>> mie_k1_, mie_k2_, mie_forward_, mie_k3_, mie_k4_;
  float rayleigh_k1_ = 0.0f, rayleigh_k2_ = 0.0f, rayleigh_dipole_ = 0.0f;
  // The camera of the last fill and its azimuth's axes: the tile passes read the table with them.
  glm::dvec3 camera_m_{0.0}, azimuth_h_{1.0, 0.0, 0.0}, azimuth_w_{0.0, 1.0, 0.0};
  float theta_top_rad_ = 0.0f, theta_horizon_rad_ = 0.0f;  // its zenith angles' mapping (eclipse_sky_mapping.glsl)
};

}  // namespace zenith::render
