// The manifest of an offline render and the resume rule (offline/offline_manifest.h).
#include "offline/offline_manifest.h"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "core/files.h"
#include "core/json_reader.h"
#include "core/sha256.h"
#include "core/strings.h"

namespace zenith::app::offline {
namespace {

using core::cat;

[[noreturn]] void fail(const std::string& source, const std::string& pointer, const std::string& message) {
  throw std::runtime_error(cat(source, ": ", pointer, ": ", message));
}

const nlohmann::json& member(const nlohmann::json& object, const char* key, const std::string& source,
                             const std::string& pointer) {
  if (!object.is_object()) fail(source, pointer, "expected an object");
  const auto it = object.find(key);
  if (it == object.end()) fail(source, cat(pointer, "/", key), "missing");
  return *it;
}

std::string hex_string(const nlohmann::json& object, const char* key, std::size_t digits, const std::string& source,
                       const std::string& pointer) {
  const nlohmann::json& value = member(object, key, source, pointer);
  const bool ok = value.is_string() && value.get_ref<const std::string&>().size() == digits &&
                  std::all_of(value.get_ref<const std::string&>().begin(), value.get_ref<const std::string&>().end(),
                              [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
  if (!ok) fail(source, cat(pointer, "/", key), cat("expected ", digits, " lowercase hex digits"));
  return value.get<std::string>();
}

}  // namespace

nlohmann::json to_json(const Manifest& manifest) {
  nlohmann::json frames = nlohmann::json::array();
  for (const auto& [index, frame] : manifest.frames) {
    nlohmann::json files = nlohmann::json::array();
    for (const ManifestFile& f : frame.files)
      files.push_back({{"path", f.path}, {"settings_key", f.settings_key}, {"sha256", f.sha256}});
    frames.push_back({{"frame", index}, {"state_digest", frame.state_digest}, {"files", std::move(files)}});
  }
  return {{"zenith_offline_render", kManifestFormatVersion}, {"run", manifest.run}, {"frames", std::move(frames)}};
}

Manifest manifest_from_json(const nlohmann::json& json, const std::string& source) {
  const nlohmann::json& version = member(json, "zenith_offline_render", source, "");
  if (!version.is_number_integer() || version.get<long long>() != kManifestFormatVersion)
    fail(source, "/zenith_offline_render",
         cat(version.dump(), ": unsupported manifest version; this build reads version ", kManifestFormatVersion,
             " (render into another --out folder, or delete the manifest to render every frame again)"));
  Manifest m;
  if (json.contains("run")) m.run = json.at("run");
  const nlohmann::json& frames = member(json, "frames", source, "");
  if (!frames.is_array()) fail(source, "/frames", "expected an array");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::string at = cat("/frames/", i);
    const nlohmann::json& f = frames[i];
    const nlohmann::json& index = member(f, "frame", source, at);
    if (!index.is_number_unsigned() && !(index.is_number_integer() && index.get<long long>() >= 0))
      fail(source, cat(at, "/frame"), "expected a frame number ≥ 0");
    ManifestFrame frame;
    frame.state_digest = hex_string(f, "state_digest", 16, source, at);
    const nlohmann::json& files = member(f, "files", source, at);
    if (!files.is_array()) fail(source, cat(at, "/files"), "expected an array");
    for (std::size_t k = 0; k < files.size(); ++k) {
      const std::string file_at = cat(at, "/files/", k);
      const nlohmann::json& path = member(files[k], "path", source, file_at);
      if (!path.is_string() || path.get_ref<const std::string&>().empty())
        fail(source, cat(file_at, "/path"), "expected a relative file path");
      frame.files.push_back({path.get<std::string>(), hex_string(files[k], "settings_key", 16, source, file_at),
                             hex_string(files[k], "sha256", 64, source, file_at)});
    }
    if (!m.frames.emplace(index.get<std::uint64_t>(), std::move(frame)).second)
      fail(source, cat(at, "/frame"), cat("frame ", index.get<std::uint64_t>(), " listed twice"));
  }
  return m;
}

Manifest read_manifest(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return {};
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw std::runtime_error(cat(path.string(), ": cannot read the manifest"));
  try {
    return manifest_from_json(nlohmann::json::parse(text.str()), path.string());
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(cat(path.string(), ": not a valid manifest (", e.what(),
                                 "); delete it to render every frame again, or render into another --out folder"));
  }
}

void write_manifest(const std::filesystem::path& path, const Manifest& manifest) {
  std::filesystem::path partial = path;
  partial += ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    out << to_json(manifest).dump(1) << '\n';
    out.flush();
    if (!out) throw std::runtime_error(cat(partial.string(), ": cannot write the manifest"));
  }
  std::error_code ec;
  std::filesystem::rename(partial, path, ec);
  if (ec) throw std::runtime_error(cat(partial.string(), ": cannot rename to ", path.string(), ": ", ec.message()));
}

std::string file_sha256(const std::filesystem::path& path) {
  const std::string bytes = core::file_bytes(path);
  return core::sha256_hex(bytes.data(), bytes.size());
}

FrameCheck check_frame(const Manifest& manifest, std::uint64_t frame, const std::string& state_digest,
                       const std::vector<ExpectedFile>& expected, const std::filesystem::path& root) {
  FrameCheck check;
  const auto it = manifest.frames.find(frame);
  if (it == manifest.frames.end()) {
    check.reason = "not in the manifest";
    return check;
  }
  if (it->second.state_digest != state_digest) {
    check.reason = cat("its state changed (", it->second.state_digest, " → ", state_digest, ")");
    return check;
  }
  if (expected.empty()) {
    check.reason = "no files expected";
    return check;
  }
  for (const ExpectedFile& e : expected) {
    const auto& files = it->second.files;
    const auto entry =
        std::find_if(files.begin(), files.end(), [&](const ManifestFile& f) { return f.path == e.path; });
    if (entry == files.end()) {
      check.reason = cat(e.path, ": not in the manifest");
      return check;
    }
    if (entry->settings_key != e.settings_key) {
      check.reason = cat(e.path, ": rendered with other settings");
      return check;
    }
    const std::filesystem::path file = root / std::filesystem::path(e.path);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
      check.reason = cat(e.path, ": missing");
      return check;
    }
    if (file_sha256(file) != entry->sha256) {
      check.reason = cat(e.path, ": changed on disk (SHA-256 differs from the manifest)");
      return check;
    }
    check.files.push_back(*entry);
  }
  check.skip = true;
  return check;
}

}  // namespace zenith::app::offline
