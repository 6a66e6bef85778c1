// The single-process FrameRenderer (offline/offline_frame_renderer.h).
#include "offline/offline_frame_renderer.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

#include "render/render_flags.h"

namespace zenith::app::offline {

LocalFrameRenderer::LocalFrameRenderer(const show::Show& show,
                                       std::map<scene::TableHash, show::AtmosphereVersion> versions,
                                       std::vector<LocalOutput> outputs, const OutputStage& stage,
                                       image::ColourMapping colour, render::TableRequest tables,
                                       const render::gl::ContextOptions& context)
    : show_(show),
      versions_(std::move(versions)),
      outputs_(std::move(outputs)),
      stage_(stage),
      colour_(colour),
      tables_(std::move(tables)),
      context_(context) {}

LocalFrameRenderer::~LocalFrameRenderer() {
  context_.make_current();  // the renderer's GL objects belong to this context
  renderer_.reset();
}

void LocalFrameRenderer::precompute_missing(const show::TablePlan& plan,
                                            const std::set<scene::TableHash>& table_hashes) {
  auto needed = [&](const show::TablePlanEntry& e) { return !e.cached && table_hashes.count(e.version.table_hash) > 0; };
  const auto missing = std::count_if(plan.sets.begin(), plan.sets.end(), needed);
  std::ptrdiff_t done = 0;
  for (const show::TablePlanEntry& entry : plan.sets) {
    if (!needed(entry)) continue;
    ++done;
    spdlog::info("table set {}/{} (body '{}', first used by frame {}): precomputing", done, missing,
                 entry.version.body, entry.first_frame);
    const render::ObtainedTables t = render::obtain_tables(entry.version.loaded.model, tables_);
    spdlog::info("table set {}/{}: {} in {:.1f} s", done, missing,
                 t.from_cache ? "found in the cache" : "precomputed and cached", t.report.total_seconds());
  }
  context_.make_current();  // the GPU precompute may have used a context of its own
}

render::Renderer& LocalFrameRenderer::renderer_for(std::uint32_t render_flags) {
  if (!renderer_ || render_flags != render_flags_) {
    // A recording may change flags between frames: a renderer per run of equal flags.
    context_.make_current();
    renderer_.reset();
    render::RenderOptions options = render::render_options_of(render_flags);
    options.colour = colour_;
    renderer_ = std::make_unique<render::Renderer>(options, [this](const atmosphere::AtmosphereModel& model) {
      render::ObtainedTables t = render::obtain_tables(model, tables_);
      context_.make_current();
      return std::move(t.tables);
    });
    render_flags_ = render_flags;
  }
  return *renderer_;
}

void LocalFrameRenderer::render_frame(const scene::FrameDescription& state,
                                      const std::vector<std::vector<std::filesystem::path>>& files) {
  if (files.size() != outputs_.size())
    throw std::invalid_argument(
        fmt::format("render_frame: files for {} outputs, the renderer has {}", files.size(), outputs_.size()));
  scene::Scene scene = show_.scene();
  show::apply_state(state, versions_, scene);
  render::Renderer& renderer = renderer_for(state.render_flags);
  for (std::size_t o = 0; o < outputs_.size(); ++o) {
    const LocalOutput& out = outputs_[o];
    OutputStage stage = stage_;
    stage.blend = out.blend ? &*out.blend : nullptr;
    stage.black_level = out.black_level;
    stage.fade_level = state.fade.level;
    stage.fade_colour = {state.fade.colour.x, state.fade.colour.y, state.fade.colour.z};
    image::ImageAttributes attributes = image_attributes(scene, *out.projection);
    attributes.insert(attributes.end(), out.attributes.begin(), out.attributes.end());
    attributes.emplace_back("zenith:frame", fmt::format("{}", state.frame));
    attributes.emplace_back("zenith:show_time_s", fmt::format("{}", state.show_time_s));
    if (state.fade.level > 0.0)
      attributes.emplace_back("zenith:fade", fmt::format("level {} colour {} {} {}", state.fade.level,
                                                         state.fade.colour.x, state.fade.colour.y, state.fade.colour.z));
    render_to_files(renderer, scene, *out.projection, files[o], stage, attributes);
  }
}

}  // namespace zenith::app::offline
