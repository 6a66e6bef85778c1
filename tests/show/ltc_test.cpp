// LTC through libltc (show/timecode/ltc_codec.h) and WAV files
// (show/timecode/audio_file.h): what the encoder writes the decoder reads
// back, frame for frame and sample for sample, at every rate.
#include "show/timecode/ltc_codec.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>

#include "show/timecode/audio_file.h"
#include "show/timecode/timecode_source.h"

namespace zenith::show {
namespace {

constexpr TimecodeRate kRates[] = {TimecodeRate::fps24, TimecodeRate::fps25, TimecodeRate::fps29_97_drop,
                                   TimecodeRate::fps30};

/// Every rate: 100 frames across a minute's turn (drop-frame: across its skipped labels) read back in
/// order, the drop-frame flag where it belongs, each frame where the encoder put it.
TEST(Ltc, EveryRateReadsBackFrameForFrame) {
  for (const TimecodeRate rate : kRates) {
    LtcSignal signal;
    signal.start = {0, 0, 58, 0};
    signal.rate = rate;
    signal.frames = 100;
    const std::vector<float> samples = encode_ltc(signal);
    const double samples_per_frame = signal.sample_rate_hz / frames_per_second(rate);
    EXPECT_NEAR(static_cast<double>(samples.size()), 100 * samples_per_frame, 2.0) << to_string(rate);
    LtcDecoder decoder(signal.sample_rate_hz, frames_per_second(rate));
    const std::vector<LtcFrame> frames = decoder.decode(samples);
    // libltc needs the first frame to find the signal's speed: it reads from the second.
    ASSERT_GE(frames.size(), 98u) << to_string(rate);
    const std::int64_t first = frame_index(signal.start, rate);
    for (const LtcFrame& f : frames) {
      const std::int64_t k = frame_index(f.timecode, rate) - first;
      ASSERT_GE(k, 0) << format_timecode(f.timecode, rate);
      EXPECT_EQ(f.drop_frame, rate == TimecodeRate::fps29_97_drop);
      EXPECT_FALSE(f.reverse);
      // Within two samples of where frame k starts.
      EXPECT_NEAR(static_cast<double>(f.first_sample), static_cast<double>(k) * samples_per_frame, 2.0)
          << to_string(rate) << " " << format_timecode(f.timecode, rate);
      EXPECT_NEAR(f.volume_dbfs, -18.0, 1.0);
    }
    // The last frame ends on an edge only the next frame's first bit makes: without it, it is not read.
    EXPECT_EQ(frames.back().timecode, timecode_at(first + 98, rate)) << to_string(rate);
  }
}

TEST(Ltc, AWavFileCarriesItAtSixteenBits) {
  LtcSignal signal;
  signal.start = {10, 0, 0, 0};
  signal.rate = TimecodeRate::fps30;
  signal.frames = 60;
  signal.sample_rate_hz = 44100.0;
  const std::filesystem::path wav =
      std::filesystem::temp_directory_path() / ("zenith-ltc-" + std::to_string(getpid()) + ".wav");
  write_wav(wav, encode_ltc(signal), signal.sample_rate_hz);
  const AudioChannel audio = read_audio_channel(wav);
  EXPECT_EQ(audio.sample_rate_hz, 44100.0);
  EXPECT_EQ(audio.channels, 1);
  LtcDecoder decoder(audio.sample_rate_hz, 30.0);
  const std::vector<LtcFrame> frames = decoder.decode(audio.samples);
  ASSERT_GE(frames.size(), 58u);
  EXPECT_EQ(frames.back().timecode, (Timecode{10, 0, 1, 28}));  // the last frame's end is the next one's start
  EXPECT_THROW(read_audio_channel(wav, 1), std::invalid_argument);
  std::filesystem::remove(wav);
  try {
    read_audio_channel(wav);
    ADD_FAILURE() << "a missing file was read";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(wav.string() + ": ", 0), 0u) << e.what();
  }
}

TEST(Ltc, ASignalBadlyAskedForIsRefusedByName) {
  LtcSignal signal;
  signal.frames = 1;
  signal.start = {0, 0, 0, 25};
  EXPECT_THROW(encode_ltc(signal), std::invalid_argument);
  signal.start = {};
  signal.speed = 3.0;
  EXPECT_THROW(encode_ltc(signal), std::invalid_argument);
  signal.speed = 1.0;
  signal.sample_rate_hz = 1000.0;
  EXPECT_THROW(encode_ltc(signal), std::invalid_argument);
  EXPECT_THROW(LtcDecoder(48000.0, 60.0), std::invalid_argument);
}

/// Noise is no timecode: nothing decoded.
TEST(Ltc, NoiseIsNotTimecode) {
  std::vector<float> noise(48000);
  std::uint32_t state = 12345;
  for (float& x : noise) {
    state = state * 1664525u + 1013904223u;
    x = static_cast<float>(state >> 8) / static_cast<float>(1u << 24) - 0.5f;
  }
  LtcDecoder decoder(48000.0);
  EXPECT_TRUE(decoder.decode(noise).empty());
}

/// A device that is not there is named with ALSA's reason (no sound card needed to check it).
TEST(TimecodeSources, AnAbsentDeviceIsNamed) {
  const auto message = [](const std::function<void()>& open) {
    try {
      open();
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(
      message([] { ltc_capture_source("hw:97,0", 0, TimecodeRate::fps25); }).find("ALSA capture device 'hw:97,0': "),
      std::string::npos);
  EXPECT_NE(message([] { mtc_midi_source("hw:97,0,0", TimecodeRate::fps25); }).find("ALSA MIDI port 'hw:97,0,0': "),
            std::string::npos);
  EXPECT_THROW(ltc_capture_source("default", 64, TimecodeRate::fps25), std::invalid_argument);
}

/// The ALSA capture path itself, without a sound card: ALSA's own `file`
/// plugin (alsa-lib, user space) plays a raw capture stream from a file, as
/// a card's input would deliver it — two channels of 32-bit float at 48 kHz,
/// a tone on the first and the house's LTC on the second. The plugin delivers
/// it as fast as it is read (no card clock), so this checks the device's
/// opening, its format, the channel's extraction and the decoding, not the
/// frames' timing (the WAV source's tests check that).
TEST(TimecodeSources, AnAlsaCaptureDeviceDeliversTheLtcOfItsChannel) {
  const std::filesystem::path alsa_conf = "/usr/share/alsa/alsa.conf";
  if (!std::filesystem::exists(alsa_conf)) GTEST_SKIP() << alsa_conf << " is missing (libasound2-data)";
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("zenith-alsa-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  LtcSignal signal;
  signal.start = {10, 0, 0, 0};
  signal.frames = 50;
  const std::vector<float> ltc = encode_ltc(signal);
  {
    std::vector<float> interleaved;
    for (std::size_t i = 0; i < ltc.size(); ++i) {
      interleaved.push_back(0.5f *
                            static_cast<float>(std::sin(2.0 * M_PI * 1000.0 * static_cast<double>(i) / 48000.0)));
      interleaved.push_back(ltc[i]);
    }
    std::ofstream raw(dir / "capture.raw", std::ios::binary);
    raw.write(reinterpret_cast<const char*>(interleaved.data()),
              static_cast<std::streamsize>(interleaved.size() * sizeof(float)));
    std::ofstream conf(dir / "asound.conf");
    conf << "<" << alsa_conf.string() << ">\n"
         << "pcm.zenith_ltc_test { type file slave.pcm \"null\" file \"/dev/null\" infile \""
         << (dir / "capture.raw").string() << "\" format \"raw\" }\n";
  }
  ::setenv("ALSA_CONFIG_PATH", (dir / "asound.conf").c_str(), 1);
  std::vector<TimecodeEvent> events;
  {
    const std::unique_ptr<TimecodeSource> source = ltc_capture_source("zenith_ltc_test", 1, TimecodeRate::fps25);
    EXPECT_EQ(source->describe(), "LTC from ALSA 'zenith_ltc_test' (channel 1, 48000 Hz)");
    for (int i = 0; i < 500 && events.size() < 49; ++i) {
      for (const TimecodeEvent& e : source->take()) events.push_back(e);
      usleep(10000);
    }
  }
  ::unsetenv("ALSA_CONFIG_PATH");
  std::filesystem::remove_all(dir);
  // Every frame in order from the first or second (libltc may need the first to find the signal's speed).
  ASSERT_GE(events.size(), 49u);
  const std::int64_t first = frame_index(signal.start, TimecodeRate::fps25);
  const std::int64_t skipped = frame_index(events[0].timecode, TimecodeRate::fps25) - first;
  EXPECT_TRUE(skipped == 0 || skipped == 1) << skipped;
  for (std::size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i].timecode, timecode_at(first + skipped + static_cast<std::int64_t>(i), TimecodeRate::fps25))
        << i;
    EXPECT_EQ(events[i].rate, TimecodeRate::fps25);
  }
}

}  // namespace
}  // namespace zenith::show
