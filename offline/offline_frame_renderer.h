#pragma once
// The single-process FrameRenderer of `zenith show render`: one headless GL
// context and renderer in this process render every output of each frame
// (offline/output_rendering.h: projection, warp, blend and black level).
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "offline/offline_render.h"
#include "offline/output_rendering.h"
#include "render/lut/table_provider.h"
#include "show/show.h"
#include "show/table_plan.h"
#include "render/gl/egl_context.h"
#include "image/colour.h"
#include "render/renderer.h"
#include "warp/blending.h"

namespace zenith::app::offline {

/// An output as this process renders it.
struct LocalOutput {
  std::shared_ptr<const warp::Projection> projection;
  std::optional<warp::BlendMask> blend;   ///< viewport outputs
  double black_level = 0.0;               ///< with a blend
  image::ImageAttributes attributes;      ///< besides the scene's (e.g. zenith:viewport, zenith:blend)
};

class LocalFrameRenderer final : public FrameRenderer {
 public:
  /// `versions`: every atmosphere version the frames use, by table hash.
  /// `stage`: its blend fields are ignored (each output's own apply).
  LocalFrameRenderer(const show::Show& show, std::map<scene::TableHash, show::AtmosphereVersion> versions,
                     std::vector<LocalOutput> outputs, const OutputStage& stage, image::ColourMapping colour,
                     render::TableRequest tables, const render::gl::ContextOptions& context);
  ~LocalFrameRenderer() override;

  /// The GL renderer's name ("llvmpipe (LLVM 15.0.7, 256 bits)", ...).
  const std::string& device() const { return context_.renderer(); }
  /// Obtains every set of `plan` among `table_hashes` that is not cached yet
  /// (precomputed and stored in the cache), with a line per set; the renderer
  /// then loads each from the cache when a frame first needs it.
  void precompute_missing(const show::TablePlan& plan, const std::set<scene::TableHash>& table_hashes);

  void render_frame(const scene::FrameDescription& state,
                    const std::vector<std::vector<std::filesystem::path>>& files) override;

 private:
  render::Renderer& renderer_for(std::uint32_t render_flags);

  const show::Show& show_;
  std::map<scene::TableHash, show::AtmosphereVersion> versions_;
  std::vector<LocalOutput> outputs_;
  OutputStage stage_;
  image::ColourMapping colour_;
  render::TableRequest tables_;
  render::gl::HeadlessContext context_;
  std::unique_ptr<render::Renderer> renderer_;  ///< for render_flags_
  std::uint32_t render_flags_ = 0;
};

}  // namespace zenith::app::offline
