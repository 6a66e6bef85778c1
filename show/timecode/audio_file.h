#pragma once
// Audio files for timecode: one channel of a WAV (or any format libsndfile
// reads: AIFF, FLAC, …) as floats, and LTC written to a WAV for a show's
// soundtrack or a test. libsndfile (in Debian) does the formats.
#include <filesystem>
#include <span>
#include <vector>

namespace zenith::show {

struct AudioChannel {
  double sample_rate_hz = 0.0;
  int channels = 0;            ///< in the file
  std::vector<float> samples;  ///< the chosen channel, full scale ±1
};

/// Channel `channel` (0 the first) of the audio file `path`. Throws
/// std::runtime_error starting "<path>: " for a missing or unreadable file,
/// std::invalid_argument naming the file and its channel count for a channel
/// it does not have.
AudioChannel read_audio_channel(const std::filesystem::path& path, int channel = 0);

/// Writes mono `samples` (full scale ±1, clipped) as a 16-bit PCM WAV,
/// atomically (a temporary name, then renamed). Throws std::runtime_error
/// starting "<path>: ".
void write_wav(const std::filesystem::path& path, std::span<const float> samples, double sample_rate_hz);

}  // namespace zenith::show
