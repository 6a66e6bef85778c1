#include "core/json_reader.h"

#include <algorithm>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/files.h"

namespace zenith {

ConfigError::ConfigError(const std::string& file, const std::string& key, const std::string& message)
    // "file: /key = value: reason" for values, "file: /key: reason" otherwise.
    : std::runtime_error(file + ": " + (key.empty() ? std::string("(top level)") : key) +
                         (message.starts_with("= ") || message.starts_with("[") ? " " : ": ") + message),
      file_(file),
      key_(key) {}

nlohmann::json parse_json(const std::string& text, const std::string& file) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // syntax errors and number overflow
    throw ConfigError(file, "", std::string("not valid JSON: ") + e.what());
  }
}

nlohmann::json read_json_file(const std::filesystem::path& path) {
  if (const std::string why = core::unreadable_reason(path); !why.empty()) throw ConfigError(path.string(), "", why);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path.string(), "", "cannot open file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_json(text.str(), path.string());
}

JsonReader::JsonReader(const nlohmann::json& object, std::string file, std::string path)
    : object_(object), file_(std::move(file)), path_(std::move(path)) {
  if (!object_.is_object()) throw ConfigError(file_, path_, "must be a JSON object, got " + object_.dump());
}

void JsonReader::fail(const std::string& key, const std::string& message) const {
  throw ConfigError(file_, key.empty() ? path_ : key_path(key), message);
}

std::string JsonReader::range_text(double lo, double hi, const std::string& unit) {
  std::ostringstream s;
  s << "must be in [" << lo << ", " << hi << "]" << (unit.empty() ? "" : " ") << unit;
  return s.str();
}

bool JsonReader::has(const std::string& key) const { return object_.contains(key); }

const nlohmann::json& JsonReader::raw(const std::string& key) {
  if (!object_.contains(key)) fail(key, "missing required key");
  read_.insert(key);
  return object_.at(key);
}

JsonReader JsonReader::object(const std::string& key) {
  const nlohmann::json& v = raw(key);
  if (!v.is_object()) fail(key, "must be an object, got " + v.dump());
  return JsonReader(v, file_, key_path(key));
}

std::optional<JsonReader> JsonReader::optional_object(const std::string& key) {
  if (!has(key)) return std::nullopt;
  return object(key);
}

double JsonReader::number(const std::string& key, double lo, double hi, const std::string& unit) {
  const nlohmann::json& v = raw(key);
  if (!v.is_number()) fail(key, "= " + v.dump() + ": must be a number, " + range_text(lo, hi, unit).substr(5));
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi) {
    std::ostringstream s;
    s << "= " << v.dump() << ": " << range_text(lo, hi, unit);
    fail(key, s.str());
  }
  return x;
}

double JsonReader::number_or(const std::string& key, double fallback, double lo, double hi, const std::string& unit) {
  return has(key) ? number(key, lo, hi, unit) : fallback;
}

int JsonReader::integer(const std::string& key, int lo, int hi) {
  const nlohmann::json& v = raw(key);
  if (!v.is_number_integer()) fail(key, "must be an integer, got " + v.dump());
  const auto x = v.get<long long>();
  if (x < lo || x > hi) fail(key, "= " + v.dump() + ": " + range_text(lo, hi, ""));
  return int(x);
}

std::string JsonReader::string(const std::string& key, const std::vector<std::string>& allowed) {
  const nlohmann::json& v = raw(key);
  if (!v.is_string()) fail(key, "must be a string, got " + v.dump());
  std::string s = v.get<std::string>();
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), s) == allowed.end()) {
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
    fail(key, "= \"" + s + "\": must be one of " + list);
  }
  return s;
}

std::filesystem::path JsonReader::existing_file(const std::string& key, const std::filesystem::path& base_dir) {
  const std::string text = string(key);
  if (text.empty()) fail(key, "= \"\": must name a file");
  std::filesystem::path path(text);
  if (path.is_relative()) path = base_dir / path;
  path = std::filesystem::absolute(path).lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    fail(key, "= \"" + text + "\": file not found (no such file: " + path.string() + ")");
  return path;
}

std::string JsonReader::string_or(const std::string& key, const std::string& fallback,
                                  const std::vector<std::string>& allowed) {
  return has(key) ? string(key, allowed) : fallback;
}

void JsonReader::finish() const {
  for (const auto& [key, value] : object_.items())
    if (!read_.count(key)) fail(key, "unknown key (check the spelling; see docs/atmosphere-config.md)");
}

namespace config {

std::string brief(const nlohmann::json& value) {
  std::string text = value.dump();
  if (text.size() > 80) text = text.substr(0, 77) + "...";
  return text;
}

double wavelength_key(const JsonReader& r, const std::string& key, const std::string& text) {
  double nm = 0.0;
  std::size_t used = 0;
  try {
    nm = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !(nm >= 100.0 && nm <= 5000.0))
    r.fail(key, "wavelength key \"" + text + "\" must be a number of nanometres in [100, 5000]");
  return nm;
}

void reject_unknown_keys(const JsonReader& r, const nlohmann::json& object,
                         std::initializer_list<std::string_view> allowed, std::string_view docs_page) {
  if (!object.is_object()) return;
  for (const auto& [key, value] : object.items()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::ostringstream s;
    s << "unknown key (check the spelling); allowed here: ";
    for (auto it = allowed.begin(); it != allowed.end(); ++it) s << (it == allowed.begin() ? "" : ", ") << *it;
    s << " (see " << docs_page << ")";
    r.fail(key, s.str());
  }
}

}  // namespace config
}  // namespace zenith
