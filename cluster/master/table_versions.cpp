#include "cluster/master/table_versions.h"

#include <algorithm>

namespace zenith::cluster {

void TableVersions::add_version(const std::string& body, const atmosphere::LoadedAtmosphere& loaded,
                                const Digest& hash) {
  if (versions_.count(hash)) return;
  show::AtmosphereVersion v;
  v.body = body;
  v.parameters = loaded.parameters;
  v.table_hash = hash;
  v.loaded = loaded;
  definitions_.emplace(hash, std::make_shared<const std::vector<std::uint8_t>>(
                                 encode(AtmosphereDefinition{body, hash, loaded.parameters.dump()})));
  versions_.emplace(hash, std::move(v));
}

std::shared_ptr<const std::vector<std::uint8_t>> TableVersions::definition(const Digest& hash) const {
  auto it = definitions_.find(hash);
  return it == definitions_.end() ? nullptr : it->second;
}

void TableVersions::add_set(TableSetFile set) {
  const Digest hash = set.table_hash;
  sets_.insert_or_assign(hash, std::move(set));
}

void TableVersions::add_current(const std::string& body, const Digest& hash, std::uint64_t effective_from_frame) {
  AtmosphereTableRef ref;
  ref.body_name = body;
  ref.table_hash = hash;
  ref.effective_from_frame = effective_from_frame;
  current_.push_back(ref);
}

void TableVersions::use_show_sets(std::vector<Digest> sets, std::vector<AtmosphereTableRef> current) {
  show_sets_ = std::move(sets);
  current_ = std::move(current);
  overrides_.assign(current_.size(), std::nullopt);
}

bool TableVersions::is_show_set(const Digest& hash) const {
  return show_sets_ && std::find(show_sets_->begin(), show_sets_->end(), hash) != show_sets_->end();
}

std::vector<Digest> TableVersions::wanted_sets() const {
  std::vector<Digest> wanted;
  const auto want = [&](const Digest& h) {
    if (std::find(wanted.begin(), wanted.end(), h) == wanted.end()) wanted.push_back(h);
  };
  if (show_sets_) {
    for (const Digest& h : *show_sets_)
      if (has_set(h)) want(h);
    for (const auto& o : overrides_)
      if (o) want(o->table_hash);
  } else {
    for (const AtmosphereTableRef& r : current_) want(r.table_hash);
  }
  if (pending_ && pending_->distributed) want(pending_->hash);
  return wanted;
}

bool TableVersions::ready_with(const std::set<Digest>& held) const {
  for (const AtmosphereTableRef& r : current_)
    if (!held.count(r.table_hash)) return false;
  if (show_sets_) {
    for (const Digest& h : *show_sets_)
      if (has_set(h) && !held.count(h)) return false;
    for (const auto& o : overrides_)
      if (o && !held.count(o->table_hash)) return false;
  }
  return true;
}

std::vector<AtmosphereTableRef> TableVersions::with_overrides(std::vector<AtmosphereTableRef> refs) const {
  for (const auto& o : overrides_) {
    if (!o) continue;
    for (AtmosphereTableRef& r : refs)
      if (r.body_name == o->body_name) r = *o;
  }
  return refs;
}

void TableVersions::begin_pending(std::size_t ref_index, const Digest& hash) {
  pending_ = Pending{ref_index, hash, false, {}};
}

void TableVersions::mark_distributed(Clock::time_point now) {
  pending_->distributed = true;
  pending_->distributed_at = now;
}

AtmosphereTableRef TableVersions::apply_pending(std::uint64_t frame) {
  const std::size_t index = pending_->ref_index;
  AtmosphereTableRef next = current_[index];
  next.table_hash = pending_->hash;
  next.effective_from_frame = frame;
  pending_.reset();
  if (show_sets_) {
    const AtmosphereTableRef before = overrides_[index].value_or(current_[index]);
    overrides_[index] = next;
    return before;
  }
  const AtmosphereTableRef before = current_[index];
  current_[index] = next;
  return before;
}

}  // namespace zenith::cluster
