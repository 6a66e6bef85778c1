#pragma once
// The operator's changes to the atmospheres of a show file (docs/operator.md,
// "set during a show"): per body, the parameter changes of every `set` so
// far, applied on top of whatever version the show's track gives the body. A
// body with changes is overridden: from the frame its first operator version
// takes effect, it renders the show's parameters with the operator's changes
// applied, and it follows the show's track with them (a new version when the
// track moves on) until `clear`. Which show version the latest operator
// version was built on is kept here too, so the master sees when the track
// has moved on. Bookkeeping only: resolving, preparing and switching versions
// are AtmosphereEdits', the table preparer's and TableVersions'.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cluster/operator/operator_command.h"
#include "cluster/protocol/messages.h"

namespace zenith::cluster {

/// Invariant: a body's changes name each pointer once, in the order first
/// set; a body without changes has no base.
class AtmosphereOverrides {
 public:
  /// Whether the operator changed `body`'s atmosphere (and has not cleared it).
  bool active(const std::string& body) const { return changes_.count(body) > 0; }
  /// `parameters` (a show version's) with `body`'s changes applied in order.
  /// Throws std::invalid_argument (show::write_parameter's) when a change no
  /// longer fits them (a pointer through a key the version lacks).
  nlohmann::json apply(const std::string& body, nlohmann::json parameters) const;
  /// Records a `set` (checked by the caller): it replaces an earlier change
  /// of the same pointer.
  void add(const operator_command::Set& set);
  /// "/aerosol/scattering/turbidity = 3, /ozone = removed"; "" without changes.
  std::string describe(const std::string& body) const;
  /// Forgets `body`'s changes and base: it follows the show's track again.
  void clear(const std::string& body);

  /// The show version `body`'s latest operator version is built on.
  std::optional<Digest> base(const std::string& body) const;
  void set_base(const std::string& body, const Digest& show_version);

 private:
  struct Change {
    nlohmann::json::json_pointer pointer;
    nlohmann::json value;  ///< null removes the key
  };
  std::map<std::string, std::vector<Change>> changes_;
  std::map<std::string, Digest> bases_;
};

}  // namespace zenith::cluster
