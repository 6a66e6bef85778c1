#include "render/renderer.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "atmosphere/lut/parallel_for.h"
#include "atmosphere/model_hash.h"
#include "render/frame/tile_culling.h"
#include "render/gl/buffer.h"
#include "render/gl/gl_error.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"
#include "render/lut/shader_model.h"
#include "render/scene/albedo_map.h"
#include "render/scene/sun_disc.h"

namespace zenith::render {
namespace {

using gl::ShaderProgram;
using gl::Texture;
using gl::TextureFormat;
using Vec4 = std::array<float, 4>;

constexpr int kMaxBodies = 64;         // as many as a scene may have (render/scene/scene_loader.cpp)
constexpr unsigned kAlbedoMapUnit = 8;  // albedo_maps (a 2D array texture)
constexpr unsigned kRayTableUnit = 7;   // projection_ray_table of projection.glsl
constexpr std::size_t kLanes = kWavelengthLanes;

// Storage bindings and image units of the render passes (frame.glsl, *.comp).
enum StorageBinding : unsigned { kBodies = 4, kTiles = 5 };
enum ImageUnit : unsigned { kGbufferHit = 0, kGbufferAlbedo = 1, kRadianceSum = 2, kTransmittance = 3, kFrameRgb = 4 };

/// frame.glsl's Body, std430 layout (6 vec4).
struct GpuBody {
  Vec4 centre;  // direction camera → centre, distance
  Vec4 shape;   // R, |c|² − R², atmosphere slot, albedo layer
  Vec4 albedo_map;
  Vec4 world_to_body[3];
};
static_assert(sizeof(GpuBody) == 6 * 16);

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
  ShaderProgram gbuffer, resolve;
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
  // Band images, (re)allocated when the band size changes.
  int band_width = 0, band_height = 0;
  Texture gbuffer_hit, gbuffer_albedo, radiance_sum, transmittance, frame_rgb;

  void ensure_band_images(int width, int height) {
    if (width == band_width && height == band_height) return;
    gbuffer_hit = Texture::create_2d(TextureFormat::rgba32f, width, height);
    gbuffer_albedo = Texture::create_2d(TextureFormat::rgba16f, width, height);
    radiance_sum = Texture::create_2d(TextureFormat::rgba32f, width, height);
    transmittance = Texture::create_2d(TextureFormat::rgba32f, width, height);
    frame_rgb = Texture::create_2d(TextureFormat::rgba32f, width, height);
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
  const std::vector<gl::ShaderDefine> resolve_defines = {
      {"SUN_DISC", options_.sun_disc ? "1" : "0"},
      {"LIMB_DARKENING", options_.limb_darkening ? "1" : "0"},
      {"ECLIPSES", options_.atmosphere.eclipses ? "1" : "0"},
  };
  const std::vector<gl::ShaderDefine> gbuffer_defines = {{"ECLIPSES", "0"}};
  impl_->gbuffer = ShaderProgram::load_compute("render/gbuffer.comp", gbuffer_defines);
  impl_->resolve = ShaderProgram::load_compute("render/resolve.comp", resolve_defines);
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

void Renderer::render(const scene::Scene& scene, const warp::Projection& projection, const RowSink& sink) {
  const auto start = std::chrono::steady_clock::now();
  Impl& im = *impl_;
  stats_ = FrameStats{};
  gl::check_gl_error("Renderer::render: an earlier GL call left an error");

  const std::size_t n = scene.wavelengths_nm.size();
  if (n == 0) throw std::invalid_argument("scene '" + scene.name + "' has no working wavelengths");
  if (scene.bodies.size() > static_cast<std::size_t>(kMaxBodies))
    throw std::invalid_argument(fmt::format("scene '{}' has {} bodies; the renderer draws at most {}", scene.name,
                                            scene.bodies.size(), kMaxBodies));
  if (scene.sun.irradiance_W_m2_nm.size() != n)
    throw std::invalid_argument(fmt::format("scene '{}': the sun has {} irradiance values for {} wavelengths",
                                            scene.name, scene.sun.irradiance_W_m2_nm.size(), n));
  const std::size_t groups = (n + kLanes - 1) / kLanes;

  // ---- per-frame constants, in double on the CPU
  const glm::dmat3 camera_to_world = glm::mat3_cast(glm::normalize(scene.camera.orientation));
  const glm::dmat3 world_to_camera = glm::transpose(camera_to_world);
  const glm::dvec3 sun = glm::normalize(scene.sun.direction);
  const double sun_radius = scene.sun.angular_radius_rad;
  const double pixel_angle = projection.max_pixel_angle_rad();

  const auto rgb_weights = image::spectral_to_rgb_weights(scene.wavelengths_nm, options_.colour);
  const auto albedo_weights = image::rgb_to_spectral_weights(scene.wavelengths_nm, options_.colour);
  // A sun resolved by the pixels is drawn as its limb-darkened disc; one
  // under 1.5 pixels in radius as a Gaussian of σ = 0.7 pixel carrying the
  // same irradiance (exp(−θ²/2σ²) E / 2πσ²): a disc sampled at pixel centres
  // would flicker and lose or gain light with its sub-pixel position.
  const double sun_point_sigma = sun_radius < 1.5 * pixel_angle ? 0.7 * pixel_angle : 0.0;
  std::vector<double> sun_centre(n), limb_exponent(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double e = scene.sun.irradiance_W_m2_nm[i];
    if (sun_point_sigma > 0.0)
      sun_centre[i] = e / (2.0 * std::numbers::pi * sun_point_sigma * sun_point_sigma);
    else
      sun_centre[i] = options_.limb_darkening ? scene::disc_centre_radiance(e, sun_radius, scene.wavelengths_nm[i])
                                              : scene::uniform_disc_radiance(e, sun_radius);
    limb_exponent[i] = scene::limb_darkening_exponent(scene.wavelengths_nm[i]);
  }

  // ---- tile cones of the projection (once per projection)
  {
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
  }
  const TileCones& cones = *im.cones;
  const std::size_t tiles_total = static_cast<std::size_t>(cones.columns()) * cones.rows();

  // ---- bodies: camera-relative, in double, then float
  std::vector<GpuBody> bodies(scene.bodies.size());
  std::vector<std::string> albedo_layers;  // body b's map is layer b
  struct AtmospherePass {
    int body = 0;
    double distance_m = 0.0, top_radius_m = 0.0, power_m2 = 0.0;
    glm::dvec3 direction_camera{0.0};
    GpuAtmosphere* gpu = nullptr;
    std::vector<std::uint32_t> band_tiles;
  };
  std::vector<AtmospherePass> passes;
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
    pass.direction_camera = world_to_camera * dir;
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
    s.tiles_total = tiles_total;
    stats_.atmospheres.push_back(s);
  }
  im.ensure_albedo_array(albedo_layers);
  for (GpuBody& g : bodies) g.albedo_map = {static_cast<float>(im.albedo_array.width()), 0, 0, 0};
  im.albedo_array.bind(kAlbedoMapUnit);
  im.bodies = gl::Buffer::from(std::span<const GpuBody>(bodies.empty() ? std::vector<GpuBody>(1) : bodies));

  // ---- tables: only for atmospheres the view touches, only when not resident
  auto touches_view = [&](const AtmospherePass& pass) {
    return !cones.tiles_touching_sphere(pass.direction_camera, pass.distance_m, pass.top_radius_m, 0,
                                        projection.height())
                .empty();
  };
  for (AtmospherePass& pass : passes) {
    if (!touches_view(pass)) continue;  // an atmosphere outside the view costs nothing
    const atmosphere::AtmosphereModel& model = scene.bodies[static_cast<std::size_t>(pass.body)].atmosphere->loaded.model;
    const std::string key = fmt::format("{} mult={} ecl={} fp64={}", atmosphere::lookup_table_hash(model),
                                        options_.atmosphere.multiple_scattering, options_.atmosphere.eclipses,
                                        options_.atmosphere.fp64);
    auto it = im.atmospheres.find(key);
    if (it == im.atmospheres.end()) {
      ++stats_.table_sets_requested;
      const atmosphere::lut::LookupTables tables = table_source_(model);
      it = im.atmospheres.emplace(key, std::make_unique<GpuAtmosphere>(model, tables, options_.atmosphere)).first;
      ++stats_.table_sets_uploaded;
      spdlog::debug("renderer: atmosphere of '{}' resident ({:.1f} MB of tables)",
                    scene.bodies[static_cast<std::size_t>(pass.body)].name, static_cast<double>(it->second->table_bytes()) / 1e6);
    }
    pass.gpu = it->second.get();
  }

  // ---- uniforms shared by all passes
  std::array<float, 9> camera_matrix{};
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) camera_matrix[col * 3 + row] = static_cast<float>(camera_to_world[col][row]);
  const warp::GpuProjection gpu_projection = projection.gpu();
  auto set_frame_uniforms = [&](const ShaderProgram& p) {
    p.set_uniform("body_count", static_cast<int>(scene.bodies.size()));
    p.set_uniform("camera_to_world", camera_matrix);
    p.set_uniform("sun_direction", std::array<float, 3>{static_cast<float>(sun.x), static_cast<float>(sun.y),
                                                        static_cast<float>(sun.z)});
    p.set_uniform("sun_angular_radius", static_cast<float>(sun_radius));
    p.set_uniform("pixel_angle", static_cast<float>(pixel_angle));
    p.set_uniform("projection_kind", static_cast<int>(gpu_projection.kind));
    for (int k = 0; k < 4; ++k)
      p.set_uniform(fmt::format("projection_params[{}]", k), gpu_projection.params[static_cast<std::size_t>(k)]);
  };
  set_frame_uniforms(im.gbuffer);
  set_frame_uniforms(im.resolve);
  for (const AtmospherePass& pass : passes)
    if (pass.gpu) set_frame_uniforms(pass.gpu->program());
  im.resolve.set_uniform("exposure", static_cast<float>(scene.camera.exposure));
  im.resolve.set_uniform("sun_draw_radius", static_cast<float>(sun_radius));
  im.resolve.set_uniform("sun_point_sigma", static_cast<float>(sun_point_sigma));

  // ---- bands
  const int width = projection.width(), height = projection.height();
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
    const std::array<int, 2> origin{0, first_row}, size{width, rows};
    auto set_band = [&](const ShaderProgram& p) {
      p.set_uniform("band_origin", origin);
      p.set_uniform("band_size", size);
    };

    if (gpu_projection.kind == warp::ProjectionKind::ray_table) {
      // Rays of this band on the CPU, in double, kept for the next frames.
      auto table = im.ray_tables.find(first_row);
      if (table == im.ray_tables.end()) {
        std::vector<float> rays(static_cast<std::size_t>(width) * im.band_height * 4, 0.0f);
        atmosphere::parallel_for(static_cast<std::size_t>(rows), 0, [&](std::size_t row) {
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
      auto set_table = [&](const ShaderProgram& p) { p.set_uniform("projection_table_origin", origin); };
      set_table(im.gbuffer);
      set_table(im.resolve);
      for (const AtmospherePass& pass : passes)
        if (pass.gpu) set_table(pass.gpu->program());
    }

    set_band(im.gbuffer);
    im.gbuffer_hit.bind_image(kGbufferHit, gl::ImageAccess::write_only);
    im.gbuffer_albedo.bind_image(kGbufferAlbedo, gl::ImageAccess::write_only);
    im.gbuffer.dispatch_covering(width, rows);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

    for (AtmospherePass& pass : passes)
      pass.band_tiles = pass.gpu ? cones.tiles_touching_sphere(pass.direction_camera, pass.distance_m,
                                                               pass.top_radius_m, first_row, rows)
                                 : std::vector<std::uint32_t>{};

    for (std::size_t g = 0; g < groups; ++g) {
      const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1};
      glClearTexImage(im.radiance_sum.id(), 0, GL_RGBA, GL_FLOAT, zero);
      glClearTexImage(im.transmittance.id(), 0, GL_RGBA, GL_FLOAT, one);
      im.gbuffer_hit.bind_image(kGbufferHit, gl::ImageAccess::read_only);
      im.gbuffer_albedo.bind_image(kGbufferAlbedo, gl::ImageAccess::read_only);
      im.radiance_sum.bind_image(kRadianceSum, gl::ImageAccess::read_write);
      im.transmittance.bind_image(kTransmittance, gl::ImageAccess::read_write);
      const Vec4 irradiance = lanes(scene.sun.irradiance_W_m2_nm, g);
      const Vec4 from_r = lanes(albedo_weights, 0, g), from_g = lanes(albedo_weights, 1, g),
                 from_b = lanes(albedo_weights, 2, g);

      for (std::size_t a = 0; a < passes.size(); ++a) {
        AtmospherePass& pass = passes[a];
        if (pass.band_tiles.empty()) continue;
        stats_.atmospheres[a].tiles += pass.band_tiles.size();
        const ShaderProgram& p = pass.gpu->program();
        pass.gpu->bind(g);
        im.bodies.bind_storage(kBodies);
        im.ensure_tiles_buffer(pass.band_tiles.size());
        im.tiles.upload(std::span<const std::uint32_t>(pass.band_tiles));
        im.tiles.bind_storage(kTiles);
        set_band(p);
        p.set_uniform("tile_count", static_cast<int>(pass.band_tiles.size()));
        p.set_uniform("planet", pass.body);
        p.set_uniform("camera_top_power", static_cast<float>(pass.power_m2));
        p.set_uniform("sun_irradiance", irradiance);
        p.set_uniform("albedo_from_r", from_r);
        p.set_uniform("albedo_from_g", from_g);
        p.set_uniform("albedo_from_b", from_b);
        const auto grid = tile_groups(pass.band_tiles.size());
        p.dispatch(grid[0], grid[1]);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
      }

      const ShaderProgram& r = im.resolve;
      set_band(r);
      im.frame_rgb.bind_image(kFrameRgb, gl::ImageAccess::read_write);
      r.set_uniform("first_group", g == 0 ? 1 : 0);
      r.set_uniform("sun_irradiance", irradiance);
      r.set_uniform("sun_centre_radiance", lanes(sun_centre, g));
      r.set_uniform("limb_exponent", lanes(limb_exponent, g));
      r.set_uniform("albedo_from_r", from_r);
      r.set_uniform("albedo_from_g", from_g);
      r.set_uniform("albedo_from_b", from_b);
      r.set_uniform("rgb_from_lanes_r", lanes(rgb_weights, 0, g));
      r.set_uniform("rgb_from_lanes_g", lanes(rgb_weights, 1, g));
      r.set_uniform("rgb_from_lanes_b", lanes(rgb_weights, 2, g));
      r.dispatch_covering(width, rows);
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    }

    // Read back (the whole band image; the last band may use fewer rows).
    const std::vector<float> rgba = im.frame_rgb.read();
    rows_rgb.resize(static_cast<std::size_t>(width) * rows * 3);
    for (std::size_t i = 0; i < static_cast<std::size_t>(width) * rows; ++i)
      for (int k = 0; k < 3; ++k) {
        // Out-of-gamut colours (the CIE mapping's negative lobes) are clipped to 0.
        const float v = rgba[4 * i + static_cast<std::size_t>(k)];
        rows_rgb[3 * i + static_cast<std::size_t>(k)] = v < 0.0f ? 0.0f : v;  // NaN stays visible
      }
    gl::check_gl_error(fmt::format("rendering rows {}–{} of '{}'", first_row, first_row + rows - 1, scene.name));
    sink(first_row, rows, rows_rgb);
  }
  stats_.seconds = seconds_since(start);
}

}  // namespace zenith::render
