#include "render/band/band_resources.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/parallel_for.h"
#include "render/band/band_readback.h"
#include "render/shader_bindings.h"

namespace zenith::render {

using gl::ImageAccess;
using gl::Texture;
using gl::TextureFormat;

namespace {
/// The G-buffer images' formats, as gbuffer.comp and the passes declare them.
constexpr TextureFormat kHitFormat = TextureFormat::rgba32f, kAlbedoFormat = TextureFormat::rgba16f,
                        kRadianceFormat = TextureFormat::rgba32f, kTransmittanceFormat = TextureFormat::rgba32f,
                        kRayTableFormat = TextureFormat::rgba32f;
}  // namespace

void BandResources::upload_bodies(std::span<const GpuBody> bodies) {
  const std::vector<GpuBody> none(1);
  bodies_ = gl::Buffer::from(bodies.empty() ? std::span<const GpuBody>(none) : bodies);
}

void BandResources::upload_air_shadows(std::span<const std::array<float, 4>> values) {
  air_shadows_ = gl::Buffer::from(values);
  air_shadows_.bind_storage(binding::kAirShadows);
}

void BandResources::bind_bodies() const {
  bodies_.bind_storage(binding::kBodies);
  if (air_shadows_.id() != 0) air_shadows_.bind_storage(binding::kAirShadows);
}

void BandResources::fit_bands(int width, int height, BandReader reader) {
  if (width != band_width_ || height != band_height_) {
    for (Texture* t : {&gbuffer_hit_, &gbuffer_albedo_, &radiance_sum_, &transmittance_}) *t = Texture();
    read_on_cpu_ = gl::Buffer();
    read_on_gpu_ = gl::Buffer();
    ray_tables_.clear();
    band_width_ = width;
    band_height_ = height;
  }
  reader_ = reader;
  gl::Buffer& buffer = reader == BandReader::cpu ? read_on_cpu_ : read_on_gpu_;
  if (buffer.id() != 0) return;
  const std::size_t bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4 * sizeof(float);
  buffer = reader == BandReader::cpu ? gl::Buffer::mappable(bytes) : gl::Buffer(bytes);
}

void BandResources::clear_output(int rows) {
  output().clear_to_zero(0, static_cast<std::size_t>(band_width_) * static_cast<std::size_t>(rows) * 4 * sizeof(float));
}

void BandResources::upload_tile_lists(const BandTiles& band) {
  tiles_ = uploads().upload(std::span<const std::uint32_t>(band.all_tiles));
  tiles_.bind_storage(binding::kTiles);
  output().bind_storage(binding::kFrameRgb);
}

void BandResources::bind_tiles() const { tiles_.bind_storage(binding::kTiles); }

gl::UploadStream& BandResources::uploads() {
  if (!uploads_) uploads_.emplace();
  return *uploads_;
}

void BandResources::end_frame() {
  if (uploads_) uploads_->end_frame();
}

void BandResources::bind_gbuffer_for_the_body_pass() {
  if (gbuffer_hit_.id() == 0) {
    gbuffer_hit_ = Texture::create_2d(kHitFormat, band_width_, band_height_);
    gbuffer_albedo_ = Texture::create_2d(kAlbedoFormat, band_width_, band_height_);
    radiance_sum_ = Texture::create_2d(kRadianceFormat, band_width_, band_height_);
    transmittance_ = Texture::create_2d(kTransmittanceFormat, band_width_, band_height_);
  }
  gbuffer_hit_.bind_image(binding::kGbufferHitImage, ImageAccess::write_only);
  gbuffer_albedo_.bind_image(binding::kGbufferAlbedoImage, ImageAccess::write_only);
  radiance_sum_.bind_image(binding::kRadianceSumImage, ImageAccess::write_only);
  transmittance_.bind_image(binding::kTransmittanceProductImage, ImageAccess::write_only);
}

void BandResources::bind_gbuffer_for_the_atmosphere_passes() {
  gbuffer_hit_.bind_image(binding::kGbufferHitImage, ImageAccess::read_only);
  gbuffer_albedo_.bind_image(binding::kGbufferAlbedoImage, ImageAccess::read_only);
  radiance_sum_.bind_image(binding::kRadianceSumImage, ImageAccess::read_write);
  transmittance_.bind_image(binding::kTransmittanceProductImage, ImageAccess::read_write);
}

void BandResources::add_dispatch_shapes(gl::DispatchShapes& shapes, int width, int rows) {
  gl::TextureShape band;
  band.width = width;
  band.height = rows;
  const auto image = [&](unsigned unit, TextureFormat format) {
    band.format = format;
    shapes.images[{static_cast<int>(unit), band.kind}] = band;
  };
  image(binding::kGbufferHitImage, kHitFormat);
  image(binding::kGbufferAlbedoImage, kAlbedoFormat);
  image(binding::kRadianceSumImage, kRadianceFormat);
  image(binding::kTransmittanceProductImage, kTransmittanceFormat);
  band.format = kRayTableFormat;
  shapes.sampled[{static_cast<int>(binding::kRayTableUnit), band.kind}] = band;
}

void BandResources::upload_rays(const warp::Projection& projection, int first_row, int rows) {
  // Each band's rays stay on the GPU from frame to frame. Uploading them per
  // band and frame into one texture moved the whole frame's rays every frame
  // (33 MB for a 1920 × 1080 projector) and rewrote a texture the band before
  // might still be reading.
  const int width = projection.width();
  Texture& table = ray_tables_[first_row];
  if (table.id() == 0 || table.width() != width || table.height() != band_height_) {
    std::vector<float> rays(static_cast<std::size_t>(width) * static_cast<std::size_t>(band_height_) * 4, 0.0f);
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
    table = Texture::create_2d(kRayTableFormat, width, band_height_);
    table.upload(rays);
  }
  table.bind(binding::kRayTableUnit);
}

std::span<const float> BandResources::read_back(const BandTiles& band, PassTimer& timer) {
  if (reader_ != BandReader::cpu) throw std::logic_error("BandResources::read_back: the bands were fitted for the GPU");
  const std::size_t band_bytes =
      static_cast<std::size_t>(band_width_) * static_cast<std::size_t>(band.rows) * 4 * sizeof(float);
  timer.cpu("readback", [&] {
    output().read_mapped(band_bytes, [&](std::span<const std::byte> bytes) {
      const std::span<const float> rgba(reinterpret_cast<const float*>(bytes.data()), bytes.size() / sizeof(float));
      pack_band_rows(rgba, band, band_width_, tile_columns(), rows_rgb_);
    });
  });
  return rows_rgb_;
}

GpuBand BandResources::bind_band_on_gpu(const BandTiles& band) {
  if (reader_ != BandReader::gpu)
    throw std::logic_error("BandResources::bind_band_on_gpu: the bands were fitted for the CPU");
  // One flag per tile of the band, 1 where nothing was dispatched: those
  // pixels of the output buffer hold whatever an earlier band left there.
  const std::vector<std::uint32_t> black(band.black.begin(), band.black.end());
  output().bind_storage(binding::kFrameRgb);
  uploads().upload(std::span<const std::uint32_t>(black)).bind_storage(binding::kBlackTiles);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the passes' stores to the output buffer
  return {band.first_row, band.rows, band_width_, tile_columns()};
}

void BandResources::end_band_on_gpu() {
  // The bits name the later accesses: the passes' stores to the buffers, the
  // output's clear and the flags' upload.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace zenith::render
