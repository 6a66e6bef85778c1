#include "show/timecode/audio_file.h"

#include <fmt/format.h>
#include <sndfile.h>
#include <unistd.h>

#include <cmath>
#include <memory>
#include <stdexcept>

namespace zenith::show {

namespace {

struct CloseFile {
  void operator()(SNDFILE* file) const { sf_close(file); }
};
using File = std::unique_ptr<SNDFILE, CloseFile>;

}  // namespace

AudioChannel read_audio_channel(const std::filesystem::path& path, int channel) {
  SF_INFO info{};
  File file(sf_open(path.c_str(), SFM_READ, &info));
  if (!file) throw std::runtime_error(fmt::format("{}: {}", path.string(), sf_strerror(nullptr)));
  if (channel < 0 || channel >= info.channels)
    throw std::invalid_argument(fmt::format("{}: channel {} asked for, the file has {} (0 to {})", path.string(),
                                            channel, info.channels, info.channels - 1));
  AudioChannel out;
  out.sample_rate_hz = info.samplerate;
  out.channels = info.channels;
  out.samples.reserve(static_cast<std::size_t>(info.frames));
  std::vector<float> block(static_cast<std::size_t>(4096 * info.channels));
  for (;;) {
    const sf_count_t frames = sf_readf_float(file.get(), block.data(), 4096);
    if (frames <= 0) break;
    for (sf_count_t i = 0; i < frames; ++i)
      out.samples.push_back(block[static_cast<std::size_t>(i * info.channels + channel)]);
  }
  if (sf_error(file.get()) != SF_ERR_NO_ERROR)
    throw std::runtime_error(fmt::format("{}: {}", path.string(), sf_strerror(file.get())));
  return out;
}

void write_wav(const std::filesystem::path& path, std::span<const float> samples, double sample_rate_hz) {
  if (!(sample_rate_hz >= 8000.0 && sample_rate_hz <= 192000.0))
    throw std::runtime_error(
        fmt::format("{}: sample rate {} Hz outside [8000, 192000]", path.string(), sample_rate_hz));
  const std::filesystem::path temporary = path.string() + fmt::format(".{}.tmp", ::getpid());
  SF_INFO info{};
  info.samplerate = static_cast<int>(std::lround(sample_rate_hz));
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  {
    File file(sf_open(temporary.c_str(), SFM_WRITE, &info));
    if (!file) throw std::runtime_error(fmt::format("{}: {}", path.string(), sf_strerror(nullptr)));
    sf_command(file.get(), SFC_SET_CLIPPING, nullptr, SF_TRUE);
    const auto count = static_cast<sf_count_t>(samples.size());
    if (sf_writef_float(file.get(), samples.data(), count) != count) {
      const std::string problem = sf_strerror(file.get());
      file.reset();
      std::filesystem::remove(temporary);
      throw std::runtime_error(fmt::format("{}: {}", path.string(), problem));
    }
  }
  std::filesystem::rename(temporary, path);
}

}  // namespace zenith::show
