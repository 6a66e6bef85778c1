#include "render/frame/sky_view_table.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/units.h"
#include "render/shader_bindings.h"
#include "render/shader_programs.h"

namespace zenith::render {

std::vector<gl::ShaderDefine> SkyViewTable::defines() {
  return {{"SKY_VIEW_AZIMUTH_TEXELS", std::to_string(kAzimuthTexels)},
          {"SKY_VIEW_ZENITH_TEXELS", std::to_string(kZenithTexels)},
          {"SKY_VIEW_LAYERS", std::to_string(kLayersPerGroup)}};
}

SkyViewTable::SkyViewTable(gl::ProgramBuilds& builds, std::span<const gl::ShaderDefine> atmosphere_defines,
                           std::size_t groups)
    : builds_(&builds),
      defines_(atmosphere_defines.begin(), atmosphere_defines.end()),
      groups_(std::max<std::size_t>(groups, 1)) {
  tables_[0] = gl::Texture::create_2d_array(gl::TextureFormat::rgba32f, kAzimuthTexels, kZenithTexels,
                                            static_cast<int>(groups_) * kLayersPerGroup);
}

void SkyViewTable::start_program() const { start_built_program(*builds_, "render/sky_view.comp", defines_); }

const gl::ShaderProgram& SkyViewTable::fill_program() const {
  return built_program(*builds_, "render/sky_view.comp", defines_);
}

void SkyViewTable::set_camera(double camera_radius_m, double ground_radius_m, double sun_cosine,
                              double sun_angular_radius_rad) {
  const double r = std::max(camera_radius_m, ground_radius_m);
  theta_horizon_rad_ = core::kPi - std::asin(std::min(ground_radius_m / r, 1.0));
  camera_ = {static_cast<float>(r), static_cast<float>((r - ground_radius_m) * (r + ground_radius_m)),
             static_cast<float>(std::clamp(sun_cosine, -1.0, 1.0)), static_cast<float>(theta_horizon_rad_),
             static_cast<float>(sun_angular_radius_rad)};
  const gl::ShaderProgram& fill = fill_program();
  fill.set_uniform("camera_r", camera_.camera_r);
  fill.set_uniform("camera_ground_power", camera_.camera_ground_power);
  fill.set_uniform("camera_mu_s", camera_.camera_mu_s);
  fill.set_uniform("theta_horizon", camera_.theta_horizon);
  fill.set_uniform("sun_angular_radius", camera_.sun_angular_radius);
}

void SkyViewTable::fill_group(std::size_t group, std::size_t light) {
  gl::Texture& table = tables_.at(light);
  if (table.id() == 0)
    table = gl::Texture::create_2d_array(gl::TextureFormat::rgba32f, kAzimuthTexels, kZenithTexels,
                                         static_cast<int>(groups_) * kLayersPerGroup);
  const gl::ShaderProgram& fill = fill_program();
  fill.set_uniform("layer_base", static_cast<int>(group) * kLayersPerGroup);
  table.bind_image(binding::kOutputImage, gl::ImageAccess::write_only);
  fill.dispatch_covering(kAzimuthTexels, kZenithTexels);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  // Whole once its last group is filled; part filled, it holds no camera.
  if (group + 1 == groups_)
    filled_.at(light) = camera_;
  else
    filled_.at(light).reset();
}

}  // namespace zenith::render
