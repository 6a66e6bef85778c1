#include "show/timecode/mtc_decoder.h"

namespace zenith::show {

namespace {

/// The rate of MTC's two rate bits.
TimecodeRate mtc_rate(int bits) {
  switch (bits & 3) {
    case 0: return TimecodeRate::fps24;
    case 1: return TimecodeRate::fps25;
    case 2: return TimecodeRate::fps29_97_drop;
    default: return TimecodeRate::fps30;
  }
}

/// A full-frame SysEx's length: F0 7F <device> 01 01 hh mm ss ff F7.
constexpr std::size_t kFullFrameBytes = 10;

}  // namespace

std::vector<TimecodeEvent> MtcDecoder::decode(std::span<const std::uint8_t> bytes, double local_s) {
  std::vector<TimecodeEvent> out;
  for (const std::uint8_t b : bytes) {
    if (b >= 0xF8) continue;  // real-time messages (clock, start, stop, active sensing) may come between any bytes
    if (in_sysex_) {
      if (b == 0xF7) {
        sysex_.push_back(b);
        in_sysex_ = false;
        full_frame(local_s, out);
        continue;
      }
      if (b < 0x80) {
        if (sysex_.size() < 64) sysex_.push_back(b);
        continue;
      }
      in_sysex_ = false;  // a status byte ends an unterminated SysEx: handled below
    }
    if (b == 0xF0) {
      in_sysex_ = true;
      sysex_.assign(1, b);
      expecting_quarter_frame_ = false;
    } else if (b == 0xF1) {
      expecting_quarter_frame_ = true;
    } else if (b < 0x80) {
      if (expecting_quarter_frame_) quarter_frame(b, local_s, out);
      expecting_quarter_frame_ = false;  // any other message's data bytes are skipped
    } else {
      expecting_quarter_frame_ = false;
    }
  }
  return out;
}

void MtcDecoder::quarter_frame(std::uint8_t data, double local_s, std::vector<TimecodeEvent>& out) {
  const int piece = data >> 4;
  if (direction_ == Direction::none || piece != next_piece_) {
    // An assembly broken off, counted once. A lone first piece is not counted:
    // after a lost byte, the forward label's piece 7 starts a backward label
    // that the next piece 0 breaks at once.
    if (pieces_ >= 2) ++restarts_;
    // A label starts at piece 0 going forward, at piece 7 going backward; other pieces wait for one.
    direction_ = piece == 0 ? Direction::forward : piece == 7 ? Direction::backward : Direction::none;
    pieces_ = 0;
    if (direction_ == Direction::none) return;
  }
  ++pieces_;
  const bool forward = direction_ == Direction::forward;
  nibbles_[piece] = data & 0x0F;
  if (piece == (forward ? 0 : 7)) first_half_s_ = local_s;
  if (piece == (forward ? 4 : 3)) second_half_s_ = local_s;
  next_piece_ = forward ? piece + 1 : piece - 1;
  if (piece != (forward ? 7 : 0)) return;
  direction_ = Direction::none;  // the next label starts afresh, in either direction
  pieces_ = 0;
  const TimecodeRate rate = mtc_rate(nibbles_[7] >> 1);
  const Timecode tc{(nibbles_[7] & 1) << 4 | nibbles_[6], nibbles_[5] << 4 | nibbles_[4],
                    nibbles_[3] << 4 | nibbles_[2], nibbles_[1] << 4 | nibbles_[0]};
  if (!valid_timecode(tc, rate)) {
    ++restarts_;
    return;
  }
  ++labels_;
  // Forward, piece 0 was sent as the label's frame began and piece 4 as the
  // next one did; backward, piece 7 at the label and piece 3 a frame below it.
  const std::int64_t index = frame_index(tc, rate);
  out.push_back({tc, rate, first_half_s_});
  out.push_back({timecode_at(index + (forward ? 1 : -1), rate), rate, second_half_s_});
}

void MtcDecoder::full_frame(double local_s, std::vector<TimecodeEvent>& out) {
  // F0 7F <device> 01 01 hr mn sc fr F7, hr = 0rrhhhhh.
  if (sysex_.size() != kFullFrameBytes || sysex_[1] != 0x7F || sysex_[3] != 0x01 || sysex_[4] != 0x01) return;
  const TimecodeRate rate = mtc_rate(sysex_[5] >> 5);
  const Timecode tc{sysex_[5] & 0x1F, sysex_[6] & 0x3F, sysex_[7] & 0x3F, sysex_[8] & 0x1F};
  direction_ = Direction::none;  // quarter frames start again from the located frame
  pieces_ = 0;
  if (!valid_timecode(tc, rate)) {
    ++restarts_;
    return;
  }
  ++labels_;
  out.push_back({tc, rate, local_s});
}

}  // namespace zenith::show
