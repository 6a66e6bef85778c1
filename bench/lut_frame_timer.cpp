#include "bench/lut_frame_timer.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "atmosphere/model_hash.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "warp/fisheye_projection.h"

namespace zenith::bench {

struct LutFrameTimer::Entry {
  atmosphere::lut::LookupTables tables;
  std::unique_ptr<render::Renderer> renderer;
  std::vector<double> ms;
  std::size_t nonfinite = 0;
};

LutFrameTimer::LutFrameTimer(const std::filesystem::path& scene_file, int size_px)
    : scene_(scene::load_scene(scene_file)),
      size_px_(size_px),
      projection_(
          std::make_unique<warp::FisheyeProjection>(size_px, size_px)) {  // 180°, the axis along the camera's up
  const auto with_atmosphere = std::count_if(scene_.bodies.begin(), scene_.bodies.end(),
                                             [](const scene::Body& b) { return b.atmosphere.has_value(); });
  if (with_atmosphere != 1)
    throw std::invalid_argument(fmt::format("{}: the frame-time scene must have exactly one atmosphere, it has {}",
                                            scene_file.string(), with_atmosphere));
  for (scene::Body& b : scene_.bodies) b.albedo = scene::AlbedoSource{};  // constant grey
}

LutFrameTimer::~LutFrameTimer() = default;

const atmosphere::AtmosphereModel& LutFrameTimer::model() const {
  for (const scene::Body& b : scene_.bodies)
    if (b.atmosphere) return b.atmosphere->loaded.model;
  throw std::logic_error("LutFrameTimer: no atmosphere");
}

std::size_t LutFrameTimer::add(atmosphere::lut::LookupTables tables, std::size_t* nonfinite_values) {
  auto e = std::make_unique<Entry>();
  e->tables = std::move(tables);
  const Entry* entry = e.get();
  const std::string hash = atmosphere::lookup_table_hash(model());
  e->renderer =
      std::make_unique<render::Renderer>(render::RenderOptions{}, [entry, hash](const atmosphere::AtmosphereModel& m) {
        if (atmosphere::lookup_table_hash(m) != hash)
          throw std::invalid_argument(fmt::format("LutFrameTimer: tables requested for another model ('{}')", m.name));
        return entry->tables;
      });
  for (float v : e->renderer->render_image(scene_, *projection_))
    if (!std::isfinite(v)) ++e->nonfinite;
  if (nonfinite_values) *nonfinite_values = e->nonfinite;
  entries_.push_back(std::move(e));
  return entries_.size() - 1;
}

std::vector<FrameTiming> LutFrameTimer::time_all(int frames) {
  const render::RowSink discard = [](int, int, std::span<const float>) {};
  for (int round = 0; round < frames; ++round)
    for (auto& e : entries_) {
      const auto start = std::chrono::steady_clock::now();
      e->renderer->render(scene_, *projection_, discard);
      e->ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
  std::vector<FrameTiming> out;
  for (auto& e : entries_) {
    std::vector<double> ms = e->ms;
    std::sort(ms.begin(), ms.end());
    FrameTiming t;
    const std::size_t n = ms.size();
    t.frames = static_cast<int>(n);
    t.nonfinite_values = e->nonfinite;
    if (n > 0) {
      t.median_ms = n % 2 == 1 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
      t.min_ms = ms.front();
    }
    out.push_back(t);
  }
  return out;
}

}  // namespace zenith::bench
