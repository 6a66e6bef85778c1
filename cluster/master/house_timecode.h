#pragma once
// The house's timecode a master chases (docs/shows.md, "Chasing timecode"):
// the input its options name (LTC from an ALSA capture device or a rehearsal
// file, MIDI timecode from a raw MIDI port) and the chase of its frames. A
// standby master opens its own while it follows, so that when it takes over
// its chase is already locked and the show goes on from the timecode.
#include <memory>
#include <string>

#include "cluster/master/master_options.h"
#include "show/show.h"
#include "show/timecode/timecode_chase.h"
#include "show/timecode/timecode_source.h"

namespace zenith::cluster {

struct HouseTimecode {
  show::TimecodeChase chase;
  std::unique_ptr<show::TimecodeSource> input;
  /// "LTC from show.wav (channel 1, 48000 Hz) at 25 fps: show time 0 at 01:00:00:00, through a dropout 2.0 s,
  /// then hold", for the logs.
  std::string summary;

  /// The frames the input read since the last call, into the chase.
  void take_frames();
};

/// Whether `options` name a timecode input.
bool chases_timecode(const MasterOptions& options);

/// Opens the input `options` name for `show` (its "timecode" block: the rate,
/// the start, the dropout rules). Throws std::invalid_argument where there is
/// no show or it has no "timecode" block, std::runtime_error for an input that
/// cannot be opened (naming the device or file and the reason).
std::shared_ptr<HouseTimecode> open_house_timecode(const MasterOptions& options, const show::Show* show);

}  // namespace zenith::cluster
