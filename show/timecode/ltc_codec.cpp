#include "show/timecode/ltc_codec.h"

#include <fmt/format.h>
#include <ltc.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace zenith::show {

namespace {

/// libltc's TV standard for a rate: where its binary-group flag bits sit.
LTC_TV_STANDARD tv_standard(TimecodeRate rate) {
  switch (rate) {
    case TimecodeRate::fps24: return LTC_TV_FILM_24;
    case TimecodeRate::fps25: return LTC_TV_625_50;
    case TimecodeRate::fps29_97_drop:
    case TimecodeRate::fps30: return LTC_TV_525_60;
  }
  return LTC_TV_525_60;
}

}  // namespace

struct LtcDecoder::Handle {
  LTCDecoder* decoder = nullptr;
  ~Handle() {
    if (decoder != nullptr) ltc_decoder_free(decoder);
  }
};

LtcDecoder::LtcDecoder(double sample_rate_hz, double fps_hint)
    : handle_(std::make_unique<Handle>()), sample_rate_hz_(sample_rate_hz) {
  if (!(sample_rate_hz >= 8000.0 && sample_rate_hz <= 192000.0))
    throw std::invalid_argument(fmt::format("LTC: sample rate {} Hz outside [8000, 192000]", sample_rate_hz));
  if (!(fps_hint >= 20.0 && fps_hint <= 35.0))
    throw std::invalid_argument(fmt::format("LTC: frame rate hint {} outside [20, 35] fps", fps_hint));
  // 32 frames of queue: a second of the fastest rate between two reads.
  handle_->decoder = ltc_decoder_create(static_cast<int>(std::lround(sample_rate_hz / fps_hint)), 32);
  if (handle_->decoder == nullptr) throw std::runtime_error("LTC: libltc could not create a decoder");
}

LtcDecoder::~LtcDecoder() = default;

std::vector<LtcFrame> LtcDecoder::decode(std::span<const float> samples) {
  std::vector<LtcFrame> out;
  // libltc takes a mutable buffer (it only reads it): copied in chunks.
  std::array<float, 1024> chunk{};
  for (std::size_t at = 0; at < samples.size(); at += chunk.size()) {
    const std::size_t n = std::min(chunk.size(), samples.size() - at);
    std::copy_n(samples.begin() + static_cast<std::ptrdiff_t>(at), n, chunk.begin());
    ltc_decoder_write_float(handle_->decoder, chunk.data(), n, position_);
    position_ += static_cast<std::int64_t>(n);
    LTCFrameExt frame{};
    while (ltc_decoder_read(handle_->decoder, &frame) > 0) {
      SMPTETimecode t{};
      ltc_frame_to_time(&t, &frame.ltc, 0);
      LtcFrame& f = out.emplace_back();
      f.timecode = {t.hours, t.mins, t.secs, t.frame};
      f.drop_frame = frame.ltc.dfbit != 0;
      f.reverse = frame.reverse != 0;
      f.first_sample = frame.off_start;
      f.last_sample = frame.off_end;
      f.volume_dbfs = frame.volume;
    }
  }
  return out;
}

std::vector<float> encode_ltc(const LtcSignal& s) {
  if (!valid_timecode(s.start, s.rate))
    throw std::invalid_argument(
        fmt::format("LTC: start {} is not a label at {} fps", format_timecode(s.start, s.rate), to_string(s.rate)));
  if (!(s.sample_rate_hz >= 8000.0 && s.sample_rate_hz <= 192000.0))
    throw std::invalid_argument(fmt::format("LTC: sample rate {} Hz outside [8000, 192000]", s.sample_rate_hz));
  if (!(s.speed >= 0.5 && s.speed <= 2.0))
    throw std::invalid_argument(fmt::format("LTC: speed {} outside [0.5, 2]", s.speed));
  if (!(s.level_dbfs >= -60.0 && s.level_dbfs <= 0.0))
    throw std::invalid_argument(fmt::format("LTC: level {} dBFS outside [-60, 0]", s.level_dbfs));
  // A signal `speed` times as fast: each frame in 1/speed of its samples,
  // i.e. encoded as for a sample rate of sample_rate / speed.
  LTCEncoder* encoder =
      ltc_encoder_create(s.sample_rate_hz / s.speed, frames_per_second(s.rate), tv_standard(s.rate), 0);
  if (encoder == nullptr) throw std::runtime_error("LTC: libltc could not create an encoder");
  ltc_encoder_set_volume(encoder, s.level_dbfs);
  SMPTETimecode t{};
  t.hours = static_cast<unsigned char>(s.start.hours);
  t.mins = static_cast<unsigned char>(s.start.minutes);
  t.secs = static_cast<unsigned char>(s.start.seconds);
  t.frame = static_cast<unsigned char>(s.start.frames);
  ltc_encoder_set_timecode(encoder, &t);
  std::vector<float> samples;
  samples.reserve(static_cast<std::size_t>(static_cast<double>(s.frames) * s.sample_rate_hz /
                                           (frames_per_second(s.rate) * s.speed)) +
                  64);
  for (std::int64_t f = 0; f < s.frames; ++f) {
    ltc_encoder_encode_frame(encoder);
    ltcsnd_sample_t* buffer = nullptr;
    const int n = ltc_encoder_get_bufferptr(encoder, &buffer, 1);
    for (int i = 0; i < n; ++i) samples.push_back((static_cast<float>(buffer[i]) - 128.0f) / 127.0f);
    ltc_encoder_inc_timecode(encoder);
  }
  ltc_encoder_free(encoder);
  return samples;
}

}  // namespace zenith::show
