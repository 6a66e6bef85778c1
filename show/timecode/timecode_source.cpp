#include "show/timecode/timecode_source.h"

#include <alsa/asoundlib.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <poll.h>
#include <algorithm>

#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <span>
#include <stdexcept>
#include <thread>
#include <utility>

#include "show/timecode/audio_file.h"
#include "show/timecode/ltc_codec.h"
#include "show/timecode/mtc_decoder.h"

namespace zenith::show {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_of(Clock::time_point t) { return std::chrono::duration<double>(t.time_since_epoch()).count(); }

/// Frames of the show's rate from a reading thread to the master's, and the
/// one warning for a timecode of another rate.
class FrameQueue {
 public:
  FrameQueue(TimecodeRate rate, std::string name) : rate_(rate), name_(std::move(name)) {}
  TimecodeRate rate() const { return rate_; }
  const std::string& name() const { return name_; }

  void push(const TimecodeEvent& e) {
    std::lock_guard lock(mutex_);
    events_.push_back(e);
  }
  /// A frame of another rate (`found`: "30 fps", "24.98 fps drop-frame"): dropped, warned of once.
  void refuse(const std::string& found) {
    if (!warned_)
      spdlog::warn(
          "{}: the timecode runs at {}, the show's is {} fps: its frames are ignored and the show holds "
          "(the show file's \"timecode\": \"rate\", or the house's timecode)",
          name_, found, to_string(rate_));
    warned_ = true;
  }
  std::vector<TimecodeEvent> take() {
    std::lock_guard lock(mutex_);
    return std::exchange(events_, {});
  }

 private:
  TimecodeRate rate_;
  std::string name_;
  bool warned_ = false;  ///< touched by the reading thread only
  std::mutex mutex_;
  std::vector<TimecodeEvent> events_;
};

/// LTC samples in, frames of the show's rate out (the two LTC sources'),
/// stamped from the stream's first sample's local time.
class LtcStream {
 public:
  LtcStream(double sample_rate_hz, TimecodeRate rate, std::string name)
      : decoder_(sample_rate_hz, frames_per_second(rate)), frames_(rate, std::move(name)) {}

  /// Decodes `samples`, the stream's next, of which the first sounded at `first_local_s`.
  void decode(std::span<const float> samples, double first_local_s) {
    const std::int64_t first = decoder_.position();
    for (const LtcFrame& f : decoder_.decode(samples)) {
      const double length = static_cast<double>(f.last_sample - f.first_sample + 1);
      const double fps = decoder_.sample_rate_hz() / length;
      const TimecodeRate rate = frames_.rate();
      if (std::abs(fps / frames_per_second(rate) - 1.0) > 0.02 ||
          f.drop_frame != (rate == TimecodeRate::fps29_97_drop)) {
        frames_.refuse(fmt::format("{:.2f} fps{}", fps, f.drop_frame ? " drop-frame" : ""));
        continue;
      }
      frames_.push(
          {f.timecode, rate, first_local_s + static_cast<double>(f.first_sample - first) / decoder_.sample_rate_hz()});
    }
  }
  std::vector<TimecodeEvent> take() { return frames_.take(); }
  const std::string& name() const { return frames_.name(); }

 private:
  LtcDecoder decoder_;
  FrameQueue frames_;
};

class FileSource final : public TimecodeSource {
 public:
  FileSource(const std::filesystem::path& path, int channel, TimecodeRate rate, Clock::time_point first_sample)
      : audio_(read_audio_channel(path, channel)),
        stream_(audio_.sample_rate_hz, rate,
                fmt::format("LTC from {} (channel {}, {} Hz)", path.string(), channel, audio_.sample_rate_hz)),
        first_sample_(first_sample),
        thread_([this] { play(); }) {}
  ~FileSource() override {
    stop_ = true;
    thread_.join();
  }
  std::vector<TimecodeEvent> take() override { return stream_.take(); }
  std::string describe() const override { return stream_.name(); }

 private:
  /// The file as a live input: 10 ms blocks, each decoded once its last
  /// sample has sounded; a file that started sounding earlier from a second
  /// before now (the decoder's time to find the frames again).
  void play() {
    const Clock::time_point start = first_sample_;
    const double rate = audio_.sample_rate_hz;
    const auto block = static_cast<std::size_t>(rate / 100.0);
    const double late_s = std::chrono::duration<double>(Clock::now() - start).count() - 1.0;
    const std::size_t first_block = late_s > 0.0 ? static_cast<std::size_t>(late_s * rate) / block : 0;
    for (std::size_t at = first_block * block; at < audio_.samples.size() && !stop_; at += block) {
      const std::size_t n = std::min(block, audio_.samples.size() - at);
      std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(
                                                std::chrono::duration<double>(static_cast<double>(at + n) / rate)));
      stream_.decode(std::span<const float>(audio_.samples).subspan(at, n),
                     seconds_of(start) + static_cast<double>(at) / rate);
    }
  }

  AudioChannel audio_;
  LtcStream stream_;
  Clock::time_point first_sample_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

class CaptureSource final : public TimecodeSource {
 public:
  CaptureSource(const std::string& device, int channel, TimecodeRate rate)
      : channel_(static_cast<std::size_t>(channel)) {
    int err = snd_pcm_open(&pcm_, device.c_str(), SND_PCM_STREAM_CAPTURE, 0);
    if (err < 0) throw std::runtime_error(fmt::format("ALSA capture device '{}': {}", device, snd_strerror(err)));
    unsigned int sample_rate = 48000;
    channels_ = static_cast<unsigned int>(channel) + 1;
    // 48 kHz float, as many channels as reach the LTC's; 20 ms of latency at most.
    err = snd_pcm_set_params(pcm_, SND_PCM_FORMAT_FLOAT_LE, SND_PCM_ACCESS_RW_INTERLEAVED, channels_, sample_rate, 1,
                             20000);
    if (err < 0) {
      snd_pcm_close(pcm_);
      throw std::runtime_error(fmt::format("ALSA capture device '{}': {} channels of 32-bit float at {} Hz: {}", device,
                                           channels_, sample_rate, snd_strerror(err)));
    }
    stream_ = std::make_unique<LtcStream>(
        sample_rate, rate, fmt::format("LTC from ALSA '{}' (channel {}, {} Hz)", device, channel, sample_rate));
    sample_rate_ = sample_rate;
    thread_ = std::thread([this] { capture(); });
  }
  ~CaptureSource() override {
    stop_ = true;
    thread_.join();
    snd_pcm_close(pcm_);
  }
  std::vector<TimecodeEvent> take() override { return stream_->take(); }
  std::string describe() const override { return stream_->name(); }

 private:
  void capture() {
    const snd_pcm_uframes_t block = sample_rate_ / 100;
    std::vector<float> interleaved(block * channels_), mono(block);
    while (!stop_) {
      const snd_pcm_sframes_t got = snd_pcm_readi(pcm_, interleaved.data(), block);
      const Clock::time_point now = Clock::now();
      if (got < 0) {
        if (snd_pcm_recover(pcm_, static_cast<int>(got), 1) < 0) {
          spdlog::error("{}: {}; timecode input stopped", stream_->name(), snd_strerror(static_cast<int>(got)));
          return;
        }
        continue;
      }
      snd_pcm_sframes_t delay = 0;  // frames captured but not yet read: the block's end sounded that long ago
      if (snd_pcm_delay(pcm_, &delay) < 0) delay = 0;
      for (snd_pcm_sframes_t i = 0; i < got; ++i)
        mono[static_cast<std::size_t>(i)] = interleaved[static_cast<std::size_t>(i) * channels_ + channel_];
      const double first_s = seconds_of(now) - static_cast<double>(got + delay) / sample_rate_;
      stream_->decode(std::span<const float>(mono).first(static_cast<std::size_t>(got)), first_s);
    }
  }

  snd_pcm_t* pcm_ = nullptr;
  unsigned int channels_ = 1, sample_rate_ = 48000;
  std::size_t channel_ = 0;
  std::unique_ptr<LtcStream> stream_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

/// MTC from a raw MIDI port: bytes read as they arrive (polled every 100 ms for the stop), stamped on arrival.
class MidiSource final : public TimecodeSource {
 public:
  MidiSource(const std::string& device, TimecodeRate rate)
      : frames_(rate, fmt::format("MTC from ALSA MIDI '{}'", device)) {
    const int err = snd_rawmidi_open(&in_, nullptr, device.c_str(), SND_RAWMIDI_NONBLOCK);
    if (err < 0) throw std::runtime_error(fmt::format("ALSA MIDI port '{}': {}", device, snd_strerror(err)));
    thread_ = std::thread([this] { read(); });
  }
  ~MidiSource() override {
    stop_ = true;
    thread_.join();
    snd_rawmidi_close(in_);
  }
  std::vector<TimecodeEvent> take() override { return frames_.take(); }
  std::string describe() const override { return frames_.name(); }

 private:
  void read() {
    std::vector<pollfd> fds(static_cast<std::size_t>(std::max(1, snd_rawmidi_poll_descriptors_count(in_))));
    snd_rawmidi_poll_descriptors(in_, fds.data(), static_cast<unsigned int>(fds.size()));
    std::uint8_t buffer[256];
    while (!stop_) {
      if (::poll(fds.data(), fds.size(), 100) <= 0) continue;
      const ssize_t n = snd_rawmidi_read(in_, buffer, sizeof buffer);
      if (n == -EAGAIN) continue;
      if (n < 0) {
        spdlog::error("{}: {}; timecode input stopped", frames_.name(), snd_strerror(static_cast<int>(n)));
        return;
      }
      const double now = seconds_of(Clock::now());
      for (const TimecodeEvent& e :
           decoder_.decode(std::span<const std::uint8_t>(buffer, static_cast<std::size_t>(n)), now)) {
        if (e.rate != frames_.rate())
          frames_.refuse(fmt::format("{} fps", to_string(e.rate)));
        else
          frames_.push(e);
      }
    }
  }

  FrameQueue frames_;
  snd_rawmidi_t* in_ = nullptr;
  MtcDecoder decoder_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace

std::unique_ptr<TimecodeSource> mtc_midi_source(const std::string& device, TimecodeRate rate) {
  return std::make_unique<MidiSource>(device, rate);
}

std::unique_ptr<TimecodeSource> ltc_file_source(const std::filesystem::path& path, int channel, TimecodeRate rate,
                                                std::optional<std::chrono::system_clock::time_point> first_sample_at) {
  // The instant on the wall clock, on the steady clock the frames are stamped on.
  Clock::time_point first = Clock::now();
  if (first_sample_at)
    first += std::chrono::duration_cast<Clock::duration>(*first_sample_at - std::chrono::system_clock::now());
  return std::make_unique<FileSource>(path, channel, rate, first);
}

std::unique_ptr<TimecodeSource> ltc_capture_source(const std::string& device, int channel, TimecodeRate rate) {
  if (channel < 0 || channel > 63)
    throw std::invalid_argument(fmt::format("ALSA capture device '{}': channel {} outside [0, 63]", device, channel));
  return std::make_unique<CaptureSource>(device, channel, rate);
}

}  // namespace zenith::show
