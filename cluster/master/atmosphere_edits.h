#pragma once
// The operator's live changes to the atmospheres of the default show or of a
// show file (docs/operator.md, "Live atmosphere parameters", "set during a
// show"; a show's changes are kept by AtmosphereOverrides). A `set` command names a
// body, a JSON pointer into its atmosphere parameters and a value; the change
// is written into the body's latest parameter set and the result goes through
// the same loader as an atmosphere file (atmosphere::resolve_atmosphere, at the
// scene's wavelengths) and the same scene check as an AtmosphereSwitch (the
// body's radius), so a bad value is refused with the loader's message naming
// the pointer and its range, and nothing is applied. An accepted change waits
// here for its turn to become a table version (the master prepares one version
// at a time, docs/cluster.md "Table versions"). No tables, no sockets.
#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "atmosphere/parameters.h"
#include "cluster/operator/operator_command.h"
#include "scene/scene.h"

namespace zenith::cluster {

/// Invariant: at most one waiting edit per body (a later edit of the same
/// body replaces it and includes its change), in the order first asked for.
class AtmosphereEdits {
 public:
  /// One body's new atmosphere, checked and resolved.
  struct Edit {
    std::size_t index =
        0;  ///< the body's place among the scene's atmospheres (scene order, as TableVersions::current())
    std::string body;
    atmosphere::LoadedAtmosphere loaded;  ///< at the scene's wavelengths; `parameters` is the whole new set
    std::string change;                   ///< "/aerosol/scattering/turbidity = 3" (several joined by ", ")
  };

  /// The scene whose atmospheres are edited (the master's).
  explicit AtmosphereEdits(scene::Scene scene);

  /// The bodies that have an atmosphere, in scene order.
  const std::vector<std::string>& bodies() const { return bodies_; }
  /// The place of `body` among bodies(). Throws std::invalid_argument naming
  /// the body and listing those with an atmosphere.
  std::size_t index_of(const std::string& body) const;

  /// The edit `set` makes to `parameters` (the body's latest parameter set:
  /// its waiting edit's, else its pending or current version's). Throws
  /// zenith::ConfigError from the atmosphere loader (source "set BODY", the
  /// pointer, the value and the range) and std::invalid_argument for an
  /// unknown body, a pointer that cannot be written or an atmosphere that
  /// does not fit its body.
  Edit resolve(const operator_command::Set& set, const nlohmann::json& parameters) const;
  /// A whole new parameter set of `body`, checked the same way (source "set
  /// BODY"); `change` describes it. Throws as resolve().
  Edit resolve_parameters(const std::string& body, const nlohmann::json& parameters, const std::string& change) const;
  /// The scene's own atmosphere of `body` as an edit (`clear` in the default
  /// show). Throws std::invalid_argument for an unknown body.
  Edit original(const std::string& body) const;

  /// Queues an edit; it replaces the waiting edit of the same body (keeping
  /// that one's place and joining the two changes' descriptions).
  void enqueue(Edit edit);
  /// The edit whose turn it is, removed from the queue; nullopt when none waits.
  std::optional<Edit> take_next();
  /// The waiting edit of `body`, nullptr when none.
  const Edit* waiting(const std::string& body) const;
  /// Drops the waiting edit of `body` (if any); true when there was one.
  bool drop(const std::string& body);
  std::size_t waiting_count() const { return queue_.size(); }

 private:
  scene::Scene scene_;
  std::vector<std::string> bodies_;
  std::deque<Edit> queue_;
};

}  // namespace zenith::cluster
