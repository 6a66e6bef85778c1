#pragma once
// Writing show files for the tests.
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/json_reader.h"
#include "tests/scratch_folder.h"

namespace zenith::show::test {

inline std::filesystem::path scene_file(const std::string& name) {
  return std::filesystem::path(ZENITH_SOURCE_DIR) / "configs" / "scenes" / (name + ".json");
}

/// A fresh folder for one test, removed when the test process ends.
inline std::filesystem::path temp_folder(const std::string& test) {
  const auto dir = zenith::testing::process_scratch_folder() / "show" / test;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::filesystem::path write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// A minimal keyframed show on `scene` (absolute path), plus `extra` keys.
inline nlohmann::json minimal_show(const std::string& scene, nlohmann::json extra = nlohmann::json::object()) {
  nlohmann::json show = {{"zenith_show", 1}, {"name", "test"}, {"scene", scene_file(scene).string()}};
  for (const auto& [key, value] : extra.items()) show[key] = value;
  return show;
}

}  // namespace zenith::show::test
