#include "cluster/node/known_atmospheres.h"

#include <spdlog/spdlog.h>

#include <fstream>

#include "atmosphere/model_hash.h"
#include "cluster/link/atmosphere_definition.h"
#include "cluster/protocol/table_transfer.h"
#include "core/json_reader.h"
#include "core/strings.h"

namespace zenith::cluster {

using core::cat;

KnownAtmospheres::KnownAtmospheres(const scene::Scene& scene, std::filesystem::path cache_directory,
                                   std::string node_name)
    : scene_(scene), cache_directory_(std::move(cache_directory)), node_name_(std::move(node_name)) {}

void KnownAtmospheres::add_scene_and_candidates(const std::vector<std::filesystem::path>& atmosphere_files) {
  const atmosphere::LoadOptions load_options{scene_.wavelengths_nm};
  std::vector<atmosphere::LoadedAtmosphere> candidates;
  for (const std::string& name : atmosphere::preset_names()) {
    try {
      candidates.push_back(atmosphere::load_preset(name, load_options));
    } catch (const std::exception& e) {
      spdlog::debug("node '{}': preset {} not usable here: {}", node_name_, name, e.what());
    }
  }
  for (const std::filesystem::path& file : atmosphere_files)
    candidates.push_back(atmosphere::load_atmosphere_file(file.string(), load_options));  // errors are fatal
  std::lock_guard lock(mutex_);
  for (const scene::Body& body : scene_.bodies) {
    if (!body.atmosphere) continue;
    auto add = [&](const atmosphere::LoadedAtmosphere& loaded) {
      entries_.emplace(digest_from_hex(atmosphere::lookup_table_hash(loaded.model)), Entry{body.name, loaded});
    };
    add(body.atmosphere->loaded);
    for (const atmosphere::LoadedAtmosphere& c : candidates)
      if (fits_body(c, body)) add(c);
  }
}

void KnownAtmospheres::define(const AtmosphereDefinition& d, bool keep) {
  atmosphere::LoadedAtmosphere loaded = resolve_definition(d, scene_);
  const Digest hash = d.table_hash;  // resolve_definition checked it
  bool added = false;
  {
    std::lock_guard lock(mutex_);
    added = entries_.emplace(hash, Entry{d.body_name, std::move(loaded)}).second;
  }
  if (added)
    spdlog::debug("node '{}': atmosphere version {} of '{}' defined", node_name_, short_hex(hash), d.body_name);
  if (keep && added) {
    std::filesystem::create_directories(definitions_directory());
    const std::string text =
        nlohmann::json{{"body", d.body_name}, {"parameters", nlohmann::json::parse(d.parameters_json)}}.dump(1);
    write_file_atomically(definitions_directory() / (to_hex(hash) + ".json"),
                          std::vector<std::uint8_t>(text.begin(), text.end()));
  }
}

void KnownAtmospheres::load_kept_definitions() {
  std::error_code ec;
  if (!std::filesystem::is_directory(definitions_directory(), ec)) return;
  for (const auto& entry : std::filesystem::directory_iterator(definitions_directory(), ec)) {
    if (entry.path().extension() != ".json") continue;
    try {
      std::ifstream in(entry.path());
      const nlohmann::json kept = nlohmann::json::parse(in);
      define(AtmosphereDefinition{kept.at("body").get<std::string>(), digest_from_hex(entry.path().stem().string()),
                                  kept.at("parameters").dump()},
             false);
    } catch (const std::exception& e) {
      spdlog::debug("node '{}': kept definition {} not used: {}", node_name_, entry.path().string(), e.what());
    }
  }
}

const KnownAtmospheres::Entry& KnownAtmospheres::find(const Digest& hash) const {
  std::lock_guard lock(mutex_);
  return entries_.at(hash);
}

bool KnownAtmospheres::knows(const Digest& hash) const {
  std::lock_guard lock(mutex_);
  return entries_.count(hash) > 0;
}

std::map<Digest, KnownAtmospheres::Entry> KnownAtmospheres::snapshot() const {
  std::lock_guard lock(mutex_);
  return entries_;
}

}  // namespace zenith::cluster
