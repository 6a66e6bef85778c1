#pragma once
// One atmosphere's lookup tables resident on the GPU for rendering, with the
// shader program of its pass (shaders/render/atmosphere_pass.comp compiled
// with the model's #defines: radii, table sizes, phase models, which terms exist).
//
// Tables are uploaded once per table set (identified by its hash); the
// renderer keeps a GpuAtmosphere per hash, so re-rendering with unchanged
// parameters uploads and precomputes nothing.
#include <string>
#include <vector>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"
#include "render/gl/buffer.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"

namespace zenith::render {

/// Which terms the atmosphere pass evaluates (each off drops code from the shader).
struct AtmospherePassFeatures {
  bool multiple_scattering = true;  ///< orders ≥ 2 (off: single scattering only)
  bool eclipses = true;             ///< other bodies' shadows on the ground
  bool fp64 = false;                ///< table mappings and interpolation in double (slower; see docs/rendering.md)
};

class GpuAtmosphere {
 public:
  /// Uploads `tables` (made for `model`) and compiles the pass. Needs a current GL context.
  GpuAtmosphere(const atmosphere::AtmosphereModel& model, const atmosphere::lut::LookupTables& tables,
                const AtmospherePassFeatures& features);

  const std::string& hash() const { return hash_; }
  std::size_t group_count() const { return groups_.size(); }
  double top_radius_m() const { return top_radius_m_; }
  double ground_radius_m() const { return ground_radius_m_; }
  const gl::ShaderProgram& program() const { return program_; }
  /// Bytes of GPU memory the tables take.
  std::size_t table_bytes() const { return table_bytes_; }

  /// Binds the tables of wavelength group g (texture units 0–4) and the model's
  /// storage buffers (bindings 0–2), and sets `wavelength_group`.
  void bind(std::size_t group) const;

 private:
  struct GroupTextures {
    gl::Texture transmittance, irradiance, single_rayleigh, single_mie, multiple;
  };
  std::string hash_;
  double top_radius_m_ = 0.0, ground_radius_m_ = 0.0;
  std::vector<GroupTextures> groups_;
  gl::Buffer wavelength_data_, table_data_, texel_coordinates_;
  gl::ShaderProgram program_;
  std::size_t table_bytes_ = 0;
};

}  // namespace zenith::render
