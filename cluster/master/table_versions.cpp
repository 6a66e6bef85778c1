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
}

std::vector<Digest> TableVersions::wanted_sets() const {
  std::vector<Digest> wanted;
  if (show_sets_) {
    for (const Digest& h : *show_sets_)
      if (has_set(h)) wanted.push_back(h);
    return wanted;
  }
  for (const AtmosphereTableRef& r : current_)
    if (std::find(wanted.begin(), wanted.end(), r.table_hash) == wanted.end()) wanted.push_back(r.table_hash);
  if (pending_ && pending_->distributed && std::find(wanted.begin(), wanted.end(), pending_->hash) == wanted.end())
    wanted.push_back(pending_->hash);
  return wanted;
}

bool TableVersions::ready_with(const std::set<Digest>& held) const {
  for (const AtmosphereTableRef& r : current_)
    if (!held.count(r.table_hash)) return false;
  if (show_sets_)
    for (const Digest& h : *show_sets_)
      if (has_set(h) && !held.count(h)) return false;
  return true;
}

void TableVersions::begin_pending(std::size_t ref_index, const Digest& hash) {
  pending_ = Pending{ref_index, hash, false, {}};
}

void TableVersions::mark_distributed(Clock::time_point now) {
  pending_->distributed = true;
  pending_->distributed_at = now;
}

AtmosphereTableRef TableVersions::apply_pending(std::uint64_t frame) {
  AtmosphereTableRef& ref = current_[pending_->ref_index];
  const AtmosphereTableRef before = ref;
  ref.table_hash = pending_->hash;
  ref.effective_from_frame = frame;
  pending_.reset();
  return before;
}

}  // namespace zenith::cluster
