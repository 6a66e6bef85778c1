#pragma once
// Where a live chase (show/timecode/timecode_chase.h) gets its frames, read
// on a thread of its own, each stamped on std::chrono::steady_clock (seconds
// since its epoch, as TimecodeEvent::local_s) when its frame began. Three
// sources: LTC from an ALSA capture device (the audio interface's input that
// the house's timecode is patched into), LTC from an audio file played in
// real time from the moment the source starts (a rehearsal against the
// soundtrack's LTC track, the tests), and MIDI timecode from an ALSA raw MIDI
// port (show/timecode/mtc_decoder.h).
//
// Frames of another rate than the show's (LTC: measured from the frames'
// length, and the drop-frame flag; MTC: the rate it names) are dropped with
// one warning naming both rates: the chase then holds the show instead of
// running it at the wrong speed.
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "show/timecode/timecode_chase.h"

namespace zenith::show {

class TimecodeSource {
 public:
  virtual ~TimecodeSource() = default;
  /// The frames read since the last call, in order (from any thread).
  virtual std::vector<TimecodeEvent> take() = 0;
  /// "LTC from show.wav (channel 1, 48000 Hz)", for logs and the status.
  virtual std::string describe() const = 0;
};

/// LTC of channel `channel` of the audio file `path`, played in real time as
/// if its first sample sounded at `first_sample_at` (now where unset; in the
/// past, the file plays on from where it would be); the file ends in silence
/// (the chase freewheels, then holds or stops). Two masters given the same
/// instant chase one rehearsal, as they would one house's timecode. Throws
/// what read_audio_channel throws.
std::unique_ptr<TimecodeSource> ltc_file_source(
    const std::filesystem::path& path, int channel, TimecodeRate rate,
    std::optional<std::chrono::system_clock::time_point> first_sample_at = std::nullopt);

/// LTC of channel `channel` of the ALSA capture device `device` ("hw:1,0",
/// "default"). Throws std::runtime_error naming the device and ALSA's reason
/// where it cannot be opened.
std::unique_ptr<TimecodeSource> ltc_capture_source(const std::string& device, int channel, TimecodeRate rate);

/// MIDI timecode from the ALSA raw MIDI port `device` ("hw:1,0,0"; `amidi -l`
/// lists them). Throws std::runtime_error naming the port and ALSA's reason
/// where it cannot be opened.
std::unique_ptr<TimecodeSource> mtc_midi_source(const std::string& device, TimecodeRate rate);

}  // namespace zenith::show
