#include "cluster/master/table_schedule.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>

#include "atmosphere/lut/table_cache.h"
#include "atmosphere/model_hash.h"
#include "atmosphere/named_inputs.h"
#include "cluster/master/takeover.h"
#include "core/strings.h"
#include "render/lut/table_provider.h"
#include "show/table_plan.h"

namespace zenith::cluster {

using core::cat;

TableSchedule::TableSchedule(Options options, const scene::Scene& scene, const show::Show* show, NodeSessions& sessions,
                             const FrameBarrier& barrier, Actions actions)
    : options_(std::move(options)),
      scene_(scene),
      show_(show),
      sessions_(sessions),
      barrier_(barrier),
      actions_(std::move(actions)) {
  std::stable_sort(options_.switches.begin(), options_.switches.end(),
                   [](const AtmosphereSwitch& a, const AtmosphereSwitch& b) { return a.frame < b.frame; });
  if (options_.operator_changes) edits_.emplace(scene_);
}

render::TableRequest TableSchedule::request_for(const ClusterConfig& config,
                                                const std::optional<std::filesystem::path>& cache_directory,
                                                bool cpu_precompute) {
  render::TableRequest request;
  atmosphere::apply_table_set(config.table_sizes, request.options);
  request.options.max_orders = config.table_orders;
  request.backend = cpu_precompute ? render::PrecomputeBackend::Cpu : render::PrecomputeBackend::Gpu;
  request.cache_directory = cache_directory;
  request.show_progress = false;
  return request;
}

double TableSchedule::ms_since(Clock::time_point t) const {
  return std::chrono::duration<double, std::milli>(actions_.now() - t).count();
}

double TableSchedule::confirmation_limit_ms() const {
  return std::max(60000.0, static_cast<double>(options_.barrier_timeout_ms));
}

TablePreparer::Job TableSchedule::job(const std::string& body, const atmosphere::AtmosphereModel& model) const {
  return TablePreparer::Job{body, digest_from_hex(atmosphere::lookup_table_hash(model)), model, options_.request};
}

// ---------------------------------------------------------------------------- before the first frame

/// The atmosphere a switch names, resolved at the scene's wavelengths and
/// checked against its body. Throws std::invalid_argument / ConfigError.
std::pair<std::size_t, atmosphere::LoadedAtmosphere> TableSchedule::resolve_switch(const AtmosphereSwitch& sw) const {
  // tables_.current() lists the bodies with an atmosphere in scene order (prepare_initial).
  std::optional<std::size_t> index;
  std::size_t with_atmosphere = 0;
  for (const scene::Body& body : scene_.bodies) {
    if (!body.atmosphere) continue;
    if (body.name == sw.body) index = with_atmosphere;
    ++with_atmosphere;
  }
  if (!index)
    throw std::invalid_argument(cat("atmosphere switch at frame ", sw.frame, ": the scene ", scene_.source,
                                    " has no body '", sw.body, "' with an atmosphere"));
  atmosphere::LoadedAtmosphere loaded = atmosphere::load_atmosphere_argument(sw.atmosphere, {scene_.wavelengths_nm});
  scene::Scene changed = scene_;
  for (scene::Body& body : changed.bodies)
    if (body.name == sw.body) body.atmosphere->loaded = loaded;
  try {
    scene::check_scene(changed);
  } catch (const std::exception& e) {
    throw std::invalid_argument(
        cat("atmosphere switch at frame ", sw.frame, " (", sw.body, ": ", sw.atmosphere, "): ", e.what()));
  }
  return {*index, std::move(loaded)};
}

void TableSchedule::check_switches() const {
  for (const AtmosphereSwitch& sw : options_.switches) resolve_switch(sw);
}

void TableSchedule::prepare_initial(const std::function<TableSetFile(const TablePreparer::Job&)>& obtain) {
  if (show_) return prepare_show_sets();
  for (const scene::Body& body : scene_.bodies) {
    if (!body.atmosphere) continue;
    TableSetFile set = obtain(job(body.name, body.atmosphere->loaded.model));
    tables_.add_current(body.name, set.table_hash);
    tables_.add_version(body.name, body.atmosphere->loaded, set.table_hash);
    spdlog::info("master: tables of '{}' ready to share: version {} ({} bytes, sha256 {}…)", body.name,
                 short_hex(set.table_hash), set.bytes->size(), to_hex(set.content_sha256).substr(0, 12));
    tables_.add_set(std::move(set));
  }
}

/// With a show: reports its table plan and hands every set it uses to the
/// preparer, in order of first use. Frame 0 starts once its own sets are
/// ready (offline) or once the rest are predicted ready in time (live:
/// ShowStartRule); the later sets reach the nodes while frames go on.
void TableSchedule::prepare_show_sets() {
  const render::TableRequest& request = options_.request;
  const show::TablePlan plan = show::plan_tables(
      *show_, options_.fps, request.options,
      atmosphere::lut::TableCache(request.cache_directory.value_or(atmosphere::lut::default_cache_directory())));
  spdlog::info("master: show '{}' at {} fps needs {} table set{} ({} to precompute):\n{}", show_->name(), options_.fps,
               plan.sets.size(), plan.sets.size() == 1 ? "" : "s", plan.missing(), show::describe(plan));
  std::vector<Digest> show_sets;
  std::vector<ShowStartRule::Set> schedule;
  for (const show::TablePlanEntry& entry : plan.sets) {
    tables_.add_version(entry.version.body, entry.version.loaded, entry.version.table_hash);
    show_sets.push_back(entry.version.table_hash);
    const bool held = tables_.has_set(entry.version.table_hash);  // a standby's, from the active master
    schedule.push_back({entry.version.table_hash, entry.first_frame, entry.cached, held});
    if (!held) actions_.prepare(job(entry.version.body, entry.version.loaded.model));
  }
  tables_.use_show_sets(std::move(show_sets), show_->state_at(0.0, 0, 0).atmospheres);
  show_start_.emplace(std::move(schedule), options_.fps, options_.paced);
  spdlog::info("master: preparing the show's table sets in the background; frame 0 starts {}",
               options_.paced ? "once the sets it uses are ready and the others are predicted ready before they "
                                "are needed"
                              : "once the sets it uses are ready");
}

void TableSchedule::adopt_takeover(const TakeoverState& state) {
  adopt_takeover_tables(state, scene_, tables_, show_ == nullptr);
  if (show_) prepare_show_sets();  // the sets not received are prepared as at the start
}

bool TableSchedule::may_start() const { return !show_start_ || show_start_->may_start(); }

// ---------------------------------------------------------------------------- results of the preparer

void TableSchedule::on_set_prepared(TableSetFile set, double seconds, bool from_cache) {
  if (stopped_) return;
  if (!show_start_ || !tables_.is_show_set(set.table_hash)) {  // a switch or an operator's version
    on_version_prepared(std::move(set));
    return;
  }
  const Digest hash = set.table_hash;
  const auto& sets = show_start_->sets();
  const auto index =
      std::find_if(sets.begin(), sets.end(), [&](const auto& e) { return e.table_hash == hash; }) - sets.begin() + 1;
  show_start_->prepared(hash, seconds, from_cache);
  tables_.add_set(std::move(set));
  const TableSetFile& prepared = tables_.set(hash);
  show_set_sent_at_[hash] = actions_.now();
  std::size_t receivers = 0;
  sessions_.for_each([&](NodeSession& s) {
    if (s.state == NodeSession::State::handshake || !s.inventory_done) return;  // gets it with its inventory
    send_set(s, prepared);
    ++receivers;
  });
  spdlog::info("master: table set {} of {} ('{}', version {}) ready ({:.1f} s, {}); sent to {} node{}", index,
               sets.size(), prepared.body_name, short_hex(hash), seconds, from_cache ? "from the cache" : "precomputed",
               receivers, receivers == 1 ? "" : "s");
  // An operator's version that is one of the show's own was waiting for it.
  if (tables_.pending() && tables_.pending()->hash == hash && !tables_.pending()->distributed)
    on_version_prepared(std::nullopt);
  every_node_maybe_ready();
  actions_.show_set_ready();
  if (!actions_.started() && !show_start_->may_start() &&
      std::none_of(sets.begin(), sets.end(), [](const auto& e) { return e.first_frame == 0 && !e.prepared; })) {
    const std::optional<double> remaining = show_start_->predicted_remaining_s();
    spdlog::info(
        "master: live show: frame 0 waits until the remaining table sets are predicted ready before they "
        "are needed ({}), so that playback does not stall",
        remaining ? fmt::format("about {:.0f} s of preparation left", *remaining) : "no estimate yet");
  }
}

/// A show cannot go on without a set (the master stops and rethrows); a
/// switch of the default show is abandoned and the show goes on with the
/// current version.
void TableSchedule::on_set_failed(const Digest& hash, std::exception_ptr error) {
  if (stopped_) return;
  std::string what = "unknown error";
  try {
    std::rethrow_exception(error);
  } catch (const std::exception& e) {
    what = e.what();
  } catch (...) {
  }
  if (show_start_ && tables_.is_show_set(hash)) {
    actions_.show_failed(cat("table set ", short_hex(hash), " of the show could not be prepared: ", what), error);
    return;
  }
  if (!tables_.pending() || tables_.pending()->hash != hash) return;  // abandoned meanwhile (clear)
  spdlog::error("master: the new tables could not be prepared: {}; the show goes on with the current version", what);
  last_error_ = cat("table version ", short_hex(hash), " (", pending_change_, "): ", what);
  tables_.abandon_pending();
  maybe_start_switch();
}

// ---------------------------------------------------------------------------- the nodes

/// Sends one set: the whole transfer, or only its TableAnnounce when the
/// node's inventory holds it (the node then loads its cached copy).
void TableSchedule::send_set(NodeSession& s, const TableSetFile& set) {
  if (auto definition = tables_.definition(set.table_hash)) {
    actions_.send(s, definition);
    s.table_bytes_sent += definition->size();
  }
  if (s.cached.count(set.table_hash)) {
    actions_.send(s, set.frames.front());
    s.table_bytes_sent += set.frames.front()->size();
    return;
  }
  for (const auto& f : set.frames) {
    actions_.send(s, f);
    s.table_bytes_sent += f->size();
  }
  s.chunks_sent += set.frames.size() - 1;
}

void TableSchedule::finish_inventory(NodeSession& s) {
  s.inventory_done = true;
  s.inventory_done_at = std::chrono::steady_clock::now();
  const std::vector<Digest> wanted = tables_.wanted_sets();
  const std::uint64_t chunks_before = s.chunks_sent;
  std::size_t cached = 0;
  for (const Digest& h : wanted) {
    cached += s.cached.count(h);
    send_set(s, tables_.set(h));
  }
  spdlog::info("master: {} '{}' holds {} of its {} table set{} in its cache: sent {} table chunk{}", to_string(s.role),
               s.name, cached, wanted.size(), wanted.size() == 1 ? "" : "s", s.chunks_sent - chunks_before,
               s.chunks_sent - chunks_before == 1 ? "" : "s");
  maybe_become_ready(s);
}

bool TableSchedule::on_table_ready(NodeSession& s, const Digest& hash) {
  if (!tables_.has_set(hash)) return false;
  s.tables_ready.insert(hash);
  maybe_become_ready(s);
  maybe_apply_pending();
  return true;
}

void TableSchedule::maybe_become_ready(NodeSession& s) {
  if (s.state != NodeSession::State::tables || !s.inventory_done || s.role != PeerRole::node) return;
  if (tables_.ready_with(s.tables_ready)) actions_.node_ready(s);
}

void TableSchedule::every_node_maybe_ready() {
  for (const std::uint32_t id : sessions_.ids())
    if (NodeSession* s = sessions_.find(id)) maybe_become_ready(*s);
}

/// A ready node that does not confirm a distributed version within the limit
/// would hold the switch back forever: it is disconnected with a log line
/// naming it, the switch goes ahead on the others, and the node rejoins at a
/// frame boundary with the new version when it reconnects.
void TableSchedule::check_confirmations() {
  if (!tables_.pending() || !tables_.pending()->distributed || stopped_) return;
  const Digest hash = tables_.pending()->hash;
  const double limit_ms = confirmation_limit_ms();
  if (ms_since(tables_.pending()->distributed_at) <= limit_ms) return;
  std::vector<std::uint32_t> late;
  sessions_.for_each([&](const NodeSession& s) {
    if (s.state == NodeSession::State::ready && !s.tables_ready.count(hash)) {
      spdlog::warn(
          "master: node '{}' did not confirm table version {} within {:.0f} ms: disconnecting it so the "
          "switch can take effect (it rejoins with the new version when it reconnects)",
          s.name, short_hex(hash), limit_ms);
      late.push_back(s.id);
    }
  });
  for (const std::uint32_t id : late)
    if (NodeSession* s = sessions_.find(id)) actions_.close(*s, "table version not confirmed in time");
  maybe_apply_pending();
}

// ---------------------------------------------------------------------------- the frames

Digest TableSchedule::effective_version(std::size_t index) const {
  if (!show_) return tables_.current()[index].table_hash;
  if (const auto& o = tables_.override_of(index)) return o->table_hash;
  return show_version_of(index).table_hash;
}

/// A show: the show's own version of atmosphere current()[index] in the
/// latest frame started (before frame 0: the first frame's).
const AtmosphereTableRef& TableSchedule::show_version_of(std::size_t index) const {
  const std::string& body = tables_.current()[index].body_name;
  for (const AtmosphereTableRef& ref : show_versions_)
    if (ref.body_name == body) return ref;
  return tables_.current()[index];
}

/// The newest version asked for atmosphere current()[index]: its waiting
/// change's, else its pending version, else the one it renders with.
Digest TableSchedule::latest_version(std::size_t index) const {
  if (const AtmosphereEdits::Edit* waiting = edits_->waiting(tables_.current()[index].body_name))
    return digest_from_hex(atmosphere::lookup_table_hash(waiting->loaded.model));
  if (tables_.pending() && tables_.pending()->ref_index == index) return tables_.pending()->hash;
  return effective_version(index);
}

void TableSchedule::apply_overrides(FrameState& state) {
  show_versions_ = state.atmospheres;
  for (const AtmosphereTableRef& ref : show_versions_) {
    const std::string& body = ref.body_name;
    if (!overrides_.active(body) || overrides_.base(body) == ref.table_hash) continue;
    const std::size_t index = edits_->index_of(body);
    // A change on its way was built on an earlier show version: follow once it is in.
    if (edits_->waiting(body) || (tables_.pending() && tables_.pending()->ref_index == index)) continue;
    overrides_.set_base(body, ref.table_hash);
    try {
      AtmosphereEdits::Edit edit = edits_->resolve_parameters(
          body, overrides_.apply(body, tables_.version(ref.table_hash).parameters),
          cat("the show's version ", short_hex(ref.table_hash), " with ", overrides_.describe(body)));
      if (digest_from_hex(atmosphere::lookup_table_hash(edit.loaded.model)) == effective_version(index)) continue;
      spdlog::info("master: the show's track of '{}' moved on to version {}: preparing it with the operator's changes",
                   body, short_hex(ref.table_hash));
      edits_->enqueue(std::move(edit));
    } catch (const std::exception& e) {
      spdlog::warn(
          "master: the show's track of '{}' moved on to version {}, but the operator's changes do not fit "
          "it ({}); '{}' keeps the operator's version until cleared",
          body, short_hex(ref.table_hash), e.what(), body);
    }
  }
  state.atmospheres = tables_.with_overrides(std::move(state.atmospheres));
  maybe_start_switch();
}

void TableSchedule::maybe_start_switch() {
  if (tables_.pending()) return;
  if (next_switch_ < options_.switches.size() && options_.switches[next_switch_].frame <= barrier_.frame()) {
    const AtmosphereSwitch& sw = options_.switches[next_switch_++];
    auto [index, loaded] = resolve_switch(sw);  // checked at start-up: does not throw here
    begin_version(index, std::move(loaded), cat("frame ", barrier_.frame()), sw.atmosphere);
  } else if (std::optional<AtmosphereEdits::Edit> edit = edits_ ? edits_->take_next() : std::nullopt) {
    begin_version(edit->index, std::move(edit->loaded), "operator", edit->change);
  }
}

/// Atmosphere current()[index] is to become `loaded` (`why`: when or who
/// asked; `what`: the preset, file or change, for the log): prepares its
/// table version in the background unless it is the current one.
void TableSchedule::begin_version(std::size_t index, atmosphere::LoadedAtmosphere loaded, const std::string& why,
                                  const std::string& what) {
  const std::string body = tables_.current()[index].body_name;
  const Digest hash = digest_from_hex(atmosphere::lookup_table_hash(loaded.model));
  if (hash == effective_version(index)) {
    spdlog::info("master: {}: '{}' already uses {}; nothing to switch", why, body, what);
    maybe_start_switch();
    return;
  }
  tables_.add_version(body, loaded, hash);
  tables_.begin_pending(index, hash);
  pending_change_ = what;
  spdlog::info(
      "master: {}: preparing table version {} of '{}' ({}) in the background; the show goes on with "
      "version {}",
      why, short_hex(hash), body, what, short_hex(effective_version(index)));
  if (tables_.has_set(hash)) {  // an earlier version again: already encoded
    actions_.defer([this] { on_version_prepared(std::nullopt); });
    return;
  }
  if (tables_.is_show_set(hash)) return;  // the show's own, still being prepared: on_set_prepared goes on
  actions_.prepare(job(body, loaded.model));
}

/// The pending version's tables are ready: sends them to every node. A set
/// of a version abandoned meanwhile (cleared) is kept for later.
void TableSchedule::on_version_prepared(std::optional<TableSetFile> set) {
  if (stopped_) return;
  if (!tables_.pending() || (set && set->table_hash != tables_.pending()->hash)) {
    if (set) tables_.add_set(std::move(*set));
    return;
  }
  if (set) tables_.add_set(std::move(*set));
  const Digest hash = tables_.pending()->hash;
  const TableSetFile& prepared = tables_.set(hash);
  tables_.mark_distributed(actions_.now());
  std::size_t receivers = 0;
  sessions_.for_each([&](NodeSession& s) {
    if (s.state == NodeSession::State::handshake || !s.inventory_done) return;  // gets it with its inventory
    // A node that holds it (an earlier version again, a show's own set) is not sent it again.
    if (s.tables_ready.count(hash) || tables_.is_show_set(hash)) return;
    send_set(s, prepared);
    ++receivers;
  });
  spdlog::info("master: table version {} of '{}' prepared ({} bytes); sent to {} node{}", short_hex(hash),
               prepared.body_name, prepared.bytes->size(), receivers, receivers == 1 ? "" : "s");
  maybe_apply_pending();
}

/// Once every ready node holds the pending version, it takes effect at the next frame to start.
void TableSchedule::maybe_apply_pending() {
  if (!tables_.pending() || !tables_.pending()->distributed || stopped_) return;
  const Digest hash = tables_.pending()->hash;
  std::size_t ready = 0;
  bool all_hold_it = true;
  sessions_.for_each([&](const NodeSession& s) {
    if (s.state != NodeSession::State::ready) return;
    if (!s.tables_ready.count(hash)) all_hold_it = false;
    ++ready;
  });
  if (!all_hold_it) return;
  const std::uint64_t effective = barrier_.next_boundary();
  const AtmosphereTableRef before = tables_.apply_pending(effective);
  spdlog::info("master: table version {} of '{}' takes effect at frame {} on all {} ready node{} (was {})",
               short_hex(hash), before.body_name, effective, ready, ready == 1 ? "" : "s",
               short_hex(before.table_hash));
  // Nodes still joining now need the new version (they were sent it) and no longer the old one.
  every_node_maybe_ready();
  maybe_start_switch();
}

bool TableSchedule::participants_hold(const FrameState& state, const std::vector<std::uint32_t>& participants,
                                      bool log) {
  for (const AtmosphereTableRef& ref : state.atmospheres) {
    if (!tables_.has_set(ref.table_hash)) {
      if (log)
        spdlog::info("master: frame {} waits for table set {} of '{}', still being prepared", state.frame,
                     short_hex(ref.table_hash), ref.body_name);
      return false;
    }
    std::vector<std::string> missing;
    std::vector<std::uint32_t> late;
    const auto sent = show_set_sent_at_.find(ref.table_hash);
    const double limit_ms = confirmation_limit_ms();
    for (const std::uint32_t id : participants) {
      NodeSession* s = sessions_.find(id);
      if (s == nullptr || s->tables_ready.count(ref.table_hash)) continue;
      missing.push_back(s->name);
      if (sent != show_set_sent_at_.end() && ms_since(sent->second) > limit_ms) {
        spdlog::warn(
            "master: node '{}' did not confirm table set {} within {:.0f} ms: disconnecting it so that "
            "frame {} can go on (it rejoins with the set when it reconnects)",
            s->name, short_hex(ref.table_hash), limit_ms, state.frame);
        late.push_back(id);
      }
    }
    for (const std::uint32_t id : late)
      if (NodeSession* s = sessions_.find(id)) actions_.close(*s, "table set not confirmed in time");
    if (!missing.empty()) {
      if (log)
        spdlog::info("master: frame {} waits for node{} '{}' to load table set {} of '{}'", state.frame,
                     missing.size() == 1 ? "" : "s", fmt::join(missing, "', '"), short_hex(ref.table_hash),
                     ref.body_name);
      return false;
    }
  }
  return true;
}

// ---------------------------------------------------------------------------- the operator's atmosphere commands

std::string TableSchedule::set_atmosphere(const operator_command::Set& set) {
  if (!edits_) throw std::invalid_argument(cat(describe(set), ": the frames come from an offline render's feed"));
  const std::size_t index = edits_->index_of(set.body);
  const Digest latest = latest_version(index);
  const AtmosphereEdits::Edit* waiting = edits_->waiting(set.body);
  // The parameters the change is made to: in a show its own version's with the operator's changes so far.
  const nlohmann::json base =
      show_     ? overrides_.apply(set.body, tables_.version(show_version_of(index).table_hash).parameters)
      : waiting ? waiting->loaded.parameters
                : tables_.version(latest).parameters;
  AtmosphereEdits::Edit edit = edits_->resolve(set, base);
  if (show_) {
    overrides_.add(set);
    overrides_.set_base(set.body, show_version_of(index).table_hash);
  }
  const Digest hash = digest_from_hex(atmosphere::lookup_table_hash(edit.loaded.model));
  if (hash == latest)
    return cat("'", set.body, "' ", edit.change, ": the tables stay version ", short_hex(hash),
               " (the change does not shape them)");
  const std::string change = edit.change;
  edits_->enqueue(std::move(edit));
  maybe_start_switch();
  const bool started_now = tables_.pending() && tables_.pending()->hash == hash;
  return cat("'", set.body, "' ", change, ": table version ", short_hex(hash),
             started_now ? " is being prepared" : " waits for the version before it",
             "; every node switches to it at one frame once all hold it",
             show_ ? " (it replaces the show's track of the body until cleared)" : "");
}

std::string TableSchedule::clear_atmosphere(const std::string& body) {
  if (!edits_)
    throw std::invalid_argument(cat("clear atmosphere of ", body, ": the frames come from an offline render's feed"));
  const std::size_t index = edits_->index_of(body);
  const bool dropped = edits_->drop(body);
  if (show_) {
    const bool had = overrides_.active(body) || tables_.override_of(index).has_value();
    overrides_.clear(body);
    if (tables_.pending() && tables_.pending()->ref_index == index)
      tables_.abandon_pending();  // its set is kept when it comes
    tables_.clear_override(index);
    maybe_start_switch();
    return had || dropped ? cat("'", body, "' follows the show's track again from the next frame")
                          : cat("'", body, "' has no operator changes: it follows the show's track");
  }
  AtmosphereEdits::Edit original = edits_->original(body);
  const Digest hash = digest_from_hex(atmosphere::lookup_table_hash(original.loaded.model));
  if (hash == latest_version(index))
    return cat("'", body, "' has the scene's own atmosphere (table version ", short_hex(hash), ")");
  edits_->enqueue(std::move(original));
  maybe_start_switch();
  return cat("'", body, "': the scene's own atmosphere, table version ", short_hex(hash),
             "; every node switches to it at one frame once all hold it");
}

}  // namespace zenith::cluster
