#include "render/frame/frame_in_progress.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "render/lut/shader_model.h"
#include "render/shader_bindings.h"

namespace zenith::render {
namespace {

/// Work groups for `count` tiles: a 2D grid (x ≤ 65535), the shader folds it back.
std::array<unsigned, 2> tile_groups(std::size_t count) {
  const std::size_t x = std::min<std::size_t>(count, 65535);
  return {static_cast<unsigned>(x), static_cast<unsigned>((count + x - 1) / x)};
}

}  // namespace

std::array<float, 4> group_lanes(const std::vector<double>& values, std::size_t group) {
  std::array<float, 4> out{0, 0, 0, 0};
  for (std::size_t k = 0; k < kWavelengthLanes && group * kWavelengthLanes + k < values.size(); ++k)
    out[k] = static_cast<float>(values[group * kWavelengthLanes + k]);
  return out;
}

std::array<float, 4> group_lanes(const std::vector<std::array<double, 3>>& weights, std::size_t channel,
                                 std::size_t group) {
  std::array<float, 4> out{0, 0, 0, 0};
  for (std::size_t k = 0; k < kWavelengthLanes && group * kWavelengthLanes + k < weights.size(); ++k)
    out[k] = static_cast<float>(weights[group * kWavelengthLanes + k][channel]);
  return out;
}

void FrameInProgress::set_the_body(const gl::ShaderProgram& p, std::size_t b) const {
  const GpuBody& g = bodies[b];
  p.set_uniform("the_body.centre", g.centre);
  p.set_uniform("the_body.shape", g.shape);
  p.set_uniform("the_body.albedo_map", g.albedo_map);
  p.set_uniform("the_body.world_to_body0", g.world_to_body[0]);
  p.set_uniform("the_body.world_to_body1", g.world_to_body[1]);
  p.set_uniform("the_body.world_to_body2", g.world_to_body[2]);
}

void FrameInProgress::set_frame_uniforms(const gl::ShaderProgram& p) const {
  p.set_uniform("body_count", static_cast<int>(scene.bodies.size()));
  p.set_uniform("camera_to_world", camera_matrix);
  p.set_uniform("sun_direction",
                std::array<float, 3>{static_cast<float>(sun.x), static_cast<float>(sun.y), static_cast<float>(sun.z)});
  p.set_uniform("sun_angular_radius", static_cast<float>(sun_radius));
  for (std::size_t k = 0; k < shadow_limb_channels.size(); ++k)
    p.set_uniform(fmt::format("shadow_limb_rgb[{}]", k), shadow_limb_channels[k]);
  p.set_uniform("air_shadow_count", static_cast<int>(air_shadow_bodies.size()));
  for (std::size_t s = 0; s < air_shadow_bodies.size(); ++s) {
    p.set_uniform(fmt::format("air_shadow_occluder[{}]", s), air_shadow_occluders[s]);
    p.set_uniform(fmt::format("air_shadow_bodies[{}]", s), air_shadow_bodies[s]);
  }
  p.set_uniform("pixel_angle", static_cast<float>(pixel_angle));
  p.set_uniform("projection_kind", static_cast<int>(gpu_projection.kind));
  for (int k = 0; k < 4; ++k)
    p.set_uniform(fmt::format("projection_params[{}]", k), gpu_projection.params[static_cast<std::size_t>(k)]);
  p.set_uniform("sun_draw_radius", static_cast<float>(sun_radius));
  p.set_uniform("sun_pixel_angle", static_cast<float>(sun_pixel_angle));
  p.set_uniform("sun_point_sigma", static_cast<float>(sun_point_sigma));
  const glm::dvec3& moon = occulter.direction;
  p.set_uniform("sun_occulter_direction", std::array<float, 3>{static_cast<float>(moon.x), static_cast<float>(moon.y),
                                                               static_cast<float>(moon.z)});
  p.set_uniform("sun_occulter_radius", static_cast<float>(occulter.angular_radius_rad));
  p.set_uniform("sun_lift_count", sun_lift.active ? kSunLiftSamples : 0);
  if (sun_lift.active) {
    const glm::dvec3& up = sun_lift.up;
    p.set_uniform("sun_lift_up",
                  std::array<float, 3>{static_cast<float>(up.x), static_cast<float>(up.y), static_cast<float>(up.z)});
    p.set_uniform("sun_lift_first", static_cast<float>(sun_lift.first_altitude_rad));
    p.set_uniform("sun_lift_step", static_cast<float>(sun_lift.step_rad));
    for (int i = 0; i < kSunLiftSamples; ++i)
      p.set_uniform(fmt::format("sun_lift_rad[{}]", i), sun_lift.lift_rad[static_cast<std::size_t>(i)]);
  }
  for (const auto& [name, k] :
       {std::pair{"world_ray_x", 0}, std::pair{"world_ray_y", 1}, std::pair{"world_ray_centre", 2}})
    p.set_uniform(name, world_ray[static_cast<std::size_t>(k)]);
}

const gl::ShaderProgram& FrameInProgress::prepare(const gl::ShaderProgram& p) {
  if (frame_ready.insert(&p).second) {
    set_frame_uniforms(p);
    p.set_uniform("exposure", static_cast<float>(scene.camera.exposure));
  }
  if (band_ready.insert(&p).second) {
    p.set_uniform("band_origin", band_origin);
    p.set_uniform("band_size", band_size);
    if (gpu_projection.kind == warp::ProjectionKind::ray_table) p.set_uniform("projection_table_origin", band_origin);
  }
  return p;
}

void FrameInProgress::dispatch_tiles(const gl::ShaderProgram& p, TileList list, std::size_t tiles_per_group) {
  prepare(p);
  p.set_uniform("tile_offset", static_cast<int>(list.offset));
  p.set_uniform("tile_count", static_cast<int>(list.count));
  const auto grid = tile_groups((list.count + tiles_per_group - 1) / tiles_per_group);
  p.dispatch(grid[0], grid[1]);
}

void FrameInProgress::set_group_uniforms(const gl::ShaderProgram& p, std::size_t g, const FrameLight& light) {
  prepare(p);
  p.set_uniform("first_group", g == 0 && light.is_sun() ? 1 : 0);  // a second light adds to the sun's
  p.set_uniform("last_group", g + 1 == groups ? 1 : 0);
  set_light_uniforms(p, g, light);
  for (std::size_t k = 0; k < std::size_t(kLimbCoefficients); ++k) {
    std::vector<double> a_k;
    for (const atmosphere::LimbDarkening& law : sun_limb) a_k.push_back(law.coefficients[k]);
    p.set_uniform(fmt::format("limb_polynomial[{}]", k), group_lanes(a_k, g));
  }
  p.set_uniform("albedo_from_r", group_lanes(albedo_weights, 0, g));
  p.set_uniform("albedo_from_g", group_lanes(albedo_weights, 1, g));
  p.set_uniform("albedo_from_b", group_lanes(albedo_weights, 2, g));
  p.set_uniform("rgb_from_lanes_r", group_lanes(rgb_weights, 0, g));
  p.set_uniform("rgb_from_lanes_g", group_lanes(rgb_weights, 1, g));
  p.set_uniform("rgb_from_lanes_b", group_lanes(rgb_weights, 2, g));
}

void FrameInProgress::set_light_uniforms(const gl::ShaderProgram& p, std::size_t g, const FrameLight& light) const {
  const glm::dvec3 d = light.direction;
  p.set_uniform("sun_direction",
                std::array<float, 3>{static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z)});
  p.set_uniform("sun_angular_radius", static_cast<float>(light.angular_radius_rad));
  p.set_uniform("sun_irradiance", group_lanes(light.irradiance_W_m2_nm, g));
  p.set_uniform("sun_centre_radiance", group_lanes(light.centre_radiance_W_m2_sr_nm, g));  // 0: no disc
  p.set_uniform("wavelength_group", static_cast<int>(g));
  p.set_uniform("air_shadow_count", light.is_sun() ? static_cast<int>(air_shadow_bodies.size()) : 0);
  // The bodies' shadows cover the sun's limb-darkened disc, or the Moon's uniform one.
  for (std::size_t k = 0; k < std::size_t(kLimbCoefficients); ++k) {
    const float uniform_disc = k == 0 ? 1.0f : 0.0f;  // b = (1, 0, …)
    p.set_uniform(fmt::format("shadow_limb_lanes[{}]", k),
                  light.is_sun() ? group_lanes(shadow_limb_over_mean(*this, k), g)
                                 : std::array<float, 4>{uniform_disc, uniform_disc, uniform_disc, uniform_disc});
  }
}

FrameLight FrameInProgress::sun_light() const {
  return {FrameLight::Source::sun, sun, sun_radius, scene.sun.irradiance_W_m2_nm, sun_centre};
}

const FrameLight* FrameInProgress::moon() const {
  for (const FrameLight& light : lights)
    if (light.source == FrameLight::Source::moon) return &light;
  return nullptr;
}

bool FrameLight::lights(const AtmospherePass& pass) const { return is_sun() || pass.moonlit; }

TileScene FrameInProgress::tile_scene(bool sun_disc, bool one_pass_tiles) const {
  TileScene tiles;
  tiles.scene = &scene;
  tiles.cones = cones;
  tiles.world_to_camera = world_to_camera;
  // The disc is drawn where it is seen: lifted by the air (sun_refraction.h).
  tiles.sun_camera = sun_lift.active ? world_to_camera * sun_lift.apparent_sun : sun_camera;
  tiles.sun_reach_rad = sun_reach;
  tiles.sun_disc = sun_disc;
  tiles.one_pass_tiles = one_pass_tiles;
  for (const AtmospherePass& pass : passes)
    tiles.shells.push_back(
        {pass.body, pass.direction_camera, pass.distance_m, pass.top_radius_m, pass.gpu != nullptr, pass.sky_view});
  return tiles;
}

bool FrameInProgress::touches_view(const AtmospherePass& pass) const {
  return !cones
              ->tiles_touching_sphere(pass.direction_camera, pass.distance_m, pass.top_radius_m, 0, projection.height())
              .empty();
}

}  // namespace zenith::render
