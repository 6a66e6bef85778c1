#include "cluster/master/playback.h"

#include <spdlog/spdlog.h>

#include <stdexcept>

#include "core/strings.h"
#include "render/render_flags.h"
#include "scene/scene_loader.h"

namespace zenith::cluster {

using core::cat;

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
    p.clock.emplace(p.show->duration_s(), p.fps, options.loop.value_or(p.show->loop()));
    spdlog::info("master: playing show '{}' ({:.1f} s at {} fps, {} frames{})", p.show->name(), p.show->duration_s(),
                 p.fps, p.show->frame_count(p.fps), p.clock->looping() ? ", looping" : "");
  }
  if (!options.ltc_device.empty() || options.ltc_file || !options.mtc_device.empty()) {
    const std::string input = options.ltc_file              ? "--ltc-file"
                              : !options.mtc_device.empty() ? "--mtc-device"
                                                            : "--ltc-device";
    if (!p.show || !p.show->timecode())
      throw std::invalid_argument(cat(input,
                                      ": the show to chase timecode needs a show file with a \"timecode\" "
                                      "block (its rate and start; docs/shows.md, \"Chasing timecode\")"));
    const show::Show::HouseTimecode& tc = *p.show->timecode();
    p.chase.emplace(tc.chase);
    if (options.ltc_file)
      p.timecode = show::ltc_file_source(*options.ltc_file, options.ltc_channel, tc.rate);
    else if (!options.mtc_device.empty())
      p.timecode = show::mtc_midi_source(options.mtc_device, tc.rate);
    else
      p.timecode = show::ltc_capture_source(options.ltc_device, options.ltc_channel, tc.rate);
    spdlog::info(
        "master: chasing {} at {} fps: show time 0 at {}, through a dropout {:.1f} s, then {}", p.timecode->describe(),
        show::to_string(tc.rate), show::format_timecode(show::timecode_at_seconds(tc.chase.offset_s, tc.rate), tc.rate),
        tc.chase.freewheel_s, tc.chase.after_dropout == show::ChaseSettings::AfterDropout::hold ? "hold" : "stop");
  }
  if (options.record)
    p.recorder = std::make_unique<show::ShowRecorder>(
        *options.record, p.show ? p.show->scene_path() : options.config.scene,
        p.show ? cat(p.show->name(), " (recorded)") : cat(options.config.name, " session"), p.fps);
}

}  // namespace zenith::cluster
