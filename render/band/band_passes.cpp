#include "render/band/band_passes.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <string>

#include "render/frame/frame_programs.h"
#include "render/frame/sun_light.h"
#include "render/gl/shader_program.h"
#include "render/shader_bindings.h"

namespace zenith::render {
namespace {

using gl::ShaderProgram;

const std::string& body_name(const FrameInProgress& frame, const AtmospherePass& pass) {
  return frame.scene.bodies[static_cast<std::size_t>(pass.body)].name;
}

/// The pass timer's name of a one-pass tile variant's pass.
std::string one_pass_label(const FrameInProgress& frame, const AtmospherePass& pass, const TileVariant& variant,
                           const FrameLight& light) {
  return fmt::format("{}atmosphere {}, one pass, {}, {}{}{}",
                     light.is_sun() ? "" : "moonlight: ", body_name(frame, pass),
                     variant.sky_view ? "sky view" : "4D tables",
                     variant.ground == TileCover::none  ? "sky"
                     : variant.ground == TileCover::all ? "ground"
                                                        : "horizon",
                     variant.others == 0 ? "" : " + bodies", variant.sun ? " + sun" : "");
}

/// Tiles one atmosphere touches, lit by `light`: a pass per wavelength group and variant, to the output.
void draw_one_pass_tiles(FrameInProgress& frame, BandResources& resources, const BandTiles& band,
                         const FrameLight& light, PassTimer& timer) {
  if (band.one_pass_atmosphere_tiles == 0) return;
  for (std::size_t g = 0; g < frame.groups; ++g) {
    for (std::size_t a = 0; a < frame.passes.size(); ++a) {
      const AtmospherePass& pass = frame.passes[a];
      if (band.lists[a].one_pass.empty() || !light.lights(pass)) continue;
      // The Moon's passes: its own sky-view table where it has one, and no sun disc.
      pass.gpu->bind(g, !light.is_sun() && pass.moon_sky_view ? light.sky_view_slot() : 0);
      resources.bind_bodies();
      resources.bind_tiles();
      for (const auto& [tile_variant, list] : band.lists[a].one_pass) {
        // The sun's light invisible through this atmosphere: its sky and
        // ground stay as the band's clear left them (zero); what lies beyond
        // the shell (another body, the sun's disc) is drawn as always.
        if (light.is_sun() && sky_and_ground_unlit(pass, tile_variant)) continue;
        TileVariant variant = tile_variant;
        if (!light.is_sun()) {
          variant.sun = false;
          variant.sky_view = variant.sky_view && pass.moon_sky_view;
        }
        // The Moon's shadow on the sun's sky (render/frame/eclipse_sky_table.h).
        const bool eclipse_sky = light.is_sun() && pass.eclipse_sky;
        // Until the tiles' own program is built, their kind's general one: the same pixels.
        const bool general = light.is_sun() && pass.general_tiles;
        const ShaderProgram& p =
            pass.gpu->tile_program(frame.variant, general ? general_tile_variant(variant) : variant, eclipse_sky);
        frame.set_group_uniforms(p, g, light);
        pass.gpu->set_group(p, g);
        if (eclipse_sky) {
          pass.gpu->eclipse_sky().set_uniforms(p, g);
          pass.gpu->eclipse_sky().bind(g);
          p.set_uniform("eclipse_shadows_ground", frame.occulter.shadow_caster_is_a_body ? 0 : 1);
        }
        frame.set_the_body(p, static_cast<std::size_t>(pass.body));
        p.set_uniform("planet", pass.body);
        p.set_uniform("camera_top_power", static_cast<float>(pass.power_m2));
        timer.gpu(one_pass_label(frame, pass, variant, light), [&] { frame.dispatch_tiles(p, list); });
      }
    }
    if (g + 1 < frame.groups) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the next group adds to these pixels
  }
}

/// Tiles where shells overlap, lit by `light`: the G-buffer, then per
/// wavelength group the atmospheres front to back and the resolve.
void draw_gbuffer_tiles(FrameInProgress& frame, BandResources& resources, const BandTiles& band,
                        const FrameLight& light, PassTimer& timer) {
  if (band.gbuffer_tiles.count == 0) return;
  const FramePasses& fp = *frame.programs;
  resources.bind_gbuffer_for_the_body_pass();
  timer.gpu("g-buffer", [&] { frame.dispatch_tiles(*fp.gbuffer, band.gbuffer_tiles); });
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

  for (std::size_t g = 0; g < frame.groups; ++g) {
    resources.bind_gbuffer_for_the_atmosphere_passes();
    for (std::size_t a = 0; a < frame.passes.size(); ++a) {
      const AtmospherePass& pass = frame.passes[a];
      if (band.lists[a].gbuffer.count == 0 || !light.lights(pass)) continue;
      const ShaderProgram& p = pass.gpu->gbuffer_path_program(frame.variant);
      pass.gpu->bind(g);
      resources.bind_bodies();
      resources.bind_tiles();
      frame.prepare(p);
      pass.gpu->set_group(p, g);
      frame.set_the_body(p, static_cast<std::size_t>(pass.body));
      p.set_uniform("planet", pass.body);
      p.set_uniform("camera_top_power", static_cast<float>(pass.power_m2));
      frame.set_light_uniforms(p, g, light);
      p.set_uniform("albedo_from_r", group_lanes(frame.albedo_weights, 0, g));
      p.set_uniform("albedo_from_g", group_lanes(frame.albedo_weights, 1, g));
      p.set_uniform("albedo_from_b", group_lanes(frame.albedo_weights, 2, g));
      timer.gpu(
          fmt::format("{}atmosphere {}, g-buffer path", light.is_sun() ? "" : "moonlight: ", body_name(frame, pass)),
          [&] { frame.dispatch_tiles(p, band.lists[a].gbuffer); });
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    frame.set_group_uniforms(*fp.resolve, g, light);
    timer.gpu("resolve", [&] { frame.dispatch_tiles(*fp.resolve, band.gbuffer_tiles); });
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

}  // namespace

void set_direct_light_uniforms(FrameInProgress& frame) {
  // direct_light.comp: every wavelength at once (render/frame/frame_constants.h);
  // the sun's disc rgb = Σ_λ exposure w(λ) I_centre(λ) Σ_k a_k(λ) μ^k × coverage,
  // a polynomial in μ whose coefficients are summed here over λ.
  const scene::Scene& scene = frame.scene;
  const FramePasses& fp = *frame.programs;
  const double exposure = scene.camera.exposure;
  const std::array<float, 9> rgb_from_albedo = direct_light_colour_matrix(frame, scene);
  frame.prepare(*fp.direct_light).set_uniform("rgb_from_albedo", rgb_from_albedo);
  frame.prepare(*fp.direct_light_one).set_uniform("rgb_from_albedo", rgb_from_albedo);
  if (!fp.direct_light_sun) return;
  const ShaderProgram& p = frame.prepare(*fp.direct_light_sun);
  p.set_uniform("rgb_from_albedo", rgb_from_albedo);
  std::array<std::array<double, 3>, kLimbCoefficients> limb{};
  std::array<double, 3> mean{};
  for (std::size_t i = 0; i < frame.n; ++i) {
    const atmosphere::LimbDarkening& law = frame.sun_limb[i];
    const double m = law.mean_over_centre();
    for (std::size_t c = 0; c < 3; ++c) {
      const double rgb = exposure * frame.rgb_weights[i][c] * frame.sun_centre[i];
      for (std::size_t k = 0; k < limb.size(); ++k) limb[k][c] += rgb * law.coefficients[k];
      mean[c] += rgb * m;
    }
  }
  const auto to_float = [](const std::array<double, 3>& v) {
    return std::array<float, 3>{static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
  };
  for (std::size_t k = 0; k < limb.size(); ++k) p.set_uniform(fmt::format("sun_rgb_limb[{}]", k), to_float(limb[k]));
  p.set_uniform("sun_rgb_mean", to_float(mean));
}

void draw_direct_tiles(FrameInProgress& frame, const BandTiles& band, PassTimer& timer) {
  const FramePasses& fp = *frame.programs;
  for (const auto& [b, list] : band.one_body_tiles) {
    frame.set_the_body(frame.prepare(*fp.direct_light_one), b);
    fp.direct_light_one->set_uniform("one_body", static_cast<int>(b));
    timer.gpu("direct light", [&] { frame.dispatch_tiles(*fp.direct_light_one, list, kDirectLightTilesPerGroup); });
  }
  if (band.body_tiles.count > 0)
    timer.gpu("direct light",
              [&] { frame.dispatch_tiles(*fp.direct_light, band.body_tiles, kDirectLightTilesPerGroup); });
  if (band.sun_tiles.count > 0)
    timer.gpu("direct light, sun",
              [&] { frame.dispatch_tiles(*fp.direct_light_sun, band.sun_tiles, kDirectLightTilesPerGroup); });
}

void draw_atmosphere_tiles(FrameInProgress& frame, BandResources& resources, const BandTiles& band,
                           const FrameLight& light, PassTimer& timer) {
  // Another light's passes add to the output the sun's wrote (render/night/moon_light.h).
  if (!light.is_sun()) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  draw_one_pass_tiles(frame, resources, band, light, timer);
  if (!light.is_sun() && band.one_pass_atmosphere_tiles > 0) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  draw_gbuffer_tiles(frame, resources, band, light, timer);
}

}  // namespace zenith::render
