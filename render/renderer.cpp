#include "render/renderer.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "core/parallel_for.h"
#include "core/units.h"
#include "atmosphere/model_hash.h"
#include "render/frame/gpu_atmosphere.h"
#include "render/frame/gpu_body.h"
#include "render/frame/pass_timer.h"
#include "render/frame/tile_culling.h"
#include "render/gl/buffer.h"
#include "render/gl/gl_error.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"
#include "render/lut/shader_model.h"
#include "render/shader_bindings.h"
#include "render/shader_programs.h"
#include "scene/albedo_map.h"
#include "scene/sun_disc.h"

namespace zenith::render {
namespace {

using gl::ShaderProgram;
using gl::Texture;
using gl::TextureFormat;
using Vec4 = std::array<float, 4>;

using scene::kMaxBodies;
constexpr std::size_t kLanes = kWavelengthLanes;

// Texture units, storage bindings and image units of the render passes
// (frame.glsl, *.comp), from render/shader_bindings.h.
constexpr unsigned kAlbedoMapUnit = binding::kAlbedoMapsUnit;  // albedo_maps (a 2D array texture)
constexpr unsigned kRayTableUnit = binding::kRayTableUnit;     // projection_ray_table of projection.glsl
using binding::kBodies, binding::kTiles, binding::kFrameRgb;
constexpr unsigned kGbufferHit = binding::kGbufferHitImage, kGbufferAlbedo = binding::kGbufferAlbedoImage,
                   kRadianceSum = binding::kRadianceSumImage, kTransmittance = binding::kTransmittanceProductImage;
constexpr int kMaxSpectrumUniforms = kSunSpectrumSize;  // direct_light.comp's sun_spectrum[]
/// Tiles per work group of direct_light.comp (its local size is 16 × 16 × this,
/// 1024 invocations, the most GL guarantees). Its pixels are cheap, so llvmpipe's
/// cost per work group showed: the no-atmosphere ground view's frame took
/// 7.4–7.6 ms instead of 7.5–8.0 ms with one tile per group (issue 13).
constexpr std::size_t kDirectLightTilesPerGroup = 4;

/// Whether some body's shadow (its penumbra) can fall on another: then the
/// passes are compiled with the eclipse code (frame.glsl's sun_visibility),
/// which a CPU rasterizer would otherwise run for every lit pixel in vain. For
/// an occluder of radius a at o and a receiver of radius b at c: the points
/// that see part of the sun (angular radius α, direction s) behind the
/// occluder lie within a + d tan α (·1.01, and a metre) of the shadow axis
/// through o, at d = (o − p)·s > 0 in front of them; the receiver's nearest
/// point is at least (its centre's distance from the axis) − b from it.
bool eclipses_possible(const scene::Scene& scene) {
  const glm::dvec3 s = glm::normalize(scene.sun.direction);
  const double tan_alpha = std::tan(std::min(scene.sun.angular_radius_rad, 1.0));
  for (const scene::Body& occluder : scene.bodies)
    for (const scene::Body& receiver : scene.bodies) {
      if (&occluder == &receiver) continue;
      const glm::dvec3 oc = occluder.position_m - receiver.position_m;
      const double d = glm::dot(oc, s) + receiver.radius_m;  // largest d over the receiver
      if (d <= 0.0) continue;  // the occluder is behind the receiver, away from the sun
      const double off_axis = glm::length(oc - glm::dot(oc, s) * s) - receiver.radius_m;
      if (off_axis < 1.01 * (occluder.radius_m + d * tan_alpha) + 1.0) return true;
    }
  return false;
}

/// Whether every albedo lookup of the frame is at level 0 of the maps
/// (surface_albedo.glsl: lod = max(0, log2(footprint / texel))): a pixel's
/// footprint on a body is at most pixel angle × distance / 0.05 (the clamp of
/// the incidence cosine), and nothing of a sphere seen from outside lies
/// farther than its horizon, √(D² − R²). Then the passes sample level 0 with a
/// constant level (ALBEDO_LOD0): the same texels, without the per-pixel mip
/// selection a CPU rasterizer pays for.
bool albedo_at_full_resolution(const scene::Scene& scene, double pixel_angle, int map_width) {
  for (const scene::Body& body : scene.bodies) {
    const double D = glm::length(body.position_m - scene.camera.position_m), R = body.radius_m;
    const double farthest = std::sqrt(std::max((D - R) * (D + R), 0.0));
    const double texel = 2.0 * core::kPi * R / std::max(map_width, 1);
    if (20.0 * pixel_angle * farthest > 0.99 * texel) return false;
  }
  return true;
}

/// Where the sky-view table is as good as the 4D lookups per pixel, for a
/// camera at radius r inside the shell [RB, RT] with the sun's cosine μs
/// (measured with render_bench --sky-view-error on horizon views, 1280×720 with
/// 10° and 79° fields, paper tables; docs/rendering-performance.md): low in the
/// atmosphere (up to 2 % of its thickness: 2 km on Earth) always; up to 20 %
/// while the sun is above the camera's horizon. Higher, and in twilight above
/// the lowest layer, the light at the horizon changes within hundredths of a
/// degree (the limb, the Earth's shadow) and 64 zenith texels a half would
/// differ by up to 25 % there: the 4D lookups stay, as from space.
bool sky_view_accurate(double r, double ground_radius, double top_radius, double mu_s) {
  const double height = (r - ground_radius) / (top_radius - ground_radius);
  const double mu_horizon = -std::sqrt(std::max(0.0, 1.0 - (ground_radius / r) * (ground_radius / r)));
  return height <= 0.02 || (height <= 0.2 && mu_s > mu_horizon);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Vec4 vec4_of(const glm::dvec3& v, double w) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z), static_cast<float>(w)};
}

/// Lanes 4g..4g+3 of per-wavelength values (missing lanes 0).
Vec4 lanes(const std::vector<double>& values, std::size_t group) {
  Vec4 out{0, 0, 0, 0};
  for (std::size_t k = 0; k < kLanes && group * kLanes + k < values.size(); ++k)
    out[k] = static_cast<float>(values[group * kLanes + k]);
  return out;
}

/// Column `channel` of per-wavelength RGB weights, lanes of group g.
Vec4 lanes(const std::vector<std::array<double, 3>>& weights, std::size_t channel, std::size_t group) {
  Vec4 out{0, 0, 0, 0};
  for (std::size_t k = 0; k < kLanes && group * kLanes + k < weights.size(); ++k)
    out[k] = static_cast<float>(weights[group * kLanes + k][channel]);
  return out;
}

/// A key identifying an albedo source (same key, same texture).
std::string albedo_key(const scene::AlbedoSource& a) {
  std::ostringstream key;
  switch (a.kind) {
    case scene::AlbedoSource::Kind::constant:
      key << "constant " << a.colour_linear_rgb.r << ' ' << a.colour_linear_rgb.g << ' ' << a.colour_linear_rgb.b;
      break;
    case scene::AlbedoSource::Kind::image: key << "image " << a.image_path.string(); break;
    case scene::AlbedoSource::Kind::procedural:
      key << "procedural " << a.procedural << ' ' << a.seed << ' ' << a.width_px << 'x' << a.height_px;
      break;
  }
  return key.str();
}

/// Work groups for `count` tiles: a 2D grid (x ≤ 65535), the shader folds it back.
std::array<unsigned, 2> tile_groups(std::size_t count) {
  const std::size_t x = std::min<std::size_t>(count, 65535);
  return {static_cast<unsigned>(x), static_cast<unsigned>((count + x - 1) / x)};
}

}  // namespace

struct Renderer::Impl {
  /// The frame passes, compiled for one projection kind (PROJECTION_KIND of
  /// shaders/projection.glsl) on first use.
  struct FramePasses {
    ShaderProgram gbuffer, resolve;
    // Tiles no atmosphere touches: bodies (one body: ONE_BODY = 1; several), and the sun's tiles (SUN = 1).
    ShaderProgram direct_light_one, direct_light, direct_light_sun;
  };
  std::map<std::string, FramePasses> frame_passes;  // by FrameVariant::key
  std::vector<gl::ShaderDefine> sun_defines;  // SUN_DISC, LIMB_DARKENING (resolve.comp, atmosphere_tile.comp)
  bool sun_disc = true, limb_darkening = true;

  const FramePasses& passes_for(const FrameVariant& frame) {
    auto it = frame_passes.find(frame.key());
    if (it != frame_passes.end()) return it->second;
    const std::vector<gl::ShaderDefine> frame_defines = frame.defines();
    std::vector<gl::ShaderDefine> resolve_defines = sun_defines;
    resolve_defines.insert(resolve_defines.end(), frame_defines.begin(), frame_defines.end());
    auto direct_defines = [&](bool sun, bool one_body) {
      std::vector<gl::ShaderDefine> d = {{"SUN", sun ? "1" : "0"},
                                         {"ONE_BODY", one_body ? "1" : "0"},
                                         {"LIMB_DARKENING", limb_darkening ? "1" : "0"},
                                         {"TILES_PER_GROUP", std::to_string(kDirectLightTilesPerGroup)}};
      d.insert(d.end(), frame_defines.begin(), frame_defines.end());
      return d;
    };
    FramePasses p;
    FrameVariant no_eclipses = frame;  // the G-buffer pass shades nothing
    no_eclipses.eclipses = false;
    const std::vector<gl::ShaderDefine> gbuffer_defines = no_eclipses.defines();
    p.gbuffer = load_compute_program("render/gbuffer.comp", gbuffer_defines);
    p.resolve = load_compute_program("render/resolve.comp", resolve_defines);
    p.direct_light_one = load_compute_program("render/direct_light.comp", direct_defines(false, true));
    p.direct_light = load_compute_program("render/direct_light.comp", direct_defines(false, false));
    if (sun_disc)
      p.direct_light_sun = load_compute_program("render/direct_light.comp", direct_defines(true, false));
    return frame_passes.emplace(frame.key(), std::move(p)).first->second;
  }
  std::map<std::string, std::unique_ptr<GpuAtmosphere>> atmospheres;  // by table hash + features
  std::map<std::string, image::LinearImage> albedo_images;           // by albedo_key
  std::string albedo_array_key;
  Texture albedo_array;  // one layer per body, all at the largest map's size

  /// The bodies' maps as the layers of one array texture (rebuilt when the list
  /// changes): each resampled bilinearly, wrapping in longitude, to the largest
  /// width and height among them.
  void ensure_albedo_array(const std::vector<std::string>& keys) {
    std::string joined;
    for (const std::string& k : keys) joined += k + '\n';
    if (joined == albedo_array_key && albedo_array.id() != 0) return;
    int width = 1, height = 1;
    for (const std::string& k : keys) {
      width = std::max(width, albedo_images.at(k).width);
      height = std::max(height, albedo_images.at(k).height);
    }
    const std::size_t layer_floats = static_cast<std::size_t>(width) * height * 4;
    std::vector<float> rgba(std::max<std::size_t>(keys.size(), 1) * layer_floats, 1.0f);
    for (std::size_t layer = 0; layer < keys.size(); ++layer) {
      const image::LinearImage& m = albedo_images.at(keys[layer]);
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          // Texel centres map to texel centres; x wraps (longitude), y clamps (poles).
          const double sx = (x + 0.5) * m.width / width - 0.5, sy = (y + 0.5) * m.height / height - 0.5;
          const double fx = std::floor(sx), fy = std::floor(sy);
          const double tx = sx - fx, ty = sy - fy;
          auto at = [&](int xi, int yi, int k) {
            xi = ((xi % m.width) + m.width) % m.width;
            yi = std::clamp(yi, 0, m.height - 1);
            return static_cast<double>(m.rgb[(static_cast<std::size_t>(yi) * m.width + xi) * 3 + k]);
          };
          const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
          float* out = &rgba[layer * layer_floats + (static_cast<std::size_t>(y) * width + x) * 4];
          for (int k = 0; k < 3; ++k)
            out[k] = static_cast<float>((1 - ty) * ((1 - tx) * at(x0, y0, k) + tx * at(x0 + 1, y0, k)) +
                                        ty * ((1 - tx) * at(x0, y0 + 1, k) + tx * at(x0 + 1, y0 + 1, k)));
        }
    }
    albedo_array = Texture::create_2d_array_mipmapped(TextureFormat::rgba16f, width, height,
                                                      static_cast<int>(std::max<std::size_t>(keys.size(), 1)), rgba);
    albedo_array.set_repeat_s(true);
    albedo_array_key = joined;
  }
  std::string projection_key;
  std::unique_ptr<TileCones> cones;
  gl::Buffer bodies;
  gl::Buffer tiles;
  // Ray tables of projections without a GPU form, per band (keyed with the projection).
  std::map<int, std::vector<float>> ray_tables;  // by first row
  Texture ray_table;
  std::size_t tiles_capacity = 0;
  // Band images, (re)allocated when the band size changes; the output is a
  // buffer of one vec4 per pixel, mapped and packed into the rows (frame_rgb.glsl).
  int band_width = 0, band_height = 0;
  Texture gbuffer_hit, gbuffer_albedo, radiance_sum, transmittance;
  gl::Buffer frame_rgb;

  void ensure_band_images(int width, int height) {
    if (width == band_width && height == band_height) return;
    gbuffer_hit = Texture::create_2d(TextureFormat::rgba32f, width, height);
    gbuffer_albedo = Texture::create_2d(TextureFormat::rgba16f, width, height);
    radiance_sum = Texture::create_2d(TextureFormat::rgba32f, width, height);
    transmittance = Texture::create_2d(TextureFormat::rgba32f, width, height);
    frame_rgb = gl::Buffer::mappable(static_cast<std::size_t>(width) * height * 4 * sizeof(float));
    band_width = width;
    band_height = height;
  }

  void ensure_tiles_buffer(std::size_t count) {
    if (count <= tiles_capacity && tiles.id() != 0) return;
    tiles_capacity = std::max<std::size_t>(count, 1024);
    tiles = gl::Buffer(tiles_capacity * sizeof(std::uint32_t));
  }
};

Renderer::Renderer(const RenderOptions& options, TableSource tables)
    : options_(options), table_source_(std::move(tables)), impl_(std::make_unique<Impl>()) {
  if (options_.max_band_pixels < std::size_t{kTileSize} * kTileSize)
    throw std::invalid_argument("RenderOptions::max_band_pixels must be at least 256");
  impl_->sun_defines = {{"SUN_DISC", options_.sun_disc ? "1" : "0"},
                        {"LIMB_DARKENING", options_.limb_darkening ? "1" : "0"}};
  impl_->sun_disc = options_.sun_disc;
  impl_->limb_darkening = options_.limb_darkening;
}

Renderer::~Renderer() = default;

std::vector<float> Renderer::render_image(const scene::Scene& scene, const warp::Projection& projection) {
  std::vector<float> image(static_cast<std::size_t>(projection.width()) * projection.height() * 3);
  render(scene, projection, [&](int first_row, int rows, std::span<const float> rgb) {
    std::copy(rgb.begin(), rgb.begin() + static_cast<std::ptrdiff_t>(rows) * projection.width() * 3,
              image.begin() + static_cast<std::ptrdiff_t>(first_row) * projection.width() * 3);
  });
  return image;
}

namespace {

/// One atmosphere the frame draws: its body, where its shell is from the
/// camera, its tables on the GPU and, per band, the tiles it draws.
struct AtmospherePass {
  int body = 0;
  double distance_m = 0.0, top_radius_m = 0.0, power_m2 = 0.0;
  glm::dvec3 direction_camera{0.0};
  GpuAtmosphere* gpu = nullptr;
  bool sky_view = false;  // the camera is inside: the sky-view variant where it can
  // The band's tiles the shell can touch (shell_tiles); of those, the tiles
  // no other shell touches, drawn in one pass (atmosphere_tile.comp) by
  // variant (GpuAtmosphere::TileVariant::key), and the others, which go
  // through the G-buffer path.
  std::vector<std::uint32_t> shell_tiles, gbuffer_tiles;
  std::map<int, std::pair<GpuAtmosphere::TileVariant, std::vector<std::uint32_t>>> one_pass;
};

/// A run of the band's tile buffer: `count` tiles from `offset`.
struct TileList {
  std::size_t offset = 0, count = 0;
};

}  // namespace

/// One frame in progress: its constants in double on the CPU, the bodies and
/// atmosphere passes, the uniforms every pass shares, the programs, and which
/// programs have their frame and band uniforms set.
struct Renderer::Frame {
  Frame(const ::zenith::scene::Scene& s, const warp::Projection& p) : scene(s), projection(p) {}

  const ::zenith::scene::Scene& scene;
  const warp::Projection& projection;
  std::size_t n = 0;       // wavelengths
  std::size_t groups = 0;  // groups of kLanes wavelengths

  // ---- per-frame constants (frame_constants)
  glm::dmat3 camera_to_world{1.0}, world_to_camera{1.0};
  glm::dvec3 sun{0.0}, sun_camera{0.0};
  double sun_radius = 0.0, pixel_angle = 0.0, sun_pixel_angle = 0.0, sun_point_sigma = 0.0;
  std::vector<std::array<double, 3>> rgb_weights, albedo_weights;
  std::vector<double> sun_centre, limb_exponent;

  // ---- the projection's tile cones (update_tile_cones)
  const TileCones* cones = nullptr;
  std::size_t tiles_total = 0;

  // ---- bodies and atmospheres (prepare_bodies)
  std::vector<GpuBody> bodies;
  std::vector<AtmospherePass> passes;

  // ---- uniforms shared by all passes and the programs (prepare_programs)
  std::array<float, 9> camera_matrix{};
  warp::GpuProjection gpu_projection;
  std::array<std::array<float, 3>, 3> world_ray{};
  FrameVariant variant;
  const Impl::FramePasses* programs = nullptr;
  double sun_reach = 0.0;  // where the sun can be drawn (set_direct_light_uniforms)

  // Frame uniforms on first use in the frame, band uniforms on first use in the band.
  std::set<const ShaderProgram*> frame_ready, band_ready;
  std::array<int, 2> band_origin{0, 0}, band_size{0, 0};

  /// frame.glsl's the_body: body b's data as plain uniforms of a pass about it.
  void set_the_body(const ShaderProgram& p, std::size_t b) const {
    const GpuBody& g = bodies[b];
    p.set_uniform("the_body.centre", g.centre);
    p.set_uniform("the_body.shape", g.shape);
    p.set_uniform("the_body.albedo_map", g.albedo_map);
    p.set_uniform("the_body.world_to_body0", g.world_to_body[0]);
    p.set_uniform("the_body.world_to_body1", g.world_to_body[1]);
    p.set_uniform("the_body.world_to_body2", g.world_to_body[2]);
  }

  /// The uniforms every pass of the frame shares: bodies, camera, sun, projection.
  void set_frame_uniforms(const ShaderProgram& p) const {
    p.set_uniform("body_count", static_cast<int>(scene.bodies.size()));
    p.set_uniform("camera_to_world", camera_matrix);
    p.set_uniform("sun_direction", std::array<float, 3>{static_cast<float>(sun.x), static_cast<float>(sun.y),
                                                        static_cast<float>(sun.z)});
    p.set_uniform("sun_angular_radius", static_cast<float>(sun_radius));
    p.set_uniform("pixel_angle", static_cast<float>(pixel_angle));
    p.set_uniform("projection_kind", static_cast<int>(gpu_projection.kind));
    for (int k = 0; k < 4; ++k)
      p.set_uniform(fmt::format("projection_params[{}]", k), gpu_projection.params[static_cast<std::size_t>(k)]);
    p.set_uniform("sun_draw_radius", static_cast<float>(sun_radius));
    p.set_uniform("sun_pixel_angle", static_cast<float>(sun_pixel_angle));
    p.set_uniform("sun_point_sigma", static_cast<float>(sun_point_sigma));
    for (const auto& [name, k] : {std::pair{"world_ray_x", 0}, std::pair{"world_ray_y", 1}, std::pair{"world_ray_centre", 2}})
      p.set_uniform(name, world_ray[static_cast<std::size_t>(k)]);
  }

  /// `p` with its frame uniforms (and exposure) set on its first use in the
  /// frame and its band uniforms on its first use in the band.
  const ShaderProgram& prepare(const ShaderProgram& p) {
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

  /// Dispatches `p` over the tiles of `list` (prepared first).
  /// One work group per `tiles_per_group` tiles of `list` (the pass's TILES_PER_GROUP).
  void dispatch_tiles(const ShaderProgram& p, TileList list, std::size_t tiles_per_group = 1) {
    prepare(p);
    p.set_uniform("tile_offset", static_cast<int>(list.offset));
    p.set_uniform("tile_count", static_cast<int>(list.count));
    const auto grid = tile_groups((list.count + tiles_per_group - 1) / tiles_per_group);
    p.dispatch(grid[0], grid[1]);
  }

  /// Per-group uniforms of the passes that turn a group's radiance into colour.
  void set_group_uniforms(const ShaderProgram& p, std::size_t g) {
    prepare(p);
    p.set_uniform("first_group", g == 0 ? 1 : 0);
    p.set_uniform("last_group", g + 1 == groups ? 1 : 0);
    p.set_uniform("sun_irradiance", lanes(scene.sun.irradiance_W_m2_nm, g));
    p.set_uniform("sun_centre_radiance", lanes(sun_centre, g));
    p.set_uniform("limb_exponent", lanes(limb_exponent, g));
    p.set_uniform("albedo_from_r", lanes(albedo_weights, 0, g));
    p.set_uniform("albedo_from_g", lanes(albedo_weights, 1, g));
    p.set_uniform("albedo_from_b", lanes(albedo_weights, 2, g));
    p.set_uniform("rgb_from_lanes_r", lanes(rgb_weights, 0, g));
    p.set_uniform("rgb_from_lanes_g", lanes(rgb_weights, 1, g));
    p.set_uniform("rgb_from_lanes_b", lanes(rgb_weights, 2, g));
  }

  /// Whether an atmosphere's shell can touch any tile of the view.
  bool touches_view(const AtmospherePass& pass) const {
    return !cones->tiles_touching_sphere(pass.direction_camera, pass.distance_m, pass.top_radius_m, 0,
                                         projection.height())
                .empty();
  }

  /// Bodies that reach into a shell: their tiles need the direct path's aerial
  /// perspective (the sky-view variant has none).
  std::vector<std::size_t> bodies_inside_shell(const AtmospherePass& pass) const {
    std::vector<std::size_t> inside;
    const glm::dvec3 centre = scene.bodies[static_cast<std::size_t>(pass.body)].position_m;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
      if (static_cast<int>(b) != pass.body &&
          glm::length(scene.bodies[b].position_m - centre) - scene.bodies[b].radius_m < pass.top_radius_m)
        inside.push_back(b);
    return inside;
  }
};

/// A band's tiles sorted by how they are drawn (classify_band_tiles): the
/// lists, one after the other in one buffer, and the counts.
struct Renderer::BandTiles {
  int first_row = 0, rows = 0, tile_rows = 0;
  std::size_t tiles = 0;                 // tiles of the band
  std::vector<std::uint8_t> shells;      // shells that can touch the tile (saturating at 2)
  std::vector<std::uint8_t> black;       // nothing is dispatched for the tile
  std::vector<std::uint32_t> all_tiles;  // every list below, one after the other
  struct PassLists {
    std::vector<std::pair<GpuAtmosphere::TileVariant, TileList>> one_pass;
    TileList gbuffer;
  };
  std::vector<PassLists> lists;  // per atmosphere pass
  std::size_t one_pass_atmosphere_tiles = 0;
  TileList gbuffer_tiles;        // tiles of the G-buffer path
  std::vector<std::pair<std::size_t, TileList>> one_body_tiles;  // tiles only body b can be in
  std::size_t one_body_count = 0;
  TileList body_tiles, sun_tiles;  // tiles with several bodies; tiles with the sun only
};

void Renderer::render(const scene::Scene& scene, const warp::Projection& projection, const RowSink& sink) {
  const auto start = std::chrono::steady_clock::now();
  stats_ = FrameStats{};
  PassTimer timer(options_.time_passes);
  gl::check_gl_error("Renderer::render: an earlier GL call left an error");

  check_scene(scene);
  Frame frame = frame_constants(scene, projection);
  update_tile_cones(frame);
  prepare_bodies(frame);
  make_tables_resident(frame);
  fill_sky_view_tables(frame, timer);
  prepare_programs(frame);
  set_direct_light_uniforms(frame);
  render_bands(frame, sink, timer);
  stats_.pass_ms = timer.milliseconds();
  stats_.seconds = seconds_since(start);
}

void Renderer::check_scene(const scene::Scene& scene) const {
  const std::size_t n = scene.wavelengths_nm.size();
  if (n == 0) throw std::invalid_argument("scene '" + scene.name + "' has no working wavelengths");
  if (scene.bodies.size() > kMaxBodies)
    throw std::invalid_argument(fmt::format("scene '{}' has {} bodies; the renderer draws at most {}", scene.name,
                                            scene.bodies.size(), kMaxBodies));
  if (scene.sun.irradiance_W_m2_nm.size() != n)
    throw std::invalid_argument(fmt::format("scene '{}': the sun has {} irradiance values for {} wavelengths",
                                            scene.name, scene.sun.irradiance_W_m2_nm.size(), n));
}

Renderer::Frame Renderer::frame_constants(const scene::Scene& scene, const warp::Projection& projection) const {
  Frame f(scene, projection);
  f.n = scene.wavelengths_nm.size();
  f.groups = (f.n + kLanes - 1) / kLanes;
  f.camera_to_world = glm::mat3_cast(glm::normalize(scene.camera.orientation));
  f.world_to_camera = glm::transpose(f.camera_to_world);
  f.sun = glm::normalize(scene.sun.direction);
  f.sun_radius = scene.sun.angular_radius_rad;
  // The worst-case footprint over the image bounds culling and decides
  // ALBEDO_LOD0 (the shaders take each pixel's own footprint for the level of
  // detail, frame.glsl); the sun is sized from the footprint where it lands (a
  // warp mesh's worst case can be tens of times the local one: issue 14).
  f.pixel_angle = projection.max_pixel_angle_rad();
  f.sun_camera = f.world_to_camera * f.sun;
  f.sun_pixel_angle = projection.pixel_angle_rad_at(f.sun_camera);

  f.rgb_weights = image::spectral_to_rgb_weights(scene.wavelengths_nm, options_.colour);
  f.albedo_weights = image::rgb_to_spectral_weights(scene.wavelengths_nm, options_.colour);
  // A sun resolved by the pixels is drawn as its limb-darkened disc; one
  // under 1.5 pixels in radius as a Gaussian of σ = 0.7 pixel carrying the
  // same irradiance (exp(−θ²/2σ²) E / 2πσ²): a disc sampled at pixel centres
  // would flicker and lose or gain light with its sub-pixel position.
  f.sun_point_sigma = f.sun_radius < 1.5 * f.sun_pixel_angle ? 0.7 * f.sun_pixel_angle : 0.0;
  f.sun_centre.resize(f.n);
  f.limb_exponent.resize(f.n);
  for (std::size_t i = 0; i < f.n; ++i) {
    const double e = scene.sun.irradiance_W_m2_nm[i];
    if (f.sun_point_sigma > 0.0)
      f.sun_centre[i] = e / (2.0 * core::kPi * f.sun_point_sigma * f.sun_point_sigma);
    else
      f.sun_centre[i] = options_.limb_darkening
                            ? scene::disc_centre_radiance(e, f.sun_radius, scene.wavelengths_nm[i])
                            : scene::uniform_disc_radiance(e, f.sun_radius);
    f.limb_exponent[i] = scene::limb_darkening_exponent(scene.wavelengths_nm[i]);
  }
  return f;
}

void Renderer::update_tile_cones(Frame& frame) {
  Impl& im = *impl_;
  const warp::Projection& projection = frame.projection;
  const warp::GpuProjection g = projection.gpu();
  std::ostringstream key;
  key << projection.describe() << ' ' << projection.width() << 'x' << projection.height() << ' '
      << static_cast<int>(g.kind);
  for (const auto& v : g.params)
    for (float f : v) key << ' ' << f;
  if (key.str() != im.projection_key || !im.cones) {
    im.cones = std::make_unique<TileCones>(projection);
    im.projection_key = key.str();
    im.ray_tables.clear();
  }
  frame.cones = im.cones.get();
  frame.tiles_total = static_cast<std::size_t>(frame.cones->columns()) * frame.cones->rows();
}

void Renderer::prepare_bodies(Frame& frame) {
  Impl& im = *impl_;
  const scene::Scene& scene = frame.scene;
  std::vector<GpuBody>& bodies = frame.bodies;
  std::vector<AtmospherePass>& passes = frame.passes;
  bodies.resize(scene.bodies.size());
  std::vector<std::string> albedo_layers;  // body b's map is layer b
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const scene::Body& body = scene.bodies[b];
    const glm::dvec3 c = body.position_m - scene.camera.position_m;
    const double D = glm::length(c);
    const glm::dvec3 dir = c / D;
    const double R = body.radius_m;
    const glm::dmat3 world_to_body = glm::transpose(glm::mat3_cast(glm::normalize(body.orientation)));
    GpuBody& g = bodies[b];
    g.centre = vec4_of(dir, D);
    g.shape = {static_cast<float>(R), static_cast<float>((D - R) * (D + R)), -1.0f, static_cast<float>(b)};
    for (int row = 0; row < 3; ++row)
      g.world_to_body[row] = vec4_of(glm::dvec3(world_to_body[0][row], world_to_body[1][row], world_to_body[2][row]), 0.0);

    const std::string key = albedo_key(body.albedo);
    if (!im.albedo_images.contains(key)) im.albedo_images.emplace(key, scene::load_albedo_map(body.albedo));
    albedo_layers.push_back(key);

    if (!body.atmosphere || !options_.atmospheres) continue;
    const atmosphere::AtmosphereModel& model = body.atmosphere->loaded.model;
    if (model.wavelengths_nm != scene.wavelengths_nm)
      throw std::invalid_argument(fmt::format("scene '{}': the atmosphere of '{}' is resolved at other wavelengths "
                                              "than the scene's",
                                              scene.name, body.name));
    AtmospherePass pass;
    pass.body = static_cast<int>(b);
    pass.distance_m = D;
    pass.top_radius_m = model.top_radius_m;
    pass.power_m2 = (D - model.top_radius_m) * (D + model.top_radius_m);
    pass.direction_camera = frame.world_to_camera * dir;
    g.shape[2] = static_cast<float>(passes.size());
    passes.push_back(std::move(pass));
  }
  // Front to back: for disjoint shells the camera's power with respect to each
  // sphere (D² − R²) orders them along every ray (the radical plane separates them).
  std::sort(passes.begin(), passes.end(),
            [](const AtmospherePass& a, const AtmospherePass& b) { return a.power_m2 < b.power_m2; });
  for (AtmospherePass& pass : passes) {
    FrameStats::Atmosphere s;
    s.body = scene.bodies[static_cast<std::size_t>(pass.body)].name;
    s.tiles_total = frame.tiles_total;
    stats_.atmospheres.push_back(s);
  }
  im.ensure_albedo_array(albedo_layers);
  for (GpuBody& g : bodies) g.albedo_map = {static_cast<float>(im.albedo_array.width()), 0, 0, 0};
  im.albedo_array.bind(kAlbedoMapUnit);
  im.bodies = gl::Buffer::from(std::span<const GpuBody>(bodies.empty() ? std::vector<GpuBody>(1) : bodies));
}

void Renderer::make_tables_resident(Frame& frame) {
  Impl& im = *impl_;
  const scene::Scene& scene = frame.scene;
  for (AtmospherePass& pass : frame.passes) {
    if (!frame.touches_view(pass)) continue;  // an atmosphere outside the view costs nothing
    const atmosphere::AtmosphereModel& model = scene.bodies[static_cast<std::size_t>(pass.body)].atmosphere->loaded.model;
    const std::string key = fmt::format("{} mult={} ecl={} fp64={}", atmosphere::lookup_table_hash(model),
                                        options_.atmosphere.multiple_scattering, options_.atmosphere.eclipses,
                                        options_.atmosphere.fp64);
    auto it = im.atmospheres.find(key);
    if (it == im.atmospheres.end()) {
      ++stats_.table_sets_requested;
      const atmosphere::lut::LookupTables tables = table_source_(model);
      it = im.atmospheres.emplace(key, std::make_unique<GpuAtmosphere>(model, tables, options_.atmosphere,
                                                                        im.sun_defines))
               .first;
      ++stats_.table_sets_uploaded;
      spdlog::debug("renderer: atmosphere of '{}' resident ({:.1f} MB of tables)",
                    scene.bodies[static_cast<std::size_t>(pass.body)].name, static_cast<double>(it->second->table_bytes()) / 1e6);
    }
    pass.gpu = it->second.get();
  }
}

void Renderer::fill_sky_view_tables(Frame& frame, PassTimer& timer) {
  const scene::Scene& scene = frame.scene;
  std::vector<const GpuAtmosphere*> sky_view_filled;
  for (AtmospherePass& pass : frame.passes) {
    if (!pass.gpu || options_.sky_view_table == SkyViewTableUse::off || pass.power_m2 > 0.0) continue;
    if (std::find(sky_view_filled.begin(), sky_view_filled.end(), pass.gpu) != sky_view_filled.end()) continue;
    const scene::Body& planet = scene.bodies[static_cast<std::size_t>(pass.body)];
    const glm::dvec3 up = glm::normalize(scene.camera.position_m - planet.position_m);
    if (!sky_view_accurate(pass.distance_m, pass.gpu->ground_radius_m(), pass.top_radius_m, glm::dot(up, frame.sun)))
      continue;
    timer.gpu("sky-view table",
              [&] { pass.gpu->fill_sky_view(pass.distance_m, glm::dot(up, frame.sun), frame.sun_radius); });
    pass.sky_view = true;
    sky_view_filled.push_back(pass.gpu);
  }
}

void Renderer::prepare_programs(Frame& frame) {
  Impl& im = *impl_;
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row)
      frame.camera_matrix[col * 3 + row] = static_cast<float>(frame.camera_to_world[col][row]);
  frame.gpu_projection = frame.projection.gpu();
  // Planar and cube-face projections: their affine ray's vectors in the world frame (frame.glsl).
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& v = frame.gpu_projection.params[k];
    const glm::dvec3 w = frame.camera_to_world * glm::dvec3(v[0], v[1], v[2]);
    frame.world_ray[k] = {static_cast<float>(w.x), static_cast<float>(w.y), static_cast<float>(w.z)};
  }
  // Programs are compiled per projection kind, and with the eclipse code only
  // when another body can cast a shadow (a CPU rasterizer runs all of it).
  frame.variant.projection_kind = static_cast<int>(frame.gpu_projection.kind);
  frame.variant.eclipses = options_.atmosphere.eclipses && eclipses_possible(frame.scene);
  frame.variant.albedo_lod0 = albedo_at_full_resolution(frame.scene, frame.pixel_angle, im.albedo_array.width());
  frame.programs = &im.passes_for(frame.variant);
}

void Renderer::set_direct_light_uniforms(Frame& frame) {
  // direct_light.comp: every wavelength at once. A body lit by the sun alone
  // is rgb = (cos i V / π) M a with M = exposure Σ_λ w(λ) E(λ) f(λ)ᵀ (w: the
  // spectral → RGB weights, f: the albedo's RGB → reflectance weights); the
  // sun's disc rgb = Σ_λ exposure w(λ) I_centre(λ) μ^α(λ) × coverage.
  const scene::Scene& scene = frame.scene;
  const Impl::FramePasses& fp = *frame.programs;
  const double exposure = scene.camera.exposure;
  std::array<float, 9> rgb_from_albedo{};  // column-major: column = albedo channel
  for (int out = 0; out < 3; ++out)
    for (int in = 0; in < 3; ++in) {
      double m = 0.0;
      for (std::size_t i = 0; i < frame.n; ++i)
        m += frame.rgb_weights[i][static_cast<std::size_t>(out)] * scene.sun.irradiance_W_m2_nm[i] *
             frame.albedo_weights[i][static_cast<std::size_t>(in)];
      rgb_from_albedo[static_cast<std::size_t>(in * 3 + out)] = static_cast<float>(exposure * m);
    }
  frame.prepare(fp.direct_light).set_uniform("rgb_from_albedo", rgb_from_albedo);
  frame.prepare(fp.direct_light_one).set_uniform("rgb_from_albedo", rgb_from_albedo);
  if (fp.direct_light_sun.id() != 0) {
    const ShaderProgram& p = frame.prepare(fp.direct_light_sun);
    p.set_uniform("rgb_from_albedo", rgb_from_albedo);
    p.set_uniform("wavelength_count", static_cast<int>(std::min<std::size_t>(frame.n, kMaxSpectrumUniforms)));
    for (std::size_t i = 0; i < frame.n && i < static_cast<std::size_t>(kMaxSpectrumUniforms); ++i) {
      const double c = exposure * frame.sun_centre[i];
      p.set_uniform(fmt::format("sun_spectrum[{}]", i),
                    std::array<float, 4>{static_cast<float>(frame.rgb_weights[i][0] * c),
                                         static_cast<float>(frame.rgb_weights[i][1] * c),
                                         static_cast<float>(frame.rgb_weights[i][2] * c),
                                         static_cast<float>(frame.sun_point_sigma > 0.0 ? 0.0 : frame.limb_exponent[i])});
    }
  }
  // Where the sun can be drawn: a cone of the disc's radius plus a pixel (or 6σ of the Gaussian).
  frame.sun_reach = std::min(core::kPi / 2, frame.sun_point_sigma > 0.0 ? 6.0 * frame.sun_point_sigma
                                                                       : frame.sun_radius + frame.sun_pixel_angle);
}

void Renderer::render_bands(Frame& frame, const RowSink& sink, PassTimer& timer) {
  Impl& im = *impl_;
  const int width = frame.projection.width(), height = frame.projection.height();
  const std::size_t rows_fit = std::max<std::size_t>(1, options_.max_band_pixels / static_cast<std::size_t>(width));
  const int band_rows = static_cast<int>(std::max<std::size_t>(
      kTileSize, std::min<std::size_t>(static_cast<std::size_t>(height + kTileSize - 1) / kTileSize * kTileSize,
                                       rows_fit / kTileSize * kTileSize)));
  im.ensure_band_images(width, std::min(band_rows, (height + kTileSize - 1) / kTileSize * kTileSize));
  im.bodies.bind_storage(kBodies);
  std::vector<float> rows_rgb;

  for (int first_row = 0; first_row < height; first_row += band_rows) {
    const int rows = std::min(band_rows, height - first_row);
    ++stats_.bands;
    frame.band_origin = {0, first_row};
    frame.band_size = {width, rows};
    frame.band_ready.clear();

    if (frame.gpu_projection.kind == warp::ProjectionKind::ray_table) upload_ray_table(frame, first_row, rows);
    const BandTiles band = classify_band_tiles(frame, first_row, rows);
    upload_tile_lists(band);
    draw_direct_tiles(frame, band, timer);
    draw_one_pass_tiles(frame, band, timer);
    draw_gbuffer_tiles(frame, band, timer);
    read_back_band(frame, band, rows_rgb, timer);
    gl::check_gl_error(fmt::format("rendering rows {}–{} of '{}'", first_row, first_row + rows - 1, frame.scene.name));
    timer.cpu("sink", [&] { sink(first_row, rows, rows_rgb); });
  }
}

void Renderer::upload_ray_table(const Frame& frame, int first_row, int rows) {
  // Rays of this band on the CPU, in double, kept for the next frames.
  Impl& im = *impl_;
  const warp::Projection& projection = frame.projection;
  const int width = projection.width();
  auto table = im.ray_tables.find(first_row);
  if (table == im.ray_tables.end()) {
    std::vector<float> rays(static_cast<std::size_t>(width) * im.band_height * 4, 0.0f);
    core::parallel_for(static_cast<std::size_t>(rows), 0, [&](std::size_t row) {
      for (int x = 0; x < width; ++x) {
        const auto r = projection.ray(x + 0.5, first_row + static_cast<double>(row) + 0.5);
        if (!r) continue;
        const glm::dvec3 d = glm::normalize(*r);
        float* t = &rays[(row * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4];
        t[0] = static_cast<float>(d.x);
        t[1] = static_cast<float>(d.y);
        t[2] = static_cast<float>(d.z);
        t[3] = 1.0f;
      }
    });
    table = im.ray_tables.emplace(first_row, std::move(rays)).first;
  }
  if (im.ray_table.width() != width || im.ray_table.height() != im.band_height)
    im.ray_table = Texture::create_2d(TextureFormat::rgba32f, width, im.band_height);
  im.ray_table.upload(table->second);
  im.ray_table.bind(kRayTableUnit);
}

Renderer::BandTiles Renderer::classify_band_tiles(Frame& frame, int first_row, int rows) {
  // The band's tiles (render/frame/tile_culling.h):
  //   exactly one atmosphere's shell can touch it: one pass for that
  //     atmosphere (atmosphere_tile.comp), from its sky-view table when the
  //     camera is inside the shell and no other body inside the shell can be
  //     in the tile, else from the 4D tables; compiled for what the tile can
  //     hold (the planet's ground: none, all or some of it; other bodies;
  //     the sun), since llvmpipe runs every branch a program has;
  //   two or more: the G-buffer path (gbuffer.comp, the atmospheres front to
  //     back, resolve.comp), which composites them;
  //   none, but a body or the sun can be in it: direct_light.comp, one pass;
  //   nothing: black (not dispatched).
  const scene::Scene& scene = frame.scene;
  const TileCones& cones = *frame.cones;
  std::vector<AtmospherePass>& passes = frame.passes;
  BandTiles band;
  band.first_row = first_row;
  band.rows = rows;
  band.tile_rows = (rows + kTileSize - 1) / kTileSize;
  band.tiles = static_cast<std::size_t>(cones.columns()) * band.tile_rows;
  const std::size_t band_tiles = band.tiles;
  auto tile_index = [&](std::uint32_t t) {
    return tile_band_row(t) * static_cast<std::size_t>(cones.columns()) + tile_column(t);
  };
  auto body_touches = [&](std::size_t b) {
    const glm::dvec3 c = scene.bodies[b].position_m - scene.camera.position_m;
    return cones.tiles_touching_sphere(frame.world_to_camera * glm::normalize(c), glm::length(c),
                                       scene.bodies[b].radius_m, first_row, rows);
  };
  std::vector<std::uint8_t>& shells = band.shells;
  shells.assign(band_tiles, 0);
  for (AtmospherePass& pass : passes) {
    pass.shell_tiles = pass.gpu ? cones.tiles_touching_sphere(pass.direction_camera, pass.distance_m,
                                                              pass.top_radius_m, first_row, rows)
                                : std::vector<std::uint32_t>{};
    for (std::uint32_t t : pass.shell_tiles) shells[tile_index(t)] = static_cast<std::uint8_t>(std::min(shells[tile_index(t)] + 1, 2));
  }
  enum TileUse : std::uint8_t { kGbuffer = 1, kBody = 2, kSun = 4 };
  std::vector<std::uint8_t> use(band_tiles, 0);
  auto mark = [&](const std::vector<std::uint32_t>& list, std::uint8_t flag) {
    for (std::uint32_t t : list) use[tile_index(t)] |= flag;
  };
  // Per body, the tiles it can be in (for the one-pass variants and the direct tiles).
  std::vector<std::vector<std::uint32_t>> body_tiles_of(scene.bodies.size());
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    body_tiles_of[b] = body_touches(b);
    mark(body_tiles_of[b], kBody);
  }
  if (options_.sun_disc)
    mark(cones.tiles_touching_sphere(frame.sun_camera, 1.0, std::sin(frame.sun_reach), first_row, rows), kSun);
  for (AtmospherePass& pass : passes) {
    pass.gbuffer_tiles.clear();
    pass.one_pass.clear();
    if (pass.shell_tiles.empty()) continue;
    const scene::Body& planet = scene.bodies[static_cast<std::size_t>(pass.body)];
    const glm::dvec3 to_planet = planet.position_m - scene.camera.position_m;
    const std::vector<TileCover> ground =
        cones.sphere_cover(frame.world_to_camera * glm::normalize(to_planet), glm::length(to_planet), planet.radius_m,
                           first_row, rows);
    // Other bodies: 1 where one beyond the shell can be, 2 where one inside it can be.
    std::vector<std::uint8_t> others(band_tiles, 0);
    const std::vector<std::size_t> inside = frame.bodies_inside_shell(pass);
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      if (static_cast<int>(b) == pass.body) continue;
      const std::uint8_t level = std::find(inside.begin(), inside.end(), b) != inside.end() ? 2 : 1;
      for (std::uint32_t t : body_tiles_of[b]) others[tile_index(t)] = std::max(others[tile_index(t)], level);
    }
    for (std::uint32_t t : pass.shell_tiles) {
      const std::size_t i = tile_index(t);
      if (shells[i] > 1 || !options_.one_pass_tiles) {
        pass.gbuffer_tiles.push_back(t);
        continue;
      }
      GpuAtmosphere::TileVariant v;
      v.sky_view = pass.sky_view && others[i] < 2;
      v.ground = ground[i];
      v.others = others[i];
      v.sun = (use[i] & kSun) != 0;
      auto& list = pass.one_pass[v.key()];
      list.first = v;
      list.second.push_back(t);
    }
    mark(pass.gbuffer_tiles, kGbuffer);
  }
  if (!options_.one_pass_tiles)
    mark(cones.tiles_touching_sphere(glm::dvec3(0, 0, -1), 0.0, 1.0, first_row, rows), kGbuffer);
  // One buffer per band holds every list: each atmosphere's, then the
  // G-buffer path's tiles, the bodies' and the sun's direct tiles.
  std::vector<std::uint32_t>& all_tiles = band.all_tiles;
  auto append = [&](const std::vector<std::uint32_t>& list) {
    const TileList l{all_tiles.size(), list.size()};
    all_tiles.insert(all_tiles.end(), list.begin(), list.end());
    return l;
  };
  band.lists.resize(passes.size());
  for (std::size_t a = 0; a < passes.size(); ++a) {
    const AtmospherePass& pass = passes[a];
    FrameStats::Atmosphere& st = stats_.atmospheres[a];
    for (const auto& [key, list] : pass.one_pass) {
      band.lists[a].one_pass.emplace_back(list.first, append(list.second));
      band.one_pass_atmosphere_tiles += list.second.size();
      if (list.first.sky_view) st.sky_view_tiles += list.second.size();
    }
    band.lists[a].gbuffer = append(pass.gbuffer_tiles);
    st.tiles += pass.shell_tiles.size();
    st.gbuffer_tiles += pass.gbuffer_tiles.size();
  }
  auto list_where = [&](auto&& keep) {  // the band's tiles i with keep(i), row by row
    TileList l{all_tiles.size(), 0};
    for (std::size_t i = 0; i < band_tiles; ++i)
      if (keep(i)) {
        all_tiles.push_back(pack_tile(static_cast<std::uint32_t>(i % static_cast<std::size_t>(cones.columns())),
                                      static_cast<std::uint32_t>(i / static_cast<std::size_t>(cones.columns()))));
        ++l.count;
      }
    return l;
  };
  band.gbuffer_tiles = list_where([&](std::size_t i) { return (use[i] & kGbuffer) != 0; });
  // Body tiles (no shell, no sun): those only one body can be in, per body
  // (direct_light.comp's ONE_BODY, its data as uniforms), then the others.
  std::vector<std::uint8_t> body_count(band_tiles, 0);
  for (const auto& list : body_tiles_of)
    for (std::uint32_t t : list) body_count[tile_index(t)] = static_cast<std::uint8_t>(std::min(body_count[tile_index(t)] + 1, 2));
  auto body_only = [&](std::size_t i) { return shells[i] == 0 && use[i] == kBody; };
  for (std::size_t b = 0; b < body_tiles_of.size(); ++b) {
    std::vector<std::uint32_t> only;
    for (std::uint32_t t : body_tiles_of[b])
      if (body_only(tile_index(t)) && body_count[tile_index(t)] == 1) only.push_back(t);
    if (only.empty()) continue;
    band.one_body_tiles.emplace_back(b, append(only));
    band.one_body_count += only.size();
  }
  band.body_tiles = list_where([&](std::size_t i) { return body_only(i) && body_count[i] > 1; });
  band.sun_tiles =
      list_where([&](std::size_t i) { return shells[i] == 0 && (use[i] & kGbuffer) == 0 && (use[i] & kSun) != 0; });
  stats_.tiles_gbuffer += band.gbuffer_tiles.count;
  stats_.tiles_one_atmosphere += band.one_pass_atmosphere_tiles;
  stats_.tiles_direct += band.one_body_count + band.body_tiles.count + band.sun_tiles.count;
  stats_.tiles_black += band_tiles - (band.gbuffer_tiles.count + band.one_pass_atmosphere_tiles + band.one_body_count +
                                      band.body_tiles.count + band.sun_tiles.count);
  // Tiles nothing is dispatched for stay black: not cleared on the GPU, zeros in the rows.
  band.black.assign(band_tiles, 0);
  for (std::size_t i = 0; i < band_tiles; ++i) band.black[i] = shells[i] == 0 && use[i] == 0;
  return band;
}

void Renderer::upload_tile_lists(const BandTiles& band) {
  Impl& im = *impl_;
  im.ensure_tiles_buffer(band.all_tiles.size());
  if (!band.all_tiles.empty()) im.tiles.upload(std::span<const std::uint32_t>(band.all_tiles));
  im.tiles.bind_storage(kTiles);
  im.frame_rgb.bind_storage(kFrameRgb);
}

void Renderer::draw_direct_tiles(Frame& frame, const BandTiles& band, PassTimer& timer) {
  const Impl::FramePasses& fp = *frame.programs;
  for (const auto& [b, list] : band.one_body_tiles) {
    frame.set_the_body(frame.prepare(fp.direct_light_one), b);
    fp.direct_light_one.set_uniform("one_body", static_cast<int>(b));
    timer.gpu("direct light", [&] { frame.dispatch_tiles(fp.direct_light_one, list, kDirectLightTilesPerGroup); });
  }
  if (band.body_tiles.count > 0)
    timer.gpu("direct light",
              [&] { frame.dispatch_tiles(fp.direct_light, band.body_tiles, kDirectLightTilesPerGroup); });
  if (band.sun_tiles.count > 0)
    timer.gpu("direct light, sun",
              [&] { frame.dispatch_tiles(fp.direct_light_sun, band.sun_tiles, kDirectLightTilesPerGroup); });
}

void Renderer::draw_one_pass_tiles(Frame& frame, const BandTiles& band, PassTimer& timer) {
  if (band.one_pass_atmosphere_tiles == 0) return;
  Impl& im = *impl_;
  for (std::size_t g = 0; g < frame.groups; ++g) {
    for (std::size_t a = 0; a < frame.passes.size(); ++a) {
      const AtmospherePass& pass = frame.passes[a];
      if (band.lists[a].one_pass.empty()) continue;
      pass.gpu->bind(g);
      im.bodies.bind_storage(kBodies);
      im.tiles.bind_storage(kTiles);
      for (const auto& [variant, list] : band.lists[a].one_pass) {
        const ShaderProgram& p = pass.gpu->tile_program(frame.variant, variant);
        frame.set_group_uniforms(p, g);
        pass.gpu->set_group(p, g);
        frame.set_the_body(p, static_cast<std::size_t>(pass.body));
        p.set_uniform("planet", pass.body);
        p.set_uniform("camera_top_power", static_cast<float>(pass.power_m2));
        timer.gpu(fmt::format("atmosphere {}, one pass, {}, {}{}{}", stats_.atmospheres[a].body,
                              variant.sky_view ? "sky view" : "4D tables",
                              variant.ground == TileCover::none  ? "sky"
                              : variant.ground == TileCover::all ? "ground"
                                                                 : "horizon",
                              variant.others == 0 ? "" : " + bodies", variant.sun ? " + sun" : ""),
                  [&] { frame.dispatch_tiles(p, list); });
      }
    }
    if (g + 1 < frame.groups) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the next group adds to these pixels
  }
}

void Renderer::draw_gbuffer_tiles(Frame& frame, const BandTiles& band, PassTimer& timer) {
  if (band.gbuffer_tiles.count == 0) return;
  Impl& im = *impl_;
  const Impl::FramePasses& fp = *frame.programs;
  const scene::Scene& scene = frame.scene;
  im.gbuffer_hit.bind_image(kGbufferHit, gl::ImageAccess::write_only);
  im.gbuffer_albedo.bind_image(kGbufferAlbedo, gl::ImageAccess::write_only);
  im.radiance_sum.bind_image(kRadianceSum, gl::ImageAccess::write_only);
  im.transmittance.bind_image(kTransmittance, gl::ImageAccess::write_only);
  timer.gpu("g-buffer", [&] { frame.dispatch_tiles(fp.gbuffer, band.gbuffer_tiles); });
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

  for (std::size_t g = 0; g < frame.groups; ++g) {
    im.gbuffer_hit.bind_image(kGbufferHit, gl::ImageAccess::read_only);
    im.gbuffer_albedo.bind_image(kGbufferAlbedo, gl::ImageAccess::read_only);
    im.radiance_sum.bind_image(kRadianceSum, gl::ImageAccess::read_write);
    im.transmittance.bind_image(kTransmittance, gl::ImageAccess::read_write);
    for (std::size_t a = 0; a < frame.passes.size(); ++a) {
      const AtmospherePass& pass = frame.passes[a];
      if (band.lists[a].gbuffer.count == 0) continue;
      const ShaderProgram& p = pass.gpu->gbuffer_path_program(frame.variant);
      pass.gpu->bind(g);
      im.bodies.bind_storage(kBodies);
      im.tiles.bind_storage(kTiles);
      frame.prepare(p);
      pass.gpu->set_group(p, g);
      frame.set_the_body(p, static_cast<std::size_t>(pass.body));
      p.set_uniform("planet", pass.body);
      p.set_uniform("camera_top_power", static_cast<float>(pass.power_m2));
      p.set_uniform("sun_irradiance", lanes(scene.sun.irradiance_W_m2_nm, g));
      p.set_uniform("albedo_from_r", lanes(frame.albedo_weights, 0, g));
      p.set_uniform("albedo_from_g", lanes(frame.albedo_weights, 1, g));
      p.set_uniform("albedo_from_b", lanes(frame.albedo_weights, 2, g));
      timer.gpu(fmt::format("atmosphere {}, g-buffer path", stats_.atmospheres[a].body),
                [&] { frame.dispatch_tiles(p, band.lists[a].gbuffer); });
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    frame.set_group_uniforms(fp.resolve, g);
    timer.gpu("resolve", [&] { frame.dispatch_tiles(fp.resolve, band.gbuffer_tiles); });
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

void Renderer::read_back_band(const Frame& frame, const BandTiles& band, std::vector<float>& rows_rgb,
                              PassTimer& timer) {
  // RGB of each (r, g, b, 0), packed from the mapped buffer by both cores, a
  // tile row per task; zeros for the black tiles, whose memory is not read.
  Impl& im = *impl_;
  const int width = frame.projection.width(), rows = band.rows;
  const int columns = frame.cones->columns();
  const std::size_t band_bytes = static_cast<std::size_t>(width) * rows * 4 * sizeof(float);
  rows_rgb.resize(static_cast<std::size_t>(width) * rows * 3);
  timer.cpu("readback", [&] {
    im.frame_rgb.read_mapped(band_bytes, [&](std::span<const std::byte> bytes) {
      const auto* rgba = reinterpret_cast<const float*>(bytes.data());
      core::parallel_for(static_cast<std::size_t>(band.tile_rows), 0, [&](std::size_t tile_row) {
        const int y_end = std::min(rows, static_cast<int>(tile_row + 1) * kTileSize);
        for (int y = static_cast<int>(tile_row) * kTileSize; y < y_end; ++y)
          for (int tx = 0; tx < columns; ++tx) {
            const std::size_t begin = static_cast<std::size_t>(y) * width + static_cast<std::size_t>(tx) * kTileSize;
            const std::size_t end = static_cast<std::size_t>(y) * width + std::min(width, (tx + 1) * kTileSize);
            if (band.black[tile_row * static_cast<std::size_t>(columns) + static_cast<std::size_t>(tx)]) {
              std::fill(rows_rgb.begin() + static_cast<std::ptrdiff_t>(3 * begin),
                        rows_rgb.begin() + static_cast<std::ptrdiff_t>(3 * end), 0.0f);
              continue;
            }
            for (std::size_t i = begin; i < end; ++i) {
              rows_rgb[3 * i] = rgba[4 * i];
              rows_rgb[3 * i + 1] = rgba[4 * i + 1];
              rows_rgb[3 * i + 2] = rgba[4 * i + 2];
            }
          }
      });
    });
  });
}

}  // namespace zenith::render
