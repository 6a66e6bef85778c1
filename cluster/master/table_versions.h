#pragma once
// The master's table versions (docs/cluster.md, "Shared tables" and "Table
// versions"): every table set prepared so far, the current version of every
// atmosphere as FrameStates carry it, and at most one pending version on its
// way to the nodes. Bookkeeping only: preparing sets (cache or precompute)
// and sending them are the master's.
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cluster/protocol/messages.h"
#include "cluster/protocol/table_transfer.h"
#include "show/show.h"

namespace zenith::cluster {

/// Invariants: every version named by current(), pending() or an override
/// has a set (once prepared) and a definition; at most one version is
/// pending. Without a show, current() is what every FrameState carries and a
/// pending version replaces an entry of it. With a show, the show's frames
/// carry its own versions; the sets a node must hold are the show's sets
/// prepared so far (its plan is fixed before the first frame; they are
/// prepared in the background, in order of first use) and every operator
/// override in effect, and a pending version becomes an override: from its
/// frame on, it replaces the body's version in every frame of the show
/// (with_overrides) until cleared (docs/operator.md, "set during a show").
class TableVersions {
 public:
  using Clock = std::chrono::steady_clock;

  /// A new version of one atmosphere on its way: prepared while frames go on
  /// with the old one, then sent to every node; it takes effect once every
  /// ready node sent TableReady for it.
  struct Pending {
    std::size_t ref_index = 0;  ///< into current()
    Digest hash{};
    bool distributed = false;  ///< prepared and sent to the nodes
    Clock::time_point distributed_at{};
  };

  // ---- versions and their sets ----
  /// Remembers a version (idempotent) and encodes its AtmosphereDefinition.
  void add_version(const std::string& body, const atmosphere::LoadedAtmosphere& loaded, const Digest& hash);
  /// A version added before; throws std::out_of_range otherwise.
  const show::AtmosphereVersion& version(const Digest& hash) const { return versions_.at(hash); }
  /// The encoded AtmosphereDefinition of a version; nullptr for an unknown one.
  std::shared_ptr<const std::vector<std::uint8_t>> definition(const Digest& hash) const;
  /// Keeps a prepared set (replacing one of the same hash).
  void add_set(TableSetFile set);
  bool has_set(const Digest& hash) const { return sets_.count(hash) > 0; }
  /// A prepared set; throws std::out_of_range otherwise.
  const TableSetFile& set(const Digest& hash) const { return sets_.at(hash); }

  // ---- current versions ----
  /// The current version of every atmosphere, in scene order, as FrameStates carry it.
  const std::vector<AtmosphereTableRef>& current() const { return current_; }
  /// Adds the next atmosphere's version, effective from `effective_from_frame`
  /// (0 at the start; a standby that takes over keeps the active master's).
  void add_current(const std::string& body, const Digest& hash, std::uint64_t effective_from_frame = 0);
  /// A show: these sets are every one it uses, in the order they are
  /// prepared; `current` the versions of its first frame (every body with an
  /// atmosphere, in scene order: the indices of begin_pending). A set counts
  /// for the nodes once it is prepared (add_set).
  void use_show_sets(std::vector<Digest> sets, std::vector<AtmosphereTableRef> current);
  /// Whether a show is played (use_show_sets).
  bool show_mode() const { return show_sets_.has_value(); }
  /// Whether `hash` is one of the show's own sets.
  bool is_show_set(const Digest& hash) const;
  /// The sets a node must be sent: the show's prepared so far and the
  /// operator's overrides, or the current versions; and a distributed pending one.
  std::vector<Digest> wanted_sets() const;
  /// A node that holds `held` (TableReady) holds every current version, every
  /// set of the show prepared so far and every override.
  bool ready_with(const std::set<Digest>& held) const;

  // ---- the operator's overrides of a show's atmospheres ----
  /// Show: the operator's version of atmosphere current()[index] and the
  /// frame it took effect at; nullopt: the show's own.
  const std::optional<AtmosphereTableRef>& override_of(std::size_t index) const { return overrides_.at(index); }
  /// Show: a frame's versions with every override in place of the body's
  /// (matched by body name).
  std::vector<AtmosphereTableRef> with_overrides(std::vector<AtmosphereTableRef> refs) const;
  /// Show: atmosphere current()[index] follows the show's track again; its
  /// override's set stays kept.
  void clear_override(std::size_t index) { overrides_.at(index).reset(); }

  // ---- the pending version ----
  const std::optional<Pending>& pending() const { return pending_; }
  /// Version `hash` of atmosphere current()[ref_index] starts on its way. Precondition: none pending.
  void begin_pending(std::size_t ref_index, const Digest& hash);
  /// The pending version was prepared and sent to the nodes at `now`.
  void mark_distributed(Clock::time_point now);
  /// The pending version could not be prepared: the show goes on with the current one.
  void abandon_pending() { pending_.reset(); }
  /// The pending version takes effect from `frame`: it becomes the current
  /// version of its atmosphere, or with a show its override. Returns the
  /// reference it replaces (with a show: the override before, else the
  /// show's first frame's). Precondition: a pending version.
  AtmosphereTableRef apply_pending(std::uint64_t frame);

 private:
  std::map<Digest, TableSetFile> sets_;  ///< current, pending and superseded versions, by table hash
  std::vector<AtmosphereTableRef> current_;
  std::optional<std::vector<Digest>> show_sets_;
  std::optional<Pending> pending_;
  std::vector<std::optional<AtmosphereTableRef>> overrides_;  ///< show: one per current() entry
  /// Every version prepared so far (the scene's, switches', the show's): for
  /// AtmosphereDefinitions and the recording.
  std::map<Digest, show::AtmosphereVersion> versions_;
  std::map<Digest, std::shared_ptr<const std::vector<std::uint8_t>>> definitions_;
};

}  // namespace zenith::cluster
