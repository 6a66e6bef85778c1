#pragma once
// The manifest of an offline render (docs/shows.md, "Offline rendering"):
// DIR/manifest.json records, for every finished frame, the digest of the state
// it was rendered from and each of its files with the key of the settings that
// made it and the SHA-256 of its bytes. It decides what a later run into the
// same folder may skip:
//
//   a frame is skipped when the manifest lists it with the same state digest
//   and, for every file the run would write, an entry with the same path and
//   settings key whose file exists with the recorded SHA-256;
//   otherwise it is rendered again.
//
// So a change of the show, the frame rate, an output or a format invalidates
// exactly the frames (and only those) whose state or files change; a frame
// whose files exist but are missing from the manifest (a run killed between
// writing them and the next manifest update) is rendered again.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace zenith::app::offline {

/// "zenith_offline_render" of the manifest; bumped on incompatible changes.
inline constexpr int kManifestFormatVersion = 1;
/// Its file name in the render folder.
inline constexpr const char* kManifestFileName = "manifest.json";

/// A file of a finished frame.
struct ManifestFile {
  std::string path;          ///< relative to the render folder, '/'-separated: "dome/dome.000012.png"
  std::string settings_key;  ///< 16 hex digits: what besides the state shaped its bytes (output, format, tables, scene)
  std::string sha256;        ///< 64 lowercase hex digits of its bytes
  bool operator==(const ManifestFile&) const = default;
};

struct ManifestFrame {
  std::string state_digest;  ///< RenderJob::frame_digest of the state it was rendered from
  std::vector<ManifestFile> files;
  bool operator==(const ManifestFrame&) const = default;
};

struct Manifest {
  /// The latest run's description (show file and its SHA-256, fps, frame
  /// range, outputs, formats, settings): for people and tools; the skip
  /// decision uses the frames only.
  nlohmann::json run = nlohmann::json::object();
  std::map<std::uint64_t, ManifestFrame> frames;  ///< by show frame index
  bool operator==(const Manifest&) const = default;
};

nlohmann::json to_json(const Manifest& manifest);
/// Throws std::runtime_error starting "<source>: " naming the JSON pointer of
/// a missing or malformed key, or an unsupported format version.
Manifest manifest_from_json(const nlohmann::json& json, const std::string& source);

/// The manifest at `path`; an empty one when there is no such file. Throws
/// std::runtime_error naming the file when it cannot be read or parsed.
Manifest read_manifest(const std::filesystem::path& path);
/// Writes atomically: PATH.partial, then renamed over PATH.
void write_manifest(const std::filesystem::path& path, const Manifest& manifest);

/// SHA-256 of a file's bytes as 64 lowercase hex digits; throws
/// std::runtime_error naming the file when it cannot be read.
std::string file_sha256(const std::filesystem::path& path);

/// A file the run writes for a frame.
struct ExpectedFile {
  std::string path;  ///< relative to the render folder, as in ManifestFile
  std::string settings_key;
};

/// The skip decision for one frame.
struct FrameCheck {
  bool skip = false;
  std::string reason;  ///< why it is rendered ("not in the manifest", "dome/dome.000003.png: changed on disk", ...)
  std::vector<ManifestFile> files;  ///< skip: the verified entries, in the order of `expected`
};

/// Applies the rule at the top of this file to frame `frame` of `manifest`,
/// `expected` being every file the run writes for it (at least one), under
/// the folder `root`. Reads (hashes) the files on disk.
FrameCheck check_frame(const Manifest& manifest, std::uint64_t frame, const std::string& state_digest,
                       const std::vector<ExpectedFile>& expected, const std::filesystem::path& root);

}  // namespace zenith::app::offline
