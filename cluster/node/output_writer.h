#pragma once
// A render node's frame files (docs/cluster.md, "The frame barrier"): each
// output of a rendered frame is written as FILE.partial and renamed into place
// on Present, so a presented frame appears atomically; every present then
// appends one line to the node's presented.log:
//
//   frame N state DIGEST tables BODY=HASH16,... show_time_s T
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cluster/node/node.h"
#include "image/image_writer.h"
#include "scene/frame_description.h"
#include "warp/viewport_config.h"

namespace zenith::cluster {

/// Whether output `o` has an output stage (a blend or a black level:
/// warp/blending.h) between tone mapping and the display encoding.
bool has_output_stage(const warp::OutputConfig& o);

/// Owns the partial files of at most one rendered frame. Used on the render
/// thread only. Invariant: the partial files on disk are those of the frame
/// recorded by finish_frame() (or of one being written); present() renames
/// them only for that frame.
class OutputWriter {
 public:
  /// What presented.log records of a rendered frame.
  struct RenderedFrame {
    std::uint64_t frame = 0;
    std::string state_digest;  ///< state_digest() of its FrameState
    std::string tables;        ///< "BODY=HASH16,...", "-" for none
    double show_time_s = 0.0;
    scene::FadeState fade;  ///< logged as "fade LEVEL R,G,B" while not the picture alone
  };

  /// `node_directory` holds presented.log; frames go under it (per_node) or
  /// under `output_directory` (offline). `format`: "png" or "exr".
  OutputWriter(const warp::ViewportConfig& viewports, FrameFileLayout layout, std::filesystem::path output_directory,
               std::filesystem::path node_directory, std::string format);

  /// Where output `o` of `frame` ends up once presented.
  std::filesystem::path frame_path(const warp::OutputConfig& o, std::uint64_t frame) const;
  /// What the projector of output `viewport_index` shows for radiance `rgb`:
  /// tone mapped, faded (image/display_fade.h), then the output stage (blend,
  /// black level; docs/viewports.md).
  std::vector<float> display_image(std::size_t viewport_index, std::vector<float> rgb,
                                   const scene::FadeState& fade = {}) const;

  /// Writes output `viewport_index`'s radiance `rgb` of `frame` to its partial
  /// file. A PNG shows the frame's `fade` as the projector does; an EXR keeps
  /// the radiance (scene-referred: a fade is a display operation) and names
  /// the fade in its zenith:fade attribute.
  void write(std::size_t viewport_index, std::uint64_t frame, std::vector<float> rgb, image::ImageAttributes attributes,
             const scene::FadeState& fade = {});
  /// Every output of the frame is written.
  void finish_frame(RenderedFrame rendered);
  /// Present `frame`: renames its partial files into place, the act that
  /// shows it. false (nothing done) when `frame` is not the finished frame.
  bool present(std::uint64_t frame);
  /// Appends the presented.log line of the frame present() last showed (once;
  /// nothing when there is none). Apart from present() so that the node can
  /// note the moment of the act before this bookkeeping (render_worker.h).
  void log_presented();
  /// Removes the partial files and forgets the frame (a new frame starts, or the node stops).
  void discard();

 private:
  const warp::ViewportConfig& viewports_;
  FrameFileLayout layout_;
  std::filesystem::path output_directory_, node_directory_;
  std::string format_;
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> partials_;  ///< partial → final
  std::optional<RenderedFrame> rendered_;
  std::optional<RenderedFrame> presented_;  ///< shown by present(), not yet logged
  std::ofstream log_;                       ///< presented.log, opened at the first line
};

}  // namespace zenith::cluster
