#pragma once
// Strict, path-aware reading of JSON configuration files.
//
// Every config in zenith (atmospheres now; scenes, clusters and shows later) is
// read through JsonReader so that bad input always produces the same kind of
// message: the file, the key as a JSON pointer, the offending value and the
// allowed range, e.g.
//   configs/atmospheres/mars.json: /aerosol/scale_height_m = -5: must be in [1, 1e+06] m
// Unknown keys are errors too (a typo must not silently fall back to a default).
#include <nlohmann/json.hpp>

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/strings.h"

namespace zenith {

class ConfigError : public std::runtime_error {
 public:
  ConfigError(const std::string& file, const std::string& key, const std::string& message);
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }

 private:
  std::string file_, key_;
};

/// Parses `text` as JSON, turning syntax errors into a ConfigError with the byte offset.
nlohmann::json parse_json(const std::string& text, const std::string& file);
/// Reads and parses a JSON file (every config loader's first step): a
/// ConfigError "<path>: (top level): cannot open file" when it cannot be
/// opened, parse_json's for bad JSON.
nlohmann::json read_json_file(const std::filesystem::path& path);

/// Reads one JSON object; call finish() when done to reject keys nobody read.
class JsonReader {
 public:
  JsonReader(const nlohmann::json& object, std::string file, std::string path = "");

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  std::string key_path(const std::string& key) const { return path_ + "/" + key; }

  bool has(const std::string& key) const;
  /// The raw value of a key (marks it as read). Throws if missing.
  const nlohmann::json& raw(const std::string& key);
  /// A nested object. Throws if missing or not an object.
  JsonReader object(const std::string& key);
  std::optional<JsonReader> optional_object(const std::string& key);

  /// A finite number in [lo, hi]; `unit` is printed in errors ("m", "K", "" ...).
  double number(const std::string& key, double lo, double hi, const std::string& unit = "");
  double number_or(const std::string& key, double fallback, double lo, double hi, const std::string& unit = "");
  int integer(const std::string& key, int lo, int hi);
  std::string string(const std::string& key, const std::vector<std::string>& allowed = {});
  std::string string_or(const std::string& key, const std::string& fallback, const std::vector<std::string>& allowed);
  /// The file named by the string at `key`: resolved against `base_dir` when
  /// relative, made absolute and normal; it must be a regular file. Errors
  /// name the key, the text and the path looked for.
  std::filesystem::path existing_file(const std::string& key, const std::filesystem::path& base_dir);

  /// Throws ConfigError for any key of the object not read so far.
  void finish() const;

  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  /// "must be in [lo, hi] unit" formatted consistently.
  static std::string range_text(double lo, double hi, const std::string& unit);

 private:
  const nlohmann::json& object_;
  std::string file_, path_;
  mutable std::set<std::string> read_;
};

/// Helpers the config loaders share (scenes, viewports, clusters).
namespace config {

/// core::cat (core/strings.h) under its old name, for code not yet moved to it.
using core::cat;

/// A JSON value for a message, shortened to 80 characters when long (an inline object).
std::string brief(const nlohmann::json& value);

/// The wavelength a key of a spectral object names ("550", "442.25") in nm,
/// within [100, 5000]; anything else fails through r.fail(key, ...).
double wavelength_key(const JsonReader& r, const std::string& key, const std::string& text);

/// Rejects, through r.fail(), the first key of `object` not in `allowed`, listing
/// those that are and pointing to `docs_page` ("docs/scenes.md"). Objects that
/// are not objects are left to JsonReader's constructor to report.
void reject_unknown_keys(const JsonReader& r, const nlohmann::json& object,
                         std::initializer_list<std::string_view> allowed, std::string_view docs_page);

}  // namespace config
}  // namespace zenith
