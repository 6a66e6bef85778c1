#pragma once
// The JSON of a `zenith cluster check --json` run whose standard output and
// log lines went to one file: the log lines (spdlog, each starting with '['),
// then the JSON object. Shared by the loopback and the rig tests.
#include <string>

#include <nlohmann/json.hpp>

namespace zenith::testing {

/// The JSON after the log lines of `output`; a discarded value (not an object) when there is none.
inline nlohmann::json check_json(const std::string& output) {
  const std::size_t start = output.starts_with("{") ? 0 : output.find("\n{\n");
  if (start == std::string::npos) return nullptr;
  return nlohmann::json::parse(output.substr(start), nullptr, false);
}

}  // namespace zenith::testing
