#include "cluster/master/house_timecode.h"

#include <fmt/format.h>

#include <chrono>
#include <stdexcept>

namespace zenith::cluster {

void HouseTimecode::take_frames() {
  for (const show::TimecodeEvent& e : input->take()) chase.receive(e);
}

bool chases_timecode(const MasterOptions& options) {
  return !options.ltc_device.empty() || options.ltc_file || !options.mtc_device.empty();
}

std::shared_ptr<HouseTimecode> open_house_timecode(const MasterOptions& options, const show::Show* show) {
  const std::string input = options.ltc_file              ? "--ltc-file"
                            : !options.mtc_device.empty() ? "--mtc-device"
                                                          : "--ltc-device";
  if (show == nullptr || !show->timecode())
    throw std::invalid_argument(
        fmt::format("{}: the show to chase timecode needs a show file with a \"timecode\" block (its rate and start; "
                    "docs/shows.md, \"Chasing timecode\")",
                    input));
  const show::Show::HouseTimecode& tc = *show->timecode();
  std::unique_ptr<show::TimecodeSource> source;
  if (options.ltc_file) {
    std::optional<std::chrono::system_clock::time_point> first_sample;
    if (options.ltc_file_epoch_s)
      first_sample =
          std::chrono::system_clock::time_point(std::chrono::duration_cast<std::chrono::system_clock::duration>(
              std::chrono::duration<double>(*options.ltc_file_epoch_s)));
    source = show::ltc_file_source(*options.ltc_file, options.ltc_channel, tc.rate, first_sample);
  } else if (!options.mtc_device.empty()) {
    source = show::mtc_midi_source(options.mtc_device, tc.rate);
  } else {
    source = show::ltc_capture_source(options.ltc_device, options.ltc_channel, tc.rate);
  }
  std::string summary = fmt::format(
      "{} at {} fps: show time 0 at {}, through a dropout {:.1f} s, then {}", source->describe(),
      show::to_string(tc.rate), show::format_timecode(show::timecode_at_seconds(tc.chase.offset_s, tc.rate), tc.rate),
      tc.chase.freewheel_s, tc.chase.after_dropout == show::ChaseSettings::AfterDropout::hold ? "hold" : "stop");
  return std::make_shared<HouseTimecode>(
      HouseTimecode{show::TimecodeChase(tc.chase), std::move(source), std::move(summary)});
}

}  // namespace zenith::cluster
