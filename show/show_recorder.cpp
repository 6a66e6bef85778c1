// ShowRecorder: a live session's presented frames → a recording show file.
#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "core/json_reader.h"
#include "core/sha256.h"
#include "core/strings.h"
#include "show/recording_json.h"
#include "show/show.h"

namespace zenith::show {

using core::cat;
using nlohmann::json;
namespace fs = std::filesystem;

struct ShowRecorder::Impl {
  fs::path path;
  std::string scene_text;  ///< the "scene" value: relative to the recording's folder when possible
  std::string name;
  double frame_rate_hz = 0.0;
  std::map<scene::TableHash, json> versions;
  std::vector<scene::TableHash> version_order;
  std::vector<scene::FrameDescription> frames;
  bool finished = false;
};

ShowRecorder::ShowRecorder(fs::path path, fs::path scene_path, std::string name, double frame_rate_hz)
    : impl_(std::make_unique<Impl>()) {
  if (!(std::isfinite(frame_rate_hz) && frame_rate_hz > 0.0 && frame_rate_hz <= 1000.0))
    throw std::invalid_argument(cat("ShowRecorder: frame rate ", frame_rate_hz, " Hz must be in (0, 1000]"));
  if (name.empty()) throw std::invalid_argument("ShowRecorder: the name must not be empty");
  impl_->path = std::move(path);
  impl_->name = std::move(name);
  impl_->frame_rate_hz = frame_rate_hz;
  std::error_code ec;
  const fs::path folder = fs::absolute(impl_->path, ec).parent_path();
  const fs::path scene = fs::absolute(scene_path, ec).lexically_normal();
  const fs::path relative = scene.lexically_relative(folder);
  impl_->scene_text = (relative.empty() ? scene : relative).generic_string();
}

ShowRecorder::~ShowRecorder() {
  if (impl_->finished) return;
  if (impl_->frames.empty()) {
    spdlog::warn("show recording {}: no frames recorded; nothing written", impl_->path.string());
    return;
  }
  try {
    finish();
  } catch (const std::exception& e) {
    spdlog::error("show recording {}: {}", impl_->path.string(), e.what());
  }
}

void ShowRecorder::add_version(const AtmosphereVersion& version) {
  if (impl_->versions.contains(version.table_hash)) return;
  impl_->versions.emplace(version.table_hash, version_to_json(version));
  impl_->version_order.push_back(version.table_hash);
}

void ShowRecorder::record(const scene::FrameDescription& state) {
  try {
    check_recordable(state);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(cat("ShowRecorder: frame ", state.frame, ": ", e.what()));
  }
  for (const scene::AtmosphereTableRef& ref : state.atmospheres)
    if (!impl_->versions.contains(ref.table_hash))
      throw std::invalid_argument(cat("ShowRecorder: frame ", state.frame, " uses table ", core::to_hex(ref.table_hash),
                                      " of body \"", ref.body_name, "\", which was not added (add_version)"));
  impl_->frames.push_back(state);
}

std::size_t ShowRecorder::frames() const { return impl_->frames.size(); }

fs::path ShowRecorder::finish() {
  if (impl_->frames.empty())
    throw std::runtime_error(cat("show recording ", impl_->path.string(), ": no frames recorded"));
  json header = {{"zenith_show", kShowFormatVersion},
                 {"name", impl_->name},
                 {"description",
                  cat("Recorded live session: ", impl_->frames.size(), " frames at ", impl_->frame_rate_hz, " Hz.")},
                 {"scene", impl_->scene_text},
                 {"loop", false}};
  json versions = json::array();
  for (const scene::TableHash& hash : impl_->version_order) versions.push_back(impl_->versions.at(hash));

  // One frame per line: readable, diffable, and still plain JSON.
  std::string text = header.dump(2);
  text.pop_back();  // the closing brace; the recording follows
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  text += cat(",\n  \"recording\": {\n    \"fps\": ", json(impl_->frame_rate_hz).dump(),
              ",\n    \"versions\": ", versions.dump(), ",\n    \"frames\": [\n");
  for (std::size_t i = 0; i < impl_->frames.size(); ++i)
    text += cat("      ", frame_to_json(impl_->frames[i]).dump(), i + 1 < impl_->frames.size() ? ",\n" : "\n");
  text += "    ]\n  }\n}\n";

  fs::path partial = impl_->path;
  partial += ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(cat("show recording: cannot write ", partial.string()));
    out << text;
    out.flush();
    if (!out) throw std::runtime_error(cat("show recording: error writing ", partial.string()));
  }
  std::error_code ec;
  fs::rename(partial, impl_->path, ec);
  if (ec)
    throw std::runtime_error(
        cat("show recording: cannot rename ", partial.string(), " to ", impl_->path.string(), ": ", ec.message()));
  impl_->finished = true;
  return impl_->path;
}

}  // namespace zenith::show
