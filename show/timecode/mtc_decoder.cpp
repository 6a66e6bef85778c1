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
  if (piece != next_piece_) {
    if (next_piece_ != 0) ++restarts_;  // an assembly broken off (counted once, not per piece while waiting)
    next_piece_ = 0;
    if (piece != 0) return;  // wait for the next piece 0
  }
  nibbles_[piece] = data & 0x0F;
  if (piece == 0) piece0_s_ = local_s;
  if (piece == 4) piece4_s_ = local_s;
  next_piece_ = (piece + 1) % 8;
  if (piece != 7) return;
  const TimecodeRate rate = mtc_rate(nibbles_[7] >> 1);
  const Timecode tc{(nibbles_[7] & 1) << 4 | nibbles_[6], nibbles_[5] << 4 | nibbles_[4],
                    nibbles_[3] << 4 | nibbles_[2], nibbles_[1] << 4 | nibbles_[0]};
  if (!valid_timecode(tc, rate)) {
    ++restarts_;
    return;
  }
  ++labels_;
  // Piece 0 was sent as the label's frame began, piece 4 as the next one did.
  const std::int64_t index = frame_index(tc, rate);
  out.push_back({tc, rate, piece0_s_});
  out.push_back({timecode_at(index + 1, rate), rate, piece4_s_});
}

void MtcDecoder::full_frame(double local_s, std::vector<TimecodeEvent>& out) {
  // F0 7F <device> 01 01 hr mn sc fr F7, hr = 0rrhhhhh.
  if (sysex_.size() != kFullFrameBytes || sysex_[1] != 0x7F || sysex_[3] != 0x01 || sysex_[4] != 0x01) return;
  const TimecodeRate rate = mtc_rate(sysex_[5] >> 5);
  const Timecode tc{sysex_[5] & 0x1F, sysex_[6] & 0x3F, sysex_[7] & 0x3F, sysex_[8] & 0x1F};
  next_piece_ = 0;  // quarter frames start again from the located frame
  if (!valid_timecode(tc, rate)) {
    ++restarts_;
    return;
  }
  ++labels_;
  out.push_back({tc, rate, local_s});
}

}  // namespace zenith::show
