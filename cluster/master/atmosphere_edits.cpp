#include "cluster/master/atmosphere_edits.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "core/json_reader.h"
#include "core/strings.h"
#include "show/parameter_track.h"

namespace zenith::cluster {

using config::brief;
using core::cat;

AtmosphereEdits::AtmosphereEdits(scene::Scene scene) : scene_(std::move(scene)) {
  for (const scene::Body& body : scene_.bodies)
    if (body.atmosphere) bodies_.push_back(body.name);
}

std::size_t AtmosphereEdits::index_of(const std::string& body) const {
  const auto it = std::find(bodies_.begin(), bodies_.end(), body);
  if (it != bodies_.end()) return static_cast<std::size_t>(it - bodies_.begin());
  std::string list;
  for (const std::string& b : bodies_) list += cat(list.empty() ? "" : ", ", "'", b, "'");
  throw std::invalid_argument(
      cat("command: /body = ", brief(nlohmann::json(body)), ": the scene ", scene_.source,
          " has no body of that name with an atmosphere (bodies with one: ", list.empty() ? "none" : list, ")"));
}

AtmosphereEdits::Edit AtmosphereEdits::resolve(const operator_command::Set& set,
                                               const nlohmann::json& parameters) const {
  index_of(set.body);  // an unknown body first, before the pointer
  // The tables are resolved at the scene's wavelengths, which override the
  // parameters' own: a change there would be ignored (and "banana" once
  // answered ok), so it is refused.
  if (!set.pointer.empty() && set.pointer.to_string().starts_with("/wavelengths_nm") &&
      (set.pointer.to_string().size() == 15 || set.pointer.to_string()[15] == '/'))
    throw std::invalid_argument(cat("set ", set.body, ": ", set.pointer.to_string(), " = ", brief(set.value),
                                    ": the wavelengths are the scene's (", scene_.source,
                                    "), not a live parameter: every table and node uses them"));
  nlohmann::json changed = parameters;
  try {
    show::write_parameter(changed, set.pointer, set.value);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(cat("command: /pointer: ", e.what(), " (in the atmosphere parameters of '", set.body,
                                    "'; docs/atmosphere-config.md)"));
  }
  const std::string change =
      cat(set.pointer.to_string(), " = ", set.value.is_null() ? std::string("removed") : brief(set.value));
  return resolve_parameters(set.body, changed, change);
}

AtmosphereEdits::Edit AtmosphereEdits::resolve_parameters(const std::string& body, const nlohmann::json& parameters,
                                                          const std::string& change) const {
  Edit edit;
  edit.index = index_of(body);
  edit.body = body;
  // The same loader as a file, at the scene's wavelengths: its errors name the pointer and the range.
  edit.loaded = atmosphere::resolve_atmosphere(parameters, cat("set ", body), {scene_.wavelengths_nm});
  scene::Scene with_edit = scene_;
  for (scene::Body& b : with_edit.bodies)
    if (b.name == body) b.atmosphere->loaded = edit.loaded;
  try {
    scene::check_scene(with_edit);
  } catch (const std::exception& e) {
    throw std::invalid_argument(
        cat("set ", body, ": ", change, ": the atmosphere no longer fits its body: ", e.what()));
  }
  edit.change = change;
  return edit;
}

AtmosphereEdits::Edit AtmosphereEdits::original(const std::string& body) const {
  Edit edit;
  edit.index = index_of(body);
  edit.body = body;
  for (const scene::Body& b : scene_.bodies)
    if (b.name == body) edit.loaded = b.atmosphere->loaded;
  edit.change = "the scene's own atmosphere";
  return edit;
}

void AtmosphereEdits::enqueue(Edit edit) {
  for (Edit& waiting : queue_) {
    if (waiting.body != edit.body) continue;
    edit.change = cat(waiting.change, ", ", edit.change);
    waiting = std::move(edit);
    return;
  }
  queue_.push_back(std::move(edit));
}

std::optional<AtmosphereEdits::Edit> AtmosphereEdits::take_next() {
  if (queue_.empty()) return std::nullopt;
  Edit next = std::move(queue_.front());
  queue_.pop_front();
  return next;
}

bool AtmosphereEdits::drop(const std::string& body) {
  return std::erase_if(queue_, [&](const Edit& e) { return e.body == body; }) > 0;
}

const AtmosphereEdits::Edit* AtmosphereEdits::waiting(const std::string& body) const {
  for (const Edit& e : queue_)
    if (e.body == body) return &e;
  return nullptr;
}

}  // namespace zenith::cluster
