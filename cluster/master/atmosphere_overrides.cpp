#include "cluster/master/atmosphere_overrides.h"

#include <algorithm>

#include "core/json_reader.h"
#include "core/strings.h"
#include "show/parameter_track.h"

namespace zenith::cluster {

using config::brief;
using core::cat;

nlohmann::json AtmosphereOverrides::apply(const std::string& body, nlohmann::json parameters) const {
  const auto it = changes_.find(body);
  if (it == changes_.end()) return parameters;
  for (const Change& change : it->second) show::write_parameter(parameters, change.pointer, change.value);
  return parameters;
}

void AtmosphereOverrides::add(const operator_command::Set& set) {
  std::vector<Change>& changes = changes_[set.body];
  const auto same =
      std::find_if(changes.begin(), changes.end(), [&](const Change& c) { return c.pointer == set.pointer; });
  if (same != changes.end())
    same->value = set.value;
  else
    changes.push_back({set.pointer, set.value});
}

std::string AtmosphereOverrides::describe(const std::string& body) const {
  const auto it = changes_.find(body);
  if (it == changes_.end()) return "";
  std::string text;
  for (const Change& c : it->second)
    text += cat(text.empty() ? "" : ", ", c.pointer.to_string(), " = ",
                c.value.is_null() ? std::string("removed") : brief(c.value));
  return text;
}

void AtmosphereOverrides::clear(const std::string& body) {
  changes_.erase(body);
  bases_.erase(body);
}

std::optional<Digest> AtmosphereOverrides::base(const std::string& body) const {
  const auto it = bases_.find(body);
  return it == bases_.end() ? std::nullopt : std::optional<Digest>(it->second);
}

void AtmosphereOverrides::set_base(const std::string& body, const Digest& show_version) {
  if (active(body)) bases_[body] = show_version;
}

}  // namespace zenith::cluster
