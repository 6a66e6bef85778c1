#pragma once
// One atmosphere's lookup tables resident on the GPU for rendering, with the
// shader program of its pass (shaders/render/atmosphere_pass.comp compiled
// with the model's #defines: radii, table sizes, phase models, which terms exist).
//
// Tables are uploaded once per table set (identified by its hash); the
// renderer keeps a GpuAtmosphere per hash, so re-rendering with unchanged
// parameters uploads and precomputes nothing.
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/lut/sky_radiance_bound.h"
#include "atmosphere/lut/sky_radiance_lower_bound.h"
#include "render/frame/eclipse_sky_table.h"
#include "render/frame/sky_view_table.h"
#include "render/frame/tile_classification.h"
#include "render/frame/tile_culling.h"
#include "render/gl/buffer.h"
#include "render/gl/first_dispatch_warmup.h"
#include "render/gl/program_builds.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"
#include "render/lut/shader_model.h"
#include "render/render_options.h"

namespace zenith::render {

/// What a frame's passes are compiled for (render/renderer.cpp): the
/// projection kind (shaders/projection.glsl's PROJECTION_KIND), whether other
/// bodies' shadows can fall (ECLIPSES) and, of those, shadows through a body's
/// air (AIR_SHADOWS: a lunar eclipse seen from space), and whether every albedo lookup is at
/// the maps' full resolution (ALBEDO_LOD0, surface_albedo.glsl). A CPU
/// rasterizer runs all the code a program has, so what a frame cannot need is
/// compiled out; each combination is compiled on first use.
struct FrameVariant {
  int projection_kind = 0;
  bool eclipses = true;
  bool air_shadows = true;  // with eclipses: a body's shadow through its air (render/frame/air_shadows.h)
  bool albedo_lod0 = false;
  std::vector<gl::ShaderDefine> defines() const;
  std::string key() const;
};

class GpuAtmosphere {
 public:
  /// Takes `tables` (made for `model`) to upload them in upload_tables();
  /// `frame_defines` are the renderer's defines of the sun's disc (SUN_DISC,
  /// LIMB_DARKENING) for the one-pass tiles, which draw it behind the
  /// atmosphere. Its programs are `builds`'s (the renderer's, which outlives
  /// this), built per variant when first started or used. Needs a current GL
  /// context.
  GpuAtmosphere(const atmosphere::AtmosphereModel& model, atmosphere::lut::LookupTables tables,
                const AtmospherePassFeatures& features, std::span<const gl::ShaderDefine> frame_defines,
                gl::ProgramBuilds& builds);

  /// Uploads the tables to textures (once; then drops the CPU copy). Apart
  /// from the constructor so that a renderer can start its programs, which
  /// need only the tables' sizes, before this upload: a driver that compiles
  /// on another thread (render/gl/program_builds.h) compiles meanwhile.
  /// Everything below that binds or fills needs it done first.
  void upload_tables();
  bool tables_uploaded() const { return !tables_to_upload_; }

  const std::string& hash() const { return hash_; }
  std::size_t group_count() const { return groups_.size(); }
  double top_radius_m() const { return top_radius_m_; }
  double ground_radius_m() const { return ground_radius_m_; }
  /// atmosphere_tile.comp for tiles only this shell touches, compiled for the
  /// frame's variant and the tiles' (render/frame/tile_classification.h).
  /// With `eclipse_sky`, the variant that reads the eclipse-sky table too (ECLIPSE_SKY).
  const gl::ShaderProgram& tile_program(const FrameVariant& frame, const TileVariant& variant,
                                        bool eclipse_sky = false);
  /// atmosphere_pass.comp for the G-buffer path (tiles where shells overlap).
  const gl::ShaderProgram& gbuffer_path_program(const FrameVariant& frame);
  /// Start building those programs (and the sky-view table's fill) with the
  /// frame's others, to be finished where first used (or for a later frame:
  /// ProgramBuilds::start).
  void start_tile_program(const FrameVariant& frame, const TileVariant& variant, bool eclipse_sky = false,
                          gl::BuildFor build_for = gl::BuildFor::this_frame) const;
  void start_gbuffer_path_program(const FrameVariant& frame, gl::BuildFor build_for = gl::BuildFor::this_frame) const;
  void start_sky_view_program() const { sky_view_->start_program(); }
  /// Whether those programs are built (tile_program, gbuffer_path_program return them at once).
  bool tile_program_built(const FrameVariant& frame, const TileVariant& variant, bool eclipse_sky) const;
  bool gbuffer_path_program_built(const FrameVariant& frame) const;
  /// Sets `wavelength_group` (the model's parameters of group g are read from
  /// WavelengthData) and the sky-view uniforms of one of these programs.
  void set_group(const gl::ShaderProgram& program, std::size_t group) const;
  /// Bytes of GPU memory the tables take (once uploaded).
  std::size_t table_bytes() const { return table_bytes_; }
  /// The transmittance table on the CPU too (geometry, sizes, channels and
  /// transmittance of the table set; the other tables empty): the stars'
  /// extinction and the night sky's (render/night/star_transmittance.h) read it per
  /// star, as the sky's passes read the same table on the GPU. A few hundred kB.
  const atmosphere::lut::LookupTables& cpu_transmittance() const { return cpu_transmittance_; }

  /// Binds the tables of wavelength group g (texture units 0–4), the sky-view
  /// table of light `light` (unit 5; 0 the sun, 1 the Moon), the model's
  /// buffers (ModelBuffers) and the texel coordinates.
  void bind(std::size_t group, std::size_t light = 0) const;
  /// The shapes of what bind() and the sky-view fill bind, into `shapes`
  /// (every group's tables are alike): render/gl/first_dispatch_warmup.h.
  void add_dispatch_shapes(gl::DispatchShapes& shapes) const;

  /// Fills the sky-view table of light `light` (0 the sun, 1 the Moon) for
  /// every wavelength group, for a camera inside the shell at
  /// `camera_radius_m` from the centre, the light's cosine there `sun_cosine`
  /// and its angular radius (render/frame/sky_view_table.h). Leaves image
  /// unit 0 and texture units 0–4 bound to its own images and tables. Returns
  /// false, filling nothing, where the table holds that camera and light
  /// already (SkyViewTable::holds: another output of the frame, a still sky).
  bool fill_sky_view(double camera_radius_m, double sun_cosine, double sun_angular_radius_rad, std::size_t light = 0);

  /// The Moon's shadow on this atmosphere and its eclipse-sky table
  /// (render/frame/eclipse_sky_table.h), made on first use.
  EclipseSkyTable& eclipse_sky();
  /// Fills the eclipse-sky table for a camera at `camera_m` (planet-centred,
  /// inside the shell) with the shadow it holds. Leaves image unit 0 and
  /// texture units 0–4 bound to its own images and tables.
  void fill_eclipse_sky(const glm::dvec3& camera_m);

  /// The most these tables can give per unit irradiance of a source
  /// (atmosphere/lut/sky_radiance_bound.h): the moonlight passes' test.
  const atmosphere::lut::SkyRadianceBound& radiance_bound() const { return radiance_bound_; }
  /// The least these tables give on a ray to space from a camera inside, per
  /// unit irradiance of the sun (atmosphere/lut/sky_radiance_lower_bound.h): the star pass's test.
  const atmosphere::lut::SkyRadianceLowerBound& radiance_lower_bound() const { return radiance_lower_bound_; }

 private:
  /// Group g's tables (texture units 0–4), the model's buffers and the texel coordinates.
  void bind_tables(std::size_t group) const;
  /// Throws std::logic_error, naming `what`, before upload_tables().
  void expect_uploaded(const char* what) const;
  struct GroupTextures {
    gl::Texture transmittance, irradiance, single_rayleigh, single_mie, multiple;
  };
  std::string hash_;
  std::string name_;  // the model's, for messages
  double top_radius_m_ = 0.0, ground_radius_m_ = 0.0;
  std::vector<GroupTextures> groups_;                              // empty textures before upload_tables
  std::optional<atmosphere::lut::LookupTables> tables_to_upload_;  // until upload_tables
  ModelBuffers model_buffers_;    // the model's parameters and constants (render/lut/shader_model.h)
  gl::Buffer texel_coordinates_;  // acos(μs_min) at TEXEL_SUN_THETA_MAX
  /// The defines of atmosphere_tile.comp for a variant, of atmosphere_pass.comp for a frame.
  std::vector<gl::ShaderDefine> tile_defines(const FrameVariant& frame, const TileVariant& variant,
                                             bool eclipse_sky) const;
  std::vector<gl::ShaderDefine> gbuffer_path_defines(const FrameVariant& frame) const;
  std::vector<gl::ShaderDefine> defines_, tile_defines_;  // atmosphere_pass.comp's; atmosphere_tile.comp's
  bool eclipses_ = true;                                  // AtmospherePassFeatures::eclipses
  gl::ProgramBuilds* builds_;                             // the programs, by text
  std::unique_ptr<SkyViewTable> sky_view_;
  std::vector<gl::ShaderDefine> fill_defines_;  // the sky-view and eclipse-sky fills'
  std::unique_ptr<EclipseSkyTable> eclipse_sky_;
  std::size_t table_bytes_ = 0;
  atmosphere::lut::LookupTables cpu_transmittance_;
  atmosphere::lut::SkyRadianceBound radiance_bound_;
  atmosphere::lut::SkyRadianceLowerBound radiance_lower_bound_;
};

}  // namespace zenith::render
