#include "render/frame/gpu_atmosphere.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "atmosphere/lut/precompute_options.h"
#include "atmosphere/model_hash.h"
#include "render/gl/gl_error.h"
#include "render/lut/shader_model.h"
#include "render/shader_bindings.h"
#include "render/shader_programs.h"

namespace zenith::render {
namespace {

using atmosphere::lut::Table2D;
using atmosphere::lut::Table3D;

constexpr std::size_t kLanes = kWavelengthLanes;

// Texture units and storage bindings of atmosphere_segment.glsl / atmosphere_common.glsl
// and the sky-view table of atmosphere_tile.comp: render/shader_bindings.h.
using namespace binding;

/// Lanes 4g..4g+3 of a channel-interleaved table, as RGBA texels (missing lanes 0).
std::vector<float> group_lanes(const std::vector<float>& data, std::size_t texels, std::size_t channels,
                               std::size_t group) {
  std::vector<float> out(texels * kLanes, 0.0f);
  const std::size_t first = group * kLanes, lanes = std::min(kLanes, channels - first);
  for (std::size_t t = 0; t < texels; ++t)
    for (std::size_t k = 0; k < lanes; ++k) out[t * kLanes + k] = data[t * channels + first + k];
  return out;
}

gl::Texture texture_2d(const Table2D& t, std::size_t group) {
  return gl::Texture::create_2d(gl::TextureFormat::rgba32f, static_cast<int>(t.width), static_cast<int>(t.height),
                                group_lanes(t.data, t.width * t.height, t.channels, group));
}

gl::Texture texture_3d(const Table3D& t, std::size_t group) {
  return gl::Texture::create_3d(gl::TextureFormat::rgba32f, static_cast<int>(t.width), static_cast<int>(t.height),
                                static_cast<int>(t.depth),
                                group_lanes(t.data, t.width * t.height * t.depth, t.channels, group));
}

}  // namespace

GpuAtmosphere::GpuAtmosphere(const atmosphere::AtmosphereModel& model, atmosphere::lut::LookupTables tables,
                             const AtmospherePassFeatures& features, std::span<const gl::ShaderDefine> frame_defines,
                             gl::ProgramBuilds& builds)
    : hash_(tables.hash),
      name_(model.name),
      top_radius_m_(model.top_radius_m),
      ground_radius_m_(model.ground_radius_m),
      builds_(&builds) {
  if (tables.channels != model.wavelength_count())
    throw std::invalid_argument(fmt::format("atmosphere '{}': tables have {} channels, the model {} wavelengths",
                                            model.name, tables.channels, model.wavelength_count()));
  if (std::abs(tables.geometry.bottom_radius_m - model.ground_radius_m) > 1e-6 ||
      std::abs(tables.geometry.top_radius_m - model.top_radius_m) > 1e-6)
    throw std::invalid_argument(fmt::format("atmosphere '{}': the tables were made for other radii", model.name));
  cpu_transmittance_.geometry = tables.geometry;
  cpu_transmittance_.sizes = tables.sizes;
  cpu_transmittance_.channels = tables.channels;
  cpu_transmittance_.transmittance = tables.transmittance;
  cpu_transmittance_.hash = tables.hash;
  radiance_bound_ = atmosphere::lut::SkyRadianceBound(model, tables);
  radiance_lower_bound_ = atmosphere::lut::SkyRadianceLowerBound(
      model, tables, features.multiple_scattering && tables.scattering_orders >= 2);

  atmosphere::lut::PrecomputeOptions options;
  options.sizes = tables.sizes;
  ShaderModel shader = shader_model(model, options, features.fp64);
  groups_.resize(shader.group_count);
  model_buffers_ = ModelBuffers(shader);
  // Of the texel-coordinate values the precompute derives, rendering reads one:
  // acos(μs_min) at TEXEL_SUN_THETA_MAX (ShaderModel::texel_layout).
  std::vector<double> texel_values(shader.texel_layout.count, 0.0);
  texel_values[shader.texel_layout.sun_theta_max] = std::acos(tables.geometry.min_sun_cosine());
  texel_coordinates_ = real_buffer(texel_values, features.fp64);

  // One program for every atmosphere of these table sizes: the model is in its buffers.
  std::vector<gl::ShaderDefine> defines = shader.shared_defines;
  for (const gl::ShaderDefine& d : SkyViewTable::defines()) defines.push_back(d);
  defines.push_back({"MULTIPLE_SCATTERING", features.multiple_scattering && tables.scattering_orders >= 2 ? "1" : "0"});
  eclipses_ = features.eclipses;
  defines_ = defines;
  defines.push_back({"ECLIPSES", "0"});  // the fill shades no surface
  fill_defines_ = defines;
  sky_view_ = std::make_unique<SkyViewTable>(builds, defines, groups_.size());
  tile_defines_ = defines_;
  tile_defines_.insert(tile_defines_.end(), frame_defines.begin(), frame_defines.end());
  gl::check_gl_error(fmt::format("the buffers of atmosphere '{}'", model.name));
  tables_to_upload_ = std::move(tables);
}

void GpuAtmosphere::upload_tables() {
  if (!tables_to_upload_) return;
  const atmosphere::lut::LookupTables& tables = *tables_to_upload_;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    GroupTextures& t = groups_[g];
    t.transmittance = texture_2d(tables.transmittance, g);
    t.irradiance = texture_2d(tables.irradiance, g);
    t.single_rayleigh = texture_3d(tables.single_rayleigh, g);
    t.single_mie = texture_3d(tables.single_mie, g);
    t.multiple = texture_3d(tables.multiple, g);
    for (const gl::Texture* x : {&t.transmittance, &t.irradiance, &t.single_rayleigh, &t.single_mie, &t.multiple})
      table_bytes_ += x->float_count() * sizeof(float);
  }
  tables_to_upload_.reset();
  gl::check_gl_error(fmt::format("uploading the tables of atmosphere '{}'", name_));
}

void GpuAtmosphere::expect_uploaded(const char* what) const {
  if (tables_to_upload_)
    throw std::logic_error(fmt::format("GpuAtmosphere '{}': {} before upload_tables()", name_, what));
}

void GpuAtmosphere::bind_tables(std::size_t group) const {
  expect_uploaded("tables bound");
  const GroupTextures& t = groups_.at(group);
  t.transmittance.bind(kTransmittanceUnit);
  t.single_rayleigh.bind(kSingleRayleighUnit);
  t.single_mie.bind(kSingleMieUnit);
  t.multiple.bind(kMultipleUnit);
  t.irradiance.bind(kIrradianceUnit);
  model_buffers_.bind();
  texel_coordinates_.bind_storage(kTexelCoordinates);
}

void GpuAtmosphere::bind(std::size_t group, std::size_t light) const {
  bind_tables(group);
  sky_view_->bind(kSkyViewUnit, light);
}

void GpuAtmosphere::add_dispatch_shapes(gl::DispatchShapes& shapes) const {
  expect_uploaded("the tables' shapes asked for");
  const GroupTextures& t = groups_.front();
  const auto sampled = [&](unsigned unit, const gl::Texture& texture) {
    const gl::TextureShape shape = texture.shape();
    shapes.sampled[{static_cast<int>(unit), shape.kind}] = shape;
  };
  sampled(kTransmittanceUnit, t.transmittance);
  sampled(kSingleRayleighUnit, t.single_rayleigh);
  sampled(kSingleMieUnit, t.single_mie);
  sampled(kMultipleUnit, t.multiple);
  sampled(kIrradianceUnit, t.irradiance);
  const gl::TextureShape sky_view = sky_view_->shape();
  shapes.sampled[{static_cast<int>(kSkyViewUnit), sky_view.kind}] = sky_view;
  shapes.images[{static_cast<int>(kOutputImage), sky_view.kind}] = sky_view;
}

void GpuAtmosphere::set_group(const gl::ShaderProgram& program, std::size_t group) const {
  program.set_uniform("wavelength_group", static_cast<int>(group));
  program.set_uniform("sky_view_layer_base", static_cast<int>(group) * SkyViewTable::kLayersPerGroup);
  program.set_uniform("sky_view_theta_horizon", static_cast<float>(sky_view_->theta_horizon_rad()));
}

std::vector<gl::ShaderDefine> FrameVariant::defines() const {
  return {{"PROJECTION_KIND", std::to_string(projection_kind)},
          {"ECLIPSES", eclipses ? "1" : "0"},
          {"AIR_SHADOWS", eclipses && air_shadows ? "1" : "0"},
          {"ALBEDO_LOD0", albedo_lod0 ? "1" : "0"}};
}

std::string FrameVariant::key() const {
  return fmt::format("{} {:d} {:d} {:d}", projection_kind, eclipses, eclipses && air_shadows, albedo_lod0);
}

std::vector<gl::ShaderDefine> GpuAtmosphere::gbuffer_path_defines(const FrameVariant& frame) const {
  FrameVariant f = frame;
  f.eclipses = frame.eclipses && eclipses_;
  std::vector<gl::ShaderDefine> defines = defines_;
  for (const gl::ShaderDefine& d : f.defines()) defines.push_back(d);
  return defines;
}

std::vector<gl::ShaderDefine> GpuAtmosphere::tile_defines(const FrameVariant& frame, const TileVariant& v,
                                                          bool eclipse_sky) const {
  FrameVariant f = frame;
  f.eclipses = frame.eclipses && eclipses_;
  std::vector<gl::ShaderDefine> defines = tile_defines_;
  for (const gl::ShaderDefine& d : f.defines()) defines.push_back(d);
  defines.insert(defines.end(), {{"SKY_VIEW", v.sky_view ? "1" : "0"},
                                 {"TILE_GROUND", std::to_string(static_cast<int>(v.ground))},
                                 {"TILE_OTHERS", std::to_string(v.others)},
                                 {"SUN", v.sun ? "1" : "0"}});
  if (eclipse_sky) {
    defines.push_back({"ECLIPSE_SKY", "1"});
    for (const gl::ShaderDefine& d : EclipseSkyTable::defines()) defines.push_back(d);
  }
  return defines;
}

const gl::ShaderProgram& GpuAtmosphere::gbuffer_path_program(const FrameVariant& frame) {
  return built_program(*builds_, "render/atmosphere_pass.comp", gbuffer_path_defines(frame));
}

const gl::ShaderProgram& GpuAtmosphere::tile_program(const FrameVariant& frame, const TileVariant& v,
                                                     bool eclipse_sky) {
  return built_program(*builds_, "render/atmosphere_tile.comp", tile_defines(frame, v, eclipse_sky));
}

void GpuAtmosphere::start_gbuffer_path_program(const FrameVariant& frame, gl::BuildFor build_for) const {
  start_built_program(*builds_, "render/atmosphere_pass.comp", gbuffer_path_defines(frame), build_for);
}

void GpuAtmosphere::start_tile_program(const FrameVariant& frame, const TileVariant& v, bool eclipse_sky,
                                       gl::BuildFor build_for) const {
  start_built_program(*builds_, "render/atmosphere_tile.comp", tile_defines(frame, v, eclipse_sky), build_for);
}

bool GpuAtmosphere::tile_program_built(const FrameVariant& frame, const TileVariant& v, bool eclipse_sky) const {
  return program_built(*builds_, "render/atmosphere_tile.comp", tile_defines(frame, v, eclipse_sky));
}

bool GpuAtmosphere::gbuffer_path_program_built(const FrameVariant& frame) const {
  return program_built(*builds_, "render/atmosphere_pass.comp", gbuffer_path_defines(frame));
}

bool GpuAtmosphere::fill_sky_view(double camera_radius_m, double sun_cosine, double sun_angular_radius_rad,
                                  std::size_t light) {
  sky_view_->set_camera(camera_radius_m, ground_radius_m_, sun_cosine, sun_angular_radius_rad);
  if (sky_view_->holds(light)) return false;
  const gl::ShaderProgram& fill = sky_view_->fill_program();
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    bind_tables(g);
    set_group(fill, g);
    sky_view_->fill_group(g, light);
  }
  return true;
}

EclipseSkyTable& GpuAtmosphere::eclipse_sky() {
  if (!eclipse_sky_)
    eclipse_sky_ =
        std::make_unique<EclipseSkyTable>(*builds_, fill_defines_, groups_.size(), ground_radius_m_, top_radius_m_);
  return *eclipse_sky_;
}

void GpuAtmosphere::fill_eclipse_sky(const glm::dvec3& camera_m) {
  eclipse_sky().fill(camera_m, [&](const gl::ShaderProgram& fill, std::size_t g) {
    bind_tables(g);
    set_group(fill, g);
  });
}

}  // namespace zenith::render
