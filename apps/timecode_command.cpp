// `zenith timecode write|read` (docs/shows.md, "Chasing timecode"): an LTC
// track written to a WAV (to rehearse a show against, or to lay on a
// soundtrack's spare channel), and an LTC track read back as a show's chase
// would read it — what an engineer runs to check the house's timecode before
// a show: its rate, whether it decodes, where it drops out or jumps, its drift.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "apps/commands.h"
#include "show/timecode/audio_file.h"
#include "show/timecode/ltc_codec.h"
#include "show/timecode/timecode_chase.h"

namespace zenith::app {
namespace {

struct WriteArgs {
  std::string out, start = "01:00:00:00", rate = "25";
  double seconds = 60.0, sample_rate_hz = 48000.0, speed = 1.0, level_dbfs = -18.0;
};

show::TimecodeRate rate_named(const std::string& name) {
  const std::optional<show::TimecodeRate> rate = show::parse_timecode_rate(name);
  if (!rate) throw std::invalid_argument(fmt::format("--rate {}: one of 24, 25, 29.97df, 30", name));
  return *rate;
}

void write_command(const WriteArgs& a) {
  show::LtcSignal signal;
  signal.rate = rate_named(a.rate);
  signal.start = show::parse_timecode(a.start, signal.rate);
  signal.sample_rate_hz = a.sample_rate_hz;
  signal.speed = a.speed;
  signal.level_dbfs = a.level_dbfs;
  signal.frames = static_cast<std::int64_t>(std::lround(a.seconds * show::frames_per_second(signal.rate) * a.speed));
  show::write_wav(a.out, show::encode_ltc(signal), a.sample_rate_hz);
  fmt::print("{}: {} frames of LTC at {} fps from {} ({:.3f} s at {} Hz, speed {}, {} dBFS)\n", a.out, signal.frames,
             show::to_string(signal.rate), show::format_timecode(signal.start, signal.rate), a.seconds,
             a.sample_rate_hz, a.speed, a.level_dbfs);
}

struct ReadArgs {
  std::string file;
  int channel = 0;
  std::string start;  ///< the show's start in timecode (the chase's offset); empty: the first frame's
  double freewheel_s = 2.0;
};

/// The rate of a stream from its frames: the drop-frame flag, else the highest label and the frames' length.
std::optional<show::TimecodeRate> rate_of(const std::vector<show::LtcFrame>& frames, double sample_rate_hz) {
  if (frames.size() < 2) return std::nullopt;
  int top = 0;
  for (const show::LtcFrame& f : frames) top = std::max(top, f.timecode.frames);
  if (frames.front().drop_frame) return show::TimecodeRate::fps29_97_drop;
  const show::LtcFrame& f = frames[frames.size() / 2];
  const double fps = sample_rate_hz / static_cast<double>(f.last_sample - f.first_sample + 1);
  if (top >= 25 || fps > 27.5) return show::TimecodeRate::fps30;
  if (top == 24 || fps > 24.5) return show::TimecodeRate::fps25;
  return show::TimecodeRate::fps24;
}

void read_command(const ReadArgs& a) {
  const show::AudioChannel audio = show::read_audio_channel(a.file, a.channel);
  show::LtcDecoder decoder(audio.sample_rate_hz);
  const std::vector<show::LtcFrame> frames = decoder.decode(audio.samples);
  const double length_s = static_cast<double>(audio.samples.size()) / audio.sample_rate_hz;
  const std::optional<show::TimecodeRate> rate = rate_of(frames, audio.sample_rate_hz);
  if (!rate)
    throw std::runtime_error(
        fmt::format("{} (channel {} of {}): no LTC in {:.1f} s of audio", a.file, a.channel, audio.channels, length_s));
  show::ChaseSettings settings;
  settings.offset_s = a.start.empty() ? show::timecode_seconds(frames.front().timecode, *rate)
                                      : show::timecode_seconds(show::parse_timecode(a.start, *rate), *rate);
  settings.freewheel_s = a.freewheel_s;
  show::TimecodeChase chase(settings);
  fmt::print("{} (channel {} of {}, {} Hz, {:.1f} s): {} LTC frames at {} fps, {} to {}, level {:.1f} dBFS\n", a.file,
             a.channel, audio.channels, audio.sample_rate_hz, length_s, frames.size(), show::to_string(*rate),
             show::format_timecode(frames.front().timecode, *rate),
             show::format_timecode(frames.back().timecode, *rate), frames[frames.size() / 2].volume_dbfs);
  fmt::print("show time 0 at {}; a line a second, and where the chase changes state:\n",
             show::format_timecode(show::timecode_at_seconds(settings.offset_s, *rate), *rate));
  fmt::print("{:>9}  {:>12}  {:<22}  {:>11}  {:>10}\n", "audio s", "timecode", "chase", "show time s", "drift ppm");
  std::size_t next = 0;
  show::ChaseState previous = show::ChaseState::waiting;
  int locates = 0;
  // Asked 100 times a second, each frame given once the audio holds its end (as a live reader has it).
  for (int k = 0; k <= static_cast<int>(length_s * 100.0); ++k) {
    const double t = k / 100.0;
    while (next < frames.size() && static_cast<double>(frames[next].last_sample) / audio.sample_rate_hz <= t) {
      const show::LtcFrame& f = frames[next++];
      chase.receive({f.timecode, *rate, static_cast<double>(f.first_sample) / audio.sample_rate_hz});
    }
    const show::ChasePosition p = chase.position(t);
    if (p.state != previous || p.locates != locates || k % 100 == 0)
      fmt::print("{:>9.2f}  {:>12}  {:<22}  {:>11.3f}  {:>10.0f}\n", t,
                 p.last ? show::format_timecode(*p.last, *rate) : std::string("-"), show::to_string(p.state),
                 p.show_time_s, std::round(p.drift_ppm) + 0.0);  // + 0.0: no "-0"
    previous = p.state;
    locates = p.locates;
  }
}

}  // namespace

void register_timecode_command(CLI::App& app) {
  CLI::App* timecode = app.add_subcommand(
      "timecode", "SMPTE timecode for shows that chase the house clock: write an LTC track, read one back");
  timecode->require_subcommand(1);

  auto w = std::make_shared<WriteArgs>();
  CLI::App* write = timecode->add_subcommand("write", "Write LTC to a 16-bit mono WAV file");
  write->add_option("out", w->out, "The WAV file")->required();
  write->add_option("--start", w->start, "The first frame's timecode, hh:mm:ss:ff (default 01:00:00:00)");
  write->add_option("--rate", w->rate, "Frames per second: 24, 25, 29.97df or 30 (default 25)");
  write->add_option("--seconds", w->seconds, "Length in seconds (default 60)")->check(CLI::Range(0.1, 86400.0));
  write->add_option("--sample-rate", w->sample_rate_hz, "Samples per second (default 48000)")
      ->check(CLI::Range(8000.0, 192000.0));
  write->add_option("--speed", w->speed, "Timecode seconds per audio second, e.g. 1.001 (default 1)")
      ->check(CLI::Range(0.5, 2.0));
  write->add_option("--level", w->level_dbfs, "Peak level in dBFS (default -18)")->check(CLI::Range(-60.0, 0.0));
  write->callback([w] { write_command(*w); });

  auto r = std::make_shared<ReadArgs>();
  CLI::App* read = timecode->add_subcommand(
      "read", "Read LTC from an audio file as a show would chase it: rate, level, lock, dropouts, locates, drift");
  read->add_option("file", r->file, "The audio file (WAV, AIFF, FLAC, ...)")->required();
  read->add_option("--channel", r->channel, "The channel holding the LTC, 0 the first (default 0)")
      ->check(CLI::Range(0, 255));
  read->add_option("--start", r->start, "The show's start in timecode (default: the first frame read)");
  read->add_option("--freewheel", r->freewheel_s, "Seconds to run on through a dropout (default 2)")
      ->check(CLI::Range(0.0, 3600.0));
  read->callback([r] { read_command(*r); });
}

}  // namespace zenith::app
