#pragma once
// MIDI timecode (MTC, MIDI 1.0 detailed specification, "MIDI Time Code"):
// timecode in MIDI messages, what show-control PCs send to the devices that
// chase them. While the timecode runs, quarter-frame messages (F1 0nnn dddd),
// four a frame, each carry a nibble of the label; the eight of two frames
// make one label — that of the frame at which the first of them (piece 0)
// was sent, so the label is known a frame and three quarters after its frame
// began. A locate (or a stopped transport) sends a full-frame message
// (F0 7F 7F 01 01 hh mm ss ff F7). Both carry the rate: 24, 25, 29.97
// drop-frame or 30.
//
// The decoder takes the bytes of a MIDI input as they arrive, with their
// arrival time, and returns timecode frames with the time each began: for
// eight quarter frames, the label at piece 0's arrival and the next label at
// piece 4's; for a full frame, its label at its arrival. Everything else of
// the stream — notes, controllers, clock, other SysEx — is skipped.
// Quarter frames out of order (a dropped byte, the transport running
// backwards) restart the assembly: no label is made of pieces of two.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "show/timecode/timecode_chase.h"

namespace zenith::show {

class MtcDecoder {
 public:
  /// The bytes of the stream that arrived at `local_s` (in order); the frames they completed.
  std::vector<TimecodeEvent> decode(std::span<const std::uint8_t> bytes, double local_s);

  /// Labels made (quarter-frame pairs and full frames), and labels broken off
  /// by a piece out of order after two or more of theirs had arrived.
  int labels() const { return labels_; }
  int restarts() const { return restarts_; }

 private:
  void quarter_frame(std::uint8_t data, double local_s, std::vector<TimecodeEvent>& out);
  void full_frame(double local_s, std::vector<TimecodeEvent>& out);

  enum class Direction { none, forward, backward };
  // Quarter frames: the label's direction and next piece, the nibbles so far,
  // when the pieces that begin its two frames arrived (forward 0 and 4, backward 7 and 3).
  Direction direction_ = Direction::none;
  int next_piece_ = 0, pieces_ = 0;
  std::uint8_t nibbles_[8] = {};
  double first_half_s_ = 0.0, second_half_s_ = 0.0;
  // The stream: a system exclusive message being read, the data bytes of another message to skip.
  bool in_sysex_ = false;
  std::vector<std::uint8_t> sysex_;
  bool expecting_quarter_frame_ = false;
  int labels_ = 0, restarts_ = 0;
};

}  // namespace zenith::show
