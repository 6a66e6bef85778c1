#pragma once
// SMPTE linear timecode (LTC, SMPTE ST 12-1): timecode as an audio signal,
// 80 bits a frame in biphase-mark code, what show-control systems and audio
// playback send down a spare channel. Decoded and encoded by libltc
// (x42/libltc, in Debian), which tracks the signal's speed from frame to
// frame; these wrap it in zenith's types.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "show/timecode/timecode.h"

namespace zenith::show {

/// One decoded LTC frame.
struct LtcFrame {
  Timecode timecode;
  bool drop_frame = false;  ///< the frame's drop-frame flag (29.97 drop-frame)
  bool reverse = false;     ///< read backwards (the audio played in reverse)
  /// The samples of the stream (counted from the first sample given) where
  /// the frame's first and last bit were: its first bit's start marks the
  /// frame's time (SMPTE ST 12-1's reference, within a bit).
  std::int64_t first_sample = 0, last_sample = 0;
  double volume_dbfs = 0.0;  ///< the signal's peak level over the frame
};

class LtcDecoder {
 public:
  /// For audio at `sample_rate_hz`; `fps_hint` sets libltc's first guess of
  /// the samples per frame (it then follows the signal's own speed).
  explicit LtcDecoder(double sample_rate_hz, double fps_hint = 25.0);
  ~LtcDecoder();
  LtcDecoder(const LtcDecoder&) = delete;
  LtcDecoder& operator=(const LtcDecoder&) = delete;

  /// Feeds the stream's next mono samples (full scale ±1); returns the frames
  /// they completed, in order.
  std::vector<LtcFrame> decode(std::span<const float> samples);
  double sample_rate_hz() const { return sample_rate_hz_; }
  /// Samples fed so far.
  std::int64_t position() const { return position_; }

 private:
  struct Handle;
  std::unique_ptr<Handle> handle_;
  double sample_rate_hz_;
  std::int64_t position_ = 0;
};

/// An LTC signal to write: `frames` frames from `start` at `rate`, at
/// `speed` × real time (1.001: the timecode runs 0.1 % fast against the
/// samples), `level_dbfs` peak.
struct LtcSignal {
  Timecode start;
  TimecodeRate rate = TimecodeRate::fps25;
  std::int64_t frames = 0;
  double sample_rate_hz = 48000.0;
  double speed = 1.0;
  double level_dbfs = -18.0;
};
/// The signal's mono samples (full scale ±1). Throws std::invalid_argument for
/// a start that is not a label of the rate, a sample rate outside [8000, 192000] Hz,
/// a speed outside [0.5, 2] or a level outside [−60, 0] dBFS.
std::vector<float> encode_ltc(const LtcSignal& signal);

}  // namespace zenith::show
