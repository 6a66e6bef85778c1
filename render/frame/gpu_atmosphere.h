#pragma once
// One atmosphere's lookup tables resident on the GPU for rendering, with the
// shader program of its pass (shaders/render/atmosphere_pass.comp compiled
// with the model's #defines: radii, table sizes, phase models, which terms exist).
//
// Tables are uploaded once per table set (identified by its hash); the
// renderer keeps a GpuAtmosphere per hash, so re-rendering with unchanged
// parameters uploads and precomputes nothing.
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"
#include "render/gl/buffer.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"
#include "render/frame/sky_view_table.h"

namespace zenith::render {

/// Which terms the atmosphere pass evaluates (each off drops code from the shader).
struct AtmospherePassFeatures {
  bool multiple_scattering = true;  ///< orders ≥ 2 (off: single scattering only)
  bool eclipses = true;             ///< other bodies' shadows on the ground
  bool fp64 = false;                ///< table mappings and interpolation in double (slower; see docs/rendering.md)
};

class GpuAtmosphere {
 public:
  /// Uploads `tables` (made for `model`) and compiles the passes; `frame_defines`
  /// are the renderer's defines of the sun's disc (SUN_DISC, LIMB_DARKENING) for
  /// the one-pass tiles, which draw it behind the atmosphere. Needs a current GL context.
  GpuAtmosphere(const atmosphere::AtmosphereModel& model, const atmosphere::lut::LookupTables& tables,
                const AtmospherePassFeatures& features, std::span<const gl::ShaderDefine> frame_defines);

  const std::string& hash() const { return hash_; }
  std::size_t group_count() const { return groups_.size(); }
  double top_radius_m() const { return top_radius_m_; }
  double ground_radius_m() const { return ground_radius_m_; }
  /// The passes of this atmosphere, compiled for one projection kind
  /// (shaders/projection.glsl's PROJECTION_KIND) on first use.
  struct Passes {
    /// The G-buffer path's pass (atmosphere_pass.comp): tiles where shells overlap.
    gl::ShaderProgram gbuffer_path;
    /// One pass straight to the output for tiles only this shell touches
    /// (atmosphere_tile.comp), from the 4D tables along each ray.
    gl::ShaderProgram tile;
    /// Its SKY_VIEW variant: a camera inside the shell, S and the ground's light
    /// by direction from this frame's sky-view table (fill_sky_view first).
    gl::ShaderProgram sky_view;
  };
  const Passes& passes(int projection_kind);
  /// Bytes of GPU memory the tables take.
  std::size_t table_bytes() const { return table_bytes_; }

  /// Binds the tables of wavelength group g (texture units 0–4), the sky-view
  /// table (unit 5) and the model's storage buffers (bindings 0–2), and sets
  /// `wavelength_group` of every compiled pass (and the sky-view uniforms of the SKY_VIEW variant).
  void bind(std::size_t group) const;

  /// Fills the sky-view table of every wavelength group for a camera inside
  /// the shell at `camera_radius_m` from the centre, the sun's cosine there
  /// `sun_cosine` and its angular radius (render/frame/sky_view_table.h).
  /// Leaves image unit 0 and texture units 0–4 bound to its own images and tables.
  void fill_sky_view(double camera_radius_m, double sun_cosine, double sun_angular_radius_rad);

 private:
  struct GroupTextures {
    gl::Texture transmittance, irradiance, single_rayleigh, single_mie, multiple;
  };
  std::string hash_;
  double top_radius_m_ = 0.0, ground_radius_m_ = 0.0;
  std::vector<GroupTextures> groups_;
  gl::Buffer wavelength_data_, table_data_, texel_coordinates_;
  std::vector<gl::ShaderDefine> defines_, tile_defines_;  // atmosphere_pass.comp's; atmosphere_tile.comp's
  std::map<int, Passes> passes_;                         // by projection kind
  std::unique_ptr<SkyViewTable> sky_view_;
  std::size_t table_bytes_ = 0;
};

}  // namespace zenith::render
