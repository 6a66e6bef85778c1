#include "render/frame/eclipse_sky_table.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include <glm/geometric.hpp>

#include "core/units.h"
#include "render/lut/shader_model.h"
#include "render/shader_bindings.h"
#include "render/shader_programs.h"

namespace zenith::render {
namespace {

constexpr std::size_t kLanes = kWavelengthLanes;

std::array<float, 3> vec3_of(const glm::dvec3& v) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}

/// A float[] literal of `values` for a GLSL define.
std::string float_array(const std::vector<double>& values) {
  std::string s = "float[](";
  for (std::size_t i = 0; i < values.size(); ++i) s += (i ? ", " : "") + std::to_string(values[i]);
  return s + ")";
}

}  // namespace

std::vector<gl::ShaderDefine> EclipseSkyTable::defines() {
  const astro::MoonShadowOptions shadow;
  return {{"ECLIPSE_SKY_AZIMUTH_TEXELS", std::to_string(kAzimuthTexels)},
          {"ECLIPSE_SKY_ZENITH_TEXELS", std::to_string(kZenithTexels)},
          {"ECLIPSE_SKY_LAYERS", std::to_string(kLayersPerGroup)},
          {"ECLIPSE_SKY_SEGMENTS", std::to_string(kSegments)},
          {"SHADOW_PROFILE_SAMPLES", std::to_string(shadow.profile_samples)},
          {"SHADOW_FIELD_ACROSS", std::to_string(shadow.field_across)},
          {"SHADOW_FIELD_SIDE", std::to_string(shadow.field_side)},
          {"SHADOW_FIELD_LEVELS", std::to_string(shadow.field_altitudes_m.size())},
          {"SHADOW_FIELD_VALUES", std::to_string(astro::kShadowSkyValues)},
          {"SHADOW_FIELD_ALTITUDES", float_array(shadow.field_altitudes_m)}};
}

EclipseSkyTable::EclipseSkyTable(gl::ProgramBuilds& builds, std::span<const gl::ShaderDefine> atmosphere_defines,
                                 std::size_t groups, double ground_radius_m, double top_radius_m)
    : builds_(&builds),
      defines_(atmosphere_defines.begin(), atmosphere_defines.end()),
      groups_(std::max<std::size_t>(groups, 1)),
      ground_radius_m_(ground_radius_m),
      top_radius_m_(top_radius_m) {
  for (const gl::ShaderDefine& d : defines()) defines_.push_back(d);
  table_ = gl::Texture::create_2d_array(gl::TextureFormat::rgba32f, kAzimuthTexels, kZenithTexels,
                                        static_cast<int>(groups_) * kLayersPerGroup);
}

EclipseSkyTable::~EclipseSkyTable() { stop_building(); }

void EclipseSkyTable::stop_building() {
  if (!next_.valid()) return;
  next_stop_.request_stop();
  next_.wait();  // holds ShadowBuildStopped (or the shadow, if it had just finished): dropped
  next_ = {};
  next_stop_ = {};
}

void EclipseSkyTable::keep_tables(const atmosphere::AtmosphereModel& model,
                                  std::shared_ptr<const atmosphere::lut::LookupTables> tables) {
  model_ = model;
  tables_ = std::move(tables);
  queries_ = std::make_unique<atmosphere::lut::TableQueries>(*model_, *tables_);
}

EclipseSkyTable::ShadowUpdate EclipseSkyTable::update(const astro::EclipseGeometry& geometry,
                                                      const glm::dvec3& camera_m, bool background) {
  if (!queries_) throw std::logic_error("EclipseSkyTable::update: no tables kept");
  ShadowUpdate done = ShadowUpdate::moved;
  if (next_.valid() && next_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    set_shadow(next_.get());
    done = ShadowUpdate::swapped;
  }
  if (shadow_ && shadow_->still_fits(geometry, camera_m)) {
    shadow_->move_to(geometry, camera_m);
    return done;
  }
  if (background) {
    // Frames go on with the shadow held, moved, until the new one is ready:
    // its sky differs by 1.4 % per degree of the axis' zenith angle
    // (docs/validation.md), which moves ~0.01° in a second of sky time.
    // With none held yet the caller draws the sky without the Moon's shadow.
    if (shadow_) shadow_->move_to(geometry, camera_m);
    if (!next_.valid()) {
      astro::MoonShadowOptions options;
      options.threads = std::max(1u, std::thread::hardware_concurrency() / 2);  // the frames need the rest
      next_ = std::async(std::launch::async, [this, geometry, camera_m, options, stop = next_stop_.get_token()] {
        return std::make_unique<astro::MoonShadow>(geometry, *queries_, *model_, camera_m, options, stop);
      });
    }
    return ShadowUpdate::building;
  }
  stop_building();  // not needed now: the frame builds the shadow it needs itself
  set_shadow(std::make_unique<astro::MoonShadow>(geometry, *queries_, *model_, camera_m));
  return ShadowUpdate::built;
}

void EclipseSkyTable::set_shadow(std::unique_ptr<astro::MoonShadow> shadow) {
  shadow_ = std::move(shadow);
  const astro::MoonShadow& s = *shadow_;
  const astro::MoonShadowOptions& o = s.options();
  const std::size_t n = s.wavelengths(), samples = o.profile_samples, levels = o.field_altitudes_m.size();
  const std::size_t nodes_per_level = o.field_across * o.field_side;
  profiles_.clear();
  fields_.clear();
  mie_k1_.assign(groups_, {});
  mie_k2_.assign(groups_, {});
  mie_forward_.assign(groups_, {});
  mie_k3_.assign(groups_, {});
  mie_k4_.assign(groups_, {});
  for (std::size_t g = 0; g < groups_; ++g) {
    const std::size_t first = g * kLanes, lanes = first < n ? std::min(kLanes, n - first) : 0;
    // V: texel k holds x_k's values for the group's wavelengths; lanes past the last wavelength 1.
    std::vector<float> profile(samples * kLanes, 1.0f);
    for (std::size_t k = 0; k < samples; ++k)
      for (std::size_t l = 0; l < lanes; ++l) profile[k * kLanes + l] = s.profile()[k * n + first + l];
    profiles_.push_back(gl::Texture::create_2d(gl::TextureFormat::rgba32f, static_cast<int>(samples), 1, profile));
    // V̄: texel (j, k, c · levels + level) holds value c of node (j, k, level), of the values V̄ reads.
    std::vector<float> field(nodes_per_level * levels * astro::kShadowSkyValues * kLanes, 0.0f);
    for (std::size_t level = 0; level < levels; ++level)
      for (std::size_t node = 0; node < nodes_per_level; ++node)
        for (std::size_t c = 0; c < astro::kShadowSkyValues; ++c)
          for (std::size_t l = 0; l < lanes; ++l) {
            const std::size_t from = ((level * nodes_per_level + node) * n + first + l) * astro::kShadowFieldValues + c;
            const std::size_t to = ((c * levels + level) * nodes_per_level + node) * kLanes + l;
            field[to] = s.field()[from];
          }
    fields_.push_back(gl::Texture::create_3d(gl::TextureFormat::rgba32f, static_cast<int>(o.field_across),
                                             static_cast<int>(o.field_side),
                                             static_cast<int>(levels * astro::kShadowSkyValues), field));
    for (std::size_t l = 0; l < lanes; ++l) {
      mie_k1_[g][l] = static_cast<float>(s.mie_scatterers()[first + l].k1);
      mie_k2_[g][l] = static_cast<float>(s.mie_scatterers()[first + l].k2);
      mie_forward_[g][l] = static_cast<float>(s.mie_scatterers()[first + l].forward);
      mie_k3_[g][l] = static_cast<float>(s.mie_scatterers()[first + l].k3);
      mie_k4_[g][l] = static_cast<float>(s.mie_scatterers()[first + l].k4);
    }
  }
  rayleigh_k1_ = static_cast<float>(s.rayleigh_scatterers().front().k1);
  rayleigh_k2_ = static_cast<float>(s.rayleigh_scatterers().front().k2);
  rayleigh_dipole_ = static_cast<float>(s.rayleigh_scatterers().front().dipole);
}

void EclipseSkyTable::start_program() const { start_built_program(*builds_, "render/eclipse_sky.comp", defines_); }

const gl::ShaderProgram& EclipseSkyTable::fill_program() const {
  return built_program(*builds_, "render/eclipse_sky.comp", defines_);
}

void EclipseSkyTable::prepare_fill(const glm::dvec3& camera_m) {
  const glm::dvec3& sun = shadow_->geometry().sun_direction;
  const double r = std::max(glm::length(camera_m), ground_radius_m_);
  const glm::dvec3 up = glm::normalize(camera_m);
  // φ = 0 toward the sun's azimuth; with the sun overhead any horizontal direction will do.
  glm::dvec3 h = sun - glm::dot(sun, up) * up;
  if (glm::length(h) < 1e-9) h = std::abs(up.x) < 0.9 ? glm::dvec3{1, 0, 0} : glm::dvec3{0, 1, 0};
  azimuth_h_ = glm::normalize(h - glm::dot(h, up) * up);
  azimuth_w_ = glm::cross(up, azimuth_h_);
  camera_m_ = camera_m;
  const double theta_horizon_rad = core::kPi - std::asin(std::min(ground_radius_m_ / r, 1.0));
  // From outside the shell only the directions within its disc meet air.
  const bool outside = r > top_radius_m_;
  theta_top_rad_ = outside ? static_cast<float>(core::kPi - std::asin(top_radius_m_ / r)) : 0.0f;
  theta_horizon_rad_ = static_cast<float>(theta_horizon_rad);
  const gl::ShaderProgram& fill = fill_program();
  fill.set_uniform("camera_r", static_cast<float>(r));
  fill.set_uniform("camera_ground_power", static_cast<float>((r - ground_radius_m_) * (r + ground_radius_m_)));
  fill.set_uniform("camera_top_power", outside ? static_cast<float>((r - top_radius_m_) * (r + top_radius_m_)) : 0.0f);
  fill.set_uniform("theta_top", theta_top_rad_);
  fill.set_uniform("theta_horizon", static_cast<float>(theta_horizon_rad));
  fill.set_uniform("camera_up", vec3_of(up));
  fill.set_uniform("azimuth_h", vec3_of(azimuth_h_));
  fill.set_uniform("azimuth_w", vec3_of(azimuth_w_));
  fill.set_uniform("fill_sun", vec3_of(sun));
}

void EclipseSkyTable::fill_group(std::size_t group) {
  const gl::ShaderProgram& fill = fill_program();
  set_uniforms(fill, group);
  fill.set_uniform("layer_base", static_cast<int>(group) * kLayersPerGroup);
  bind(group);
  table_.bind_image(binding::kOutputImage, gl::ImageAccess::write_only);
  fill.dispatch_covering(kAzimuthTexels, kZenithTexels);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void EclipseSkyTable::set_shadow_frame(const gl::ShaderProgram& p) const {
  const astro::MoonShadow& s = *shadow_;
  const astro::EclipseGeometry& g = s.geometry();
  // w = m − c from the camera to the Moon's centre; the camera's offset from the axis is −w⊥.
  const glm::dvec3 w = g.moon_centre_m - camera_m_;
  const double along = glm::dot(w, g.sun_direction);
  const glm::dvec3 across = -(w - along * g.sun_direction);
  p.set_uniform("shadow_sun", vec3_of(g.sun_direction));
  p.set_uniform("shadow_e1", vec3_of(s.axis_1()));
  p.set_uniform("shadow_e2", vec3_of(s.axis_2()));
  p.set_uniform("shadow_camera_across", std::array<float, 2>{static_cast<float>(glm::dot(across, s.axis_1())),
                                                             static_cast<float>(glm::dot(across, s.axis_2()))});
  p.set_uniform("shadow_camera_along", static_cast<float>(along));
  p.set_uniform("shadow_moon_radius", static_cast<float>(g.moon_radius_m));
  p.set_uniform("shadow_moon_radius_0", static_cast<float>(s.camera_moon_radius_rad()));
  p.set_uniform("shadow_profile_end", static_cast<float>(s.profile_end_rad()));
  p.set_uniform("shadow_field_end", static_cast<float>(s.field_end_m()));
  p.set_uniform("shadow_rayleigh_k1", rayleigh_k1_);
  p.set_uniform("shadow_rayleigh_k2", rayleigh_k2_);
  p.set_uniform("shadow_rayleigh_dipole", rayleigh_dipole_);
}

void EclipseSkyTable::set_uniforms(const gl::ShaderProgram& p, std::size_t group) const {
  set_shadow_frame(p);
  p.set_uniform("shadow_mie_k1", mie_k1_.at(group));
  p.set_uniform("shadow_mie_k2", mie_k2_.at(group));
  p.set_uniform("shadow_mie_forward", mie_forward_.at(group));
  p.set_uniform("shadow_mie_k3", mie_k3_.at(group));
  p.set_uniform("shadow_mie_k4", mie_k4_.at(group));
  p.set_uniform("eclipse_sky_h", vec3_of(azimuth_h_));
  p.set_uniform("eclipse_sky_w", vec3_of(azimuth_w_));
  p.set_uniform("eclipse_sky_theta_top", theta_top_rad_);
  p.set_uniform("eclipse_sky_theta_horizon", theta_horizon_rad_);
  p.set_uniform("eclipse_sky_layer_base", static_cast<int>(group) * kLayersPerGroup);
}

void EclipseSkyTable::bind(std::size_t group) const {
  table_.bind(binding::kEclipseSkyUnit);
  profiles_.at(group).bind(binding::kShadowProfileUnit);
  fields_.at(group).bind(binding::kShadowFieldUnit);
}

}  // namespace zenith::render
