// The frame loop of offline rendering (offline/offline_render.h).
#include "offline/offline_render.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include "core/progress_bar.h"
#include "core/sha256.h"
#include "core/strings.h"
#include "core/timing.h"
#include "image/contact_sheet.h"
#include "offline/offline_manifest.h"

namespace zenith::app::offline {
namespace {

using core::cat;
using Clock = std::chrono::steady_clock;

using core::seconds_since;

/// "42 s", "3 min 05 s", "2 h 07 min".
std::string format_duration(double seconds) {
  if (!(seconds >= 0.0) || seconds > 1e9) return "?";
  const auto s = static_cast<long long>(std::llround(seconds));
  if (s < 60) return fmt::format("{} s", s);
  if (s < 3600) return fmt::format("{} min {:02} s", s / 60, s % 60);
  return fmt::format("{} h {:02} min", s / 3600, (s % 3600) / 60);
}

void check_job(const RenderJob& job) {
  if (job.show == nullptr) throw std::invalid_argument("offline render: no show");
  if (!job.frame_digest) throw std::invalid_argument("offline render: no frame digest");
  if (!(job.fps > 0.0 && job.fps <= 1000.0))
    throw std::invalid_argument(fmt::format("--fps {}: must be in (0, 1000] frames per second", job.fps));
  const std::uint64_t count = job.show->frame_count(job.fps);
  if (job.first_frame > job.last_frame || job.last_frame >= count)
    throw std::invalid_argument(fmt::format("--from {} --to {}: the show has frames 0 to {} at {} fps", job.first_frame,
                                            job.last_frame, count - 1, job.fps));
  if (job.outputs.empty()) throw std::invalid_argument("offline render: no outputs");
  if (job.formats.empty()) throw std::invalid_argument("--format: give a comma list of png, png16, tiff and exr");
  std::set<std::string> names;
  for (const OutputSpec& o : job.outputs)
    if (o.name.empty() || !names.insert(o.name).second)
      throw std::invalid_argument(fmt::format("offline render: output name '{}' empty or used twice", o.name));
}

/// Per output, per format: the file's path relative to the render folder and its settings key.
struct FrameFiles {
  std::vector<ExpectedFile> expected;                     ///< outputs × formats, output-major
  std::vector<std::vector<std::filesystem::path>> paths;  ///< absolute, [output][format]
};

FrameFiles files_of(const RenderJob& job, const std::vector<std::vector<std::string>>& keys, std::uint64_t frame) {
  FrameFiles f;
  for (std::size_t o = 0; o < job.outputs.size(); ++o) {
    std::vector<std::filesystem::path>& paths = f.paths.emplace_back();
    for (std::size_t k = 0; k < job.formats.size(); ++k) {
      const std::string relative = frame_file_path(job.outputs[o].name, frame, job.formats[k], job.naming);
      f.expected.push_back({relative, keys[o][k]});
      paths.push_back(job.out_dir / relative);
    }
  }
  return f;
}

/// The contact sheet: evenly spaced frames of the range, each cell the
/// outputs side by side (the PNG of each when rendered, else the EXR).
std::filesystem::path write_sheet(const RenderJob& job, ImageFormat format) {
  const std::vector<std::uint64_t> frames =
      image::evenly_spaced_frames(job.first_frame, job.last_frame, job.contact_sheet_frames);
  const bool mosaic = std::all_of(job.outputs.begin(), job.outputs.end(),
                                  [](const OutputSpec& o) { return o.mosaic_origin_px.has_value(); });
  if (mosaic) {  // tiles of one dome master: each cell the whole picture
    std::vector<std::vector<image::MosaicTile>> tiles;
    int picture_height_px = 0;
    for (const std::uint64_t frame : frames) {
      std::vector<image::MosaicTile>& cell = tiles.emplace_back();
      for (const OutputSpec& o : job.outputs) {
        cell.push_back({job.out_dir / frame_file_path(o.name, frame, format, job.naming), (*o.mosaic_origin_px)[0],
                        (*o.mosaic_origin_px)[1]});
        picture_height_px = std::max(picture_height_px, (*o.mosaic_origin_px)[1] + o.height_px);
      }
    }
    image::ContactSheetOptions options;
    options.cell_height_px = std::max(1, std::min(options.cell_height_px, picture_height_px));
    const auto [w, h] = image::write_mosaic_contact_sheet(*job.contact_sheet, tiles, job.tone, options);
    spdlog::info("contact sheet of {} frames: {} ({}x{})", tiles.size(), job.contact_sheet->string(), w, h);
    return *job.contact_sheet;
  }
  std::vector<std::vector<std::filesystem::path>> cells;
  for (const std::uint64_t frame :
       image::evenly_spaced_frames(job.first_frame, job.last_frame, job.contact_sheet_frames)) {
    std::vector<std::filesystem::path>& cell = cells.emplace_back();
    for (const OutputSpec& o : job.outputs)
      cell.push_back(job.out_dir / frame_file_path(o.name, frame, format, job.naming));
  }
  // Thumbnails 135 px high (a 24-frame sheet of square domes: about 1100 px
  // wide), no taller than the shortest output: thumbnails are never enlarged.
  image::ContactSheetOptions options;
  for (const OutputSpec& o : job.outputs) options.cell_height_px = std::min(options.cell_height_px, o.height_px);
  options.cell_height_px = std::max(options.cell_height_px, 1);
  const auto [w, h] = image::write_contact_sheet(*job.contact_sheet, cells, job.tone, options);
  spdlog::info("contact sheet of {} frames: {} ({}x{})", cells.size(), job.contact_sheet->string(), w, h);
  return *job.contact_sheet;
}

}  // namespace

const char* extension_of(ImageFormat format) {
  switch (format) {
    case ImageFormat::png:
    case ImageFormat::png16: return "png";
    case ImageFormat::tiff: return "tif";
    case ImageFormat::exr: return "exr";
  }
  return "?";
}

const char* name_of(ImageFormat format) {
  switch (format) {
    case ImageFormat::png: return "png";
    case ImageFormat::png16: return "png16";
    case ImageFormat::tiff: return "tiff";
    case ImageFormat::exr: return "exr";
  }
  return "?";
}

bool is_display_format(ImageFormat format) { return format != ImageFormat::exr; }

std::vector<ImageFormat> parse_formats(const std::string& text) {
  const auto refuse = [&](const std::string& why) {
    return std::invalid_argument(
        fmt::format("--format '{}': {}; give a comma list of png, png16, tiff and exr (e.g. png,exr)", text, why));
  };
  std::vector<ImageFormat> formats;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    const std::string name = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    ImageFormat f;
    if (name == "png")
      f = ImageFormat::png;
    else if (name == "png16")
      f = ImageFormat::png16;
    else if (name == "tiff" || name == "tif")
      f = ImageFormat::tiff;
    else if (name == "exr")
      f = ImageFormat::exr;
    else
      throw refuse(fmt::format("'{}' is not a format", name));
    if (std::find(formats.begin(), formats.end(), f) != formats.end()) throw refuse(fmt::format("{} twice", name));
    formats.push_back(f);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  const auto has = [&](ImageFormat f) { return std::find(formats.begin(), formats.end(), f) != formats.end(); };
  if (has(ImageFormat::png) && has(ImageFormat::png16))
    throw refuse("png and png16 would share the file names (.png); choose one");
  return formats;
}

namespace {

/// The frame-number conversion of a pattern: its position, length and width (0: none).
struct NumberField {
  std::size_t position = 0, length = 0;
  int width = 0;
};

/// Finds the one `%d` / `%0Nd` of `pattern`; throws naming --frame-name otherwise.
NumberField number_field(const std::string& pattern, const std::string& as_given) {
  std::optional<NumberField> field;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') continue;
    NumberField f{i, 0, 0};
    std::size_t j = i + 1;
    if (j + 1 < pattern.size() && pattern[j] == '0' && pattern[j + 1] >= '1' && pattern[j + 1] <= '9') {
      f.width = pattern[j + 1] - '0';
      j += 2;
    }
    if (j >= pattern.size() || pattern[j] != 'd' || field)
      throw std::invalid_argument(fmt::format(
          "--frame-name '{}': needs exactly one frame number, %d or %0Nd with N in [1, 9] (e.g. dome.%06d), and no "
          "other %",
          as_given));
    f.length = j + 1 - i;
    field = f;
  }
  if (!field)
    throw std::invalid_argument(
        fmt::format("--frame-name '{}': has no frame number; add %d or %0Nd (e.g. dome.%06d)", as_given));
  return *field;
}

}  // namespace

FileNaming parse_file_naming(const std::string& text, std::uint64_t start_number) {
  std::string pattern = text;
  for (const char* ext : {".png", ".tif", ".tiff", ".exr"}) {
    const std::string e = ext;
    if (pattern.size() > e.size() && pattern.compare(pattern.size() - e.size(), e.size(), e) == 0) {
      pattern.resize(pattern.size() - e.size());
      break;
    }
  }
  if (pattern.empty() || pattern.find('/') != std::string::npos || pattern.find('\\') != std::string::npos)
    throw std::invalid_argument(fmt::format(
        "--frame-name '{}': must be a file name (no folders: each output's files go into DIR/<output>/)", text));
  number_field(pattern, text);
  if (start_number > 1'000'000'000'000ull)
    throw std::invalid_argument(fmt::format("--start-number {}: must be in [0, 10^12]", start_number));
  return {pattern, start_number};
}

std::string frame_file_path(const std::string& output, std::uint64_t frame, ImageFormat format,
                            const FileNaming& naming) {
  std::string name = naming.pattern;
  const NumberField field = number_field(name, name);
  const std::uint64_t number = naming.start_number + frame;
  name.replace(field.position, field.length,
               field.width > 0 ? fmt::format("{:0{}}", number, field.width) : fmt::format("{}", number));
  for (std::size_t at = name.find("{output}"); at != std::string::npos; at = name.find("{output}", at + output.size()))
    name.replace(at, 8, output);
  return fmt::format("{}/{}.{}", output, name, extension_of(format));
}

std::string settings_key(const RenderJob& job, const OutputSpec& output, ImageFormat format) {
  const std::string text = cat(job.settings, "\noutput ", output.name, " ", output.width_px, "x", output.height_px, " ",
                               output.description, "\nformat ", name_of(format), " ",
                               format == ImageFormat::exr    ? job.exr_settings
                               : format == ImageFormat::tiff ? job.tiff_settings
                                                             : job.png_settings);
  return core::sha256_hex(text.data(), text.size()).substr(0, 16);
}

void FrameRenderer::submit_frame(const scene::FrameDescription& state,
                                 const std::vector<std::vector<std::filesystem::path>>& files) {
  render_frame(state, files);
  FinishedFrame& f = finished_.emplace_back();
  f.frame = state.frame;
  for (const auto& output : files)
    for (const std::filesystem::path& path : output) f.file_sha256.push_back(file_sha256(path));
}

std::vector<FinishedFrame> FrameRenderer::take_finished() { return std::exchange(finished_, {}); }

RenderSummary run_render_job(const RenderJob& job, FrameRenderer& renderer) {
  check_job(job);
  const Clock::time_point start = Clock::now();
  std::filesystem::create_directories(job.out_dir);
  const std::filesystem::path manifest_path = job.out_dir / kManifestFileName;
  Manifest manifest = read_manifest(manifest_path);
  const std::uint64_t show_frames = job.show->frame_count(job.fps);
  // Frames past the end of the show as it is now are no longer part of it.
  manifest.frames.erase(manifest.frames.lower_bound(show_frames), manifest.frames.end());
  manifest.run = job.run;

  std::vector<std::vector<std::string>> keys;
  for (const OutputSpec& o : job.outputs) {
    std::vector<std::string>& k = keys.emplace_back();
    for (const ImageFormat f : job.formats) k.push_back(settings_key(job, o, f));
  }

  // 1. Which frames are done already (the files are hashed: a first run over
  //    an empty folder is instant, a resume reads what it skips once).
  RenderSummary summary;
  summary.frames = job.last_frame - job.first_frame + 1;
  std::vector<std::uint64_t> pending;
  std::set<scene::TableHash> pending_tables;  // the table sets the pending frames use
  {
    core::ProgressBar bar("checking");
    std::uint64_t in_manifest = 0;
    for (std::uint64_t frame = job.first_frame; frame <= job.last_frame; ++frame) {
      const scene::FrameDescription state =
          job.show->state_at(job.show->frame_time_s(frame, job.fps), frame, job.render_flags);
      const FrameFiles files = files_of(job, keys, frame);
      const FrameCheck check = check_frame(manifest, frame, job.frame_digest(state), files.expected, job.out_dir);
      if (check.skip) {
        ++summary.skipped;
        manifest.frames[frame].files = check.files;  // only what this run would write
      } else {
        pending.push_back(frame);
        for (const scene::AtmosphereTableRef& ref : state.atmospheres) pending_tables.insert(ref.table_hash);
        if (manifest.frames.count(frame) > 0) {
          ++in_manifest;
          spdlog::info("frame {}: rendering again: {}", frame, check.reason);
        }
      }
      if ((frame - job.first_frame) % 64 == 0 || frame == job.last_frame)
        bar.update(fmt::format("frame {}", frame),
                   static_cast<double>(frame - job.first_frame + 1) / static_cast<double>(summary.frames));
    }
    bar.finish();
    spdlog::info("{} of {} frames verified from the manifest, {} to render ({} of them listed but invalid)",
                 summary.skipped, summary.frames, pending.size(), in_manifest);
  }

  // 2. Render the others, in order. A pipelined renderer returns from
  //    submit_frame before the frame's files exist; a frame enters the manifest
  //    once take_finished() reports its files complete (frames in order).
  if (!pending.empty()) {
    if (job.before_rendering) job.before_rendering(pending.size(), pending_tables);
    core::ProgressBar bar("rendering");
    const Clock::time_point render_start = Clock::now();
    Clock::time_point last_write = render_start;
    double first_frame_s = 0.0;
    std::map<std::uint64_t, std::pair<std::string, FrameFiles>> in_flight;  // submitted, not finished
    std::size_t finished = 0;
    const auto record = [&](const std::vector<FinishedFrame>& frames) {
      for (const FinishedFrame& f : frames) {
        const auto it = in_flight.find(f.frame);
        if (it == in_flight.end() || f.file_sha256.size() != it->second.second.expected.size())
          throw std::logic_error(fmt::format("offline render: frame {} finished but not as submitted", f.frame));
        ManifestFrame& entry = manifest.frames[f.frame];
        entry.state_digest = it->second.first;
        entry.files.clear();
        for (std::size_t k = 0; k < f.file_sha256.size(); ++k)
          entry.files.push_back(
              {it->second.second.expected[k].path, it->second.second.expected[k].settings_key, f.file_sha256[k]});
        in_flight.erase(it);
        ++summary.rendered;
        // The first frame also loads tables, albedo and shaders: the rate is
        // that of the frames after it, once there are some.
        const double elapsed = seconds_since(render_start);
        if (finished == 0) first_frame_s = elapsed;
        const double per_frame = finished == 0 ? elapsed : (elapsed - first_frame_s) / static_cast<double>(finished);
        ++finished;
        bar.update(
            fmt::format("frame {} ({}/{}), {:.2f} frames/s, ETA {}", f.frame, finished, pending.size(), 1.0 / per_frame,
                        format_duration(per_frame * static_cast<double>(pending.size() - finished))),
            static_cast<double>(finished) / static_cast<double>(pending.size()));
      }
      if (seconds_since(last_write) >= job.manifest_interval_s) {
        write_manifest(manifest_path, manifest);
        last_write = Clock::now();
      }
    };
    try {
      for (const std::uint64_t frame : pending) {
        const scene::FrameDescription state =
            job.show->state_at(job.show->frame_time_s(frame, job.fps), frame, job.render_flags);
        FrameFiles files = files_of(job, keys, frame);
        manifest.frames.erase(frame);  // until its files are hashed
        const std::vector<std::vector<std::filesystem::path>> paths = files.paths;
        in_flight.emplace(frame, std::make_pair(job.frame_digest(state), std::move(files)));
        renderer.submit_frame(state, paths);
        record(renderer.take_finished());
      }
      renderer.finish_frames();
      record(renderer.take_finished());
    } catch (...) {
      // Keep what is finished: the frames completed before the error.
      try {
        renderer.finish_frames();
      } catch (...) {
      }
      try {
        record(renderer.take_finished());
      } catch (...) {
      }
      bar.finish();
      write_manifest(manifest_path, manifest);
      throw;
    }
    bar.finish();
    summary.render_s = seconds_since(render_start);
  }
  write_manifest(manifest_path, manifest);

  // 3. The contact sheet.
  // From the PNGs when there are some, else the EXRs (a TIFF-only render has none).
  std::optional<ImageFormat> sheet_format;
  for (const ImageFormat f : {ImageFormat::png, ImageFormat::png16, ImageFormat::exr})
    if (!sheet_format && std::find(job.formats.begin(), job.formats.end(), f) != job.formats.end()) sheet_format = f;
  if (job.contact_sheet && !sheet_format)
    spdlog::info("no contact sheet: it is made from PNG or EXR frames, and this render writes only TIFF");
  if (job.contact_sheet && sheet_format) summary.contact_sheet = write_sheet(job, *sheet_format);
  summary.total_s = seconds_since(start);
  return summary;
}

std::string describe(const RenderSummary& s) {
  std::string text =
      fmt::format("rendered {}, skipped {} of {} frames in {:.1f} s", s.rendered, s.skipped, s.frames, s.total_s);
  if (s.rendered > 0)
    text += fmt::format(" ({:.3f} s per rendered frame, {:.2f} frames/s)", s.render_s / static_cast<double>(s.rendered),
                        static_cast<double>(s.rendered) / std::max(s.render_s, 1e-9));
  return text;
}

}  // namespace zenith::app::offline
