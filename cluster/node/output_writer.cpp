#include "cluster/node/output_writer.h"

#include <fmt/format.h>

#include <fstream>
#include <optional>

#include "image/display_fade.h"
#include "image/tone_mapping.h"
#include "render/display/colour_signal.h"
#include "warp/blending.h"

namespace zenith::cluster {

bool has_output_stage(const warp::OutputConfig& o) {
  return o.blend.mode != warp::BlendMode::none || o.black_level != 0.0;
}

OutputWriter::OutputWriter(const warp::ViewportConfig& viewports, FrameFileLayout layout,
                           std::filesystem::path output_directory, std::filesystem::path node_directory,
                           std::string format)
    : viewports_(viewports),
      layout_(layout),
      output_directory_(std::move(output_directory)),
      node_directory_(std::move(node_directory)),
      format_(std::move(format)) {}

std::filesystem::path OutputWriter::frame_path(const warp::OutputConfig& o, std::uint64_t frame) const {
  if (layout_ == FrameFileLayout::offline)  // apps/offline_render.h: frame_file_path()
    return output_directory_ / o.name / fmt::format("{}.{:06d}.{}", o.name, frame, format_);
  return node_directory_ / o.name / fmt::format("frame-{:06d}.{}", frame, format_);
}

std::vector<float> OutputWriter::display_image(std::size_t viewport_index, std::vector<float> rgb,
                                               const scene::FadeState& fade) const {
  const warp::OutputConfig& o = viewports_.outputs[viewport_index];
  for (float& v : rgb) v = image::tone_map(v, image::ToneMapping::exponential);
  image::apply_fade(rgb, fade.level, {fade.colour.x, fade.colour.y, fade.colour.z});
  if (has_output_stage(o))
    warp::apply_blend(rgb, 0, o.height_px, warp::output_blend_mask(viewports_, viewport_index), o.black_level);
  return rgb;
}

void OutputWriter::write(std::size_t viewport_index, std::uint64_t frame, std::vector<float> rgb,
                         image::ImageAttributes attributes, const scene::FadeState& fade) {
  const warp::OutputConfig& o = viewports_.outputs[viewport_index];
  const std::filesystem::path final_path = frame_path(o, frame);
  std::filesystem::path partial = final_path;
  partial += ".partial";
  std::filesystem::create_directories(final_path.parent_path());
  const bool blended = has_output_stage(o);
  const bool faded = fade.level > 0.0;
  if (faded)
    attributes.emplace_back("zenith:fade", fmt::format("level {} colour {} {} {}", fade.level, fade.colour.x,
                                                       fade.colour.y, fade.colour.z));
  if (format_ == "exr") {
    if (blended)
      warp::apply_blend(rgb, 0, o.height_px, warp::output_blend_mask(viewports_, viewport_index), o.black_level);
    image::write_exr(partial, o.width_px, o.height_px, rgb, image::ExrPixelType::half, attributes);
  } else if (o.colour) {
    // The region's colour profile (docs/warp-meshes.md, "Colour profile"), as the display pass applies it.
    for (float& v : rgb) v = image::tone_map(v, image::ToneMapping::exponential);
    image::apply_fade(rgb, fade.level, {fade.colour.x, fade.colour.y, fade.colour.z});
    const std::optional<warp::BlendMask> mask =
        blended ? std::optional(warp::output_blend_mask(viewports_, viewport_index)) : std::nullopt;
    render::display::apply_colour_profile(rgb, 0, o.height_px, o.width_px, *o.colour, mask ? &*mask : nullptr,
                                          blended ? o.black_level : 0.0);
    render::display::to_srgb_code_centres(rgb);  // the PNG writer encodes sRGB: it stores V's codes
    image::write_png(partial, o.width_px, o.height_px, rgb, image::ToneMapping::clamp, attributes);
  } else if (!blended && !faded) {
    image::write_png(partial, o.width_px, o.height_px, rgb, image::ToneMapping::exponential, attributes);
  } else {
    // As `zenith render --viewport`: tone map, then the output stage, then sRGB (docs/viewports.md).
    image::write_png(partial, o.width_px, o.height_px, display_image(viewport_index, std::move(rgb), fade),
                     image::ToneMapping::clamp, attributes);
  }
  partials_.emplace_back(partial, final_path);
}

void OutputWriter::finish_frame(RenderedFrame rendered) { rendered_ = std::move(rendered); }

bool OutputWriter::present(std::uint64_t frame) {
  if (!rendered_ || rendered_->frame != frame) return false;
  for (const auto& [partial, final_path] : partials_) std::filesystem::rename(partial, final_path);
  partials_.clear();
  presented_ = std::move(rendered_);
  rendered_.reset();
  return true;
}

void OutputWriter::log_presented() {
  if (!presented_) return;
  const RenderedFrame presented = std::move(*presented_);
  presented_.reset();
  // Kept open: a present is one write, not a file opened and closed each frame.
  if (!log_.is_open()) log_.open(node_directory_ / "presented.log", std::ios::app);
  log_ << "frame " << presented.frame << " state " << presented.state_digest << " tables " << presented.tables
       << " show_time_s " << fmt::format("{}", presented.show_time_s);
  if (presented.fade.level > 0.0)
    log_ << fmt::format(" fade {} {},{},{}", presented.fade.level, presented.fade.colour.x, presented.fade.colour.y,
                        presented.fade.colour.z);
  log_ << "\n";
  log_.flush();  // read while the show runs (tests, the console)
}

void OutputWriter::discard() {
  std::error_code ec;
  for (const auto& [partial, final_path] : partials_) std::filesystem::remove(partial, ec);
  partials_.clear();
  rendered_.reset();
}

}  // namespace zenith::cluster
