#include "cluster/master/playback.h"

#include <spdlog/spdlog.h>

#include <stdexcept>

#include "cluster/link/cluster_config.h"
#include "core/strings.h"
#include "render/render_flags.h"
#include "scene/scene_loader.h"

namespace zenith::cluster {

using core::cat;

namespace {

/// A paced show's frames go out on a schedule at its rate (FrameSchedule's
/// period): the rate must be one the cluster's timing allows, as
/// timing.frame_rate_hz must. Unpaced, the rate only samples show time.
void check_paced_rate(const MasterOptions& options, double fps, const char* source) {
  if (!options.paced || (fps >= kMinFrameRateHz && fps <= kMaxFrameRateHz)) return;
  throw std::invalid_argument(cat("master: ", fps, " frames per second (", source, "): a paced show presents ",
                                  kMinFrameRateHz, " to ", kMaxFrameRateHz,
                                  " frames per second (the nodes' frame schedule); --unpaced renders at any rate"));
}

}  // namespace

void load_playback(const MasterOptions& options, Playback& p) {
  p.render_flags = render::render_flags_of(render::RenderOptions{});
  p.fps = options.config.frame_rate_hz;
  if (!options.show) {
    p.scene = scene::load_scene(options.config.scene);
  } else {
    if (!options.atmosphere_switches.empty())
      throw std::invalid_argument(
          "atmosphere switches cannot be combined with a show: use the show's atmosphere tracks");
    p.show.emplace(show::load_show(*options.show));
    p.scene = p.show->scene();
    if (options.show_fps > 0.0)
      p.fps = options.show_fps;
    else if (p.show->kind() == show::Show::Kind::recording)
      p.fps = p.show->frame_rate_hz();
    check_paced_rate(options, p.fps, options.show_fps > 0.0 ? "--fps" : "the recording's frame rate");
    p.clock.emplace(p.show->duration_s(), p.fps, options.loop.value_or(p.show->loop()));
    spdlog::info("master: playing show '{}' ({:.1f} s at {} fps, {} frames{})", p.show->name(), p.show->duration_s(),
                 p.fps, p.show->frame_count(p.fps), p.clock->looping() ? ", looping" : "");
  }
  if (options.house_timecode) {
    p.timecode = options.house_timecode;
    spdlog::info("master: chasing {} (the standby's input, chased while it followed)", p.timecode->summary);
  } else if (chases_timecode(options)) {
    p.timecode = open_house_timecode(options, p.show ? &*p.show : nullptr);
    spdlog::info("master: chasing {}", p.timecode->summary);
  }
  if (options.record)
    p.recorder = std::make_unique<show::ShowRecorder>(
        *options.record, p.show ? p.show->scene_path() : options.config.scene,
        p.show ? cat(p.show->name(), " (recorded)") : cat(options.config.name, " session"), p.fps);
}

}  // namespace zenith::cluster
