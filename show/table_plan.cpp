#include "show/table_plan.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/json_reader.h"
#include "core/sha256.h"
#include "core/strings.h"

namespace zenith::show {
namespace {

using core::cat;

/// Float32 bytes of one table set: transmittance, irradiance and the three
/// 4D scattering tables (single Rayleigh, single Mie, multiple), one channel
/// per wavelength each (atmosphere/lut/lookup_tables.h).
std::uint64_t table_set_bytes(const atmosphere::lut::TableSizes& s, std::size_t channels) {
  const std::uint64_t texels = std::uint64_t{s.transmittance_mu} * s.transmittance_r +
                               std::uint64_t{s.irradiance_mu_s} * s.irradiance_r +
                               3 * std::uint64_t{s.scattering_texels()};
  return texels * channels * sizeof(float);
}

/// The leaves of `a` that differ from `b` (or that `b` lacks), as "pointer = value".
void differences(const nlohmann::json& a, const nlohmann::json& b, const std::string& pointer,
                 std::vector<std::string>& out) {
  if (a.is_object() && b.is_object()) {
    for (const auto& [key, value] : a.items()) {
      const std::string child = cat(pointer, "/", key);
      if (!b.contains(key))
        out.push_back(cat(child, " = ", value.dump()));
      else
        differences(value, b.at(key), child, out);
    }
    for (const auto& [key, value] : b.items())
      if (!a.contains(key)) out.push_back(cat(pointer, "/", key, " removed"));
    return;
  }
  if (a != b) out.push_back(cat(pointer, " = ", a.dump()));
}

}  // namespace

std::size_t TablePlan::missing() const {
  std::size_t n = 0;
  for (const TablePlanEntry& e : sets) n += e.cached ? 0 : 1;
  return n;
}

std::uint64_t TablePlan::total_bytes() const {
  std::uint64_t n = 0;
  for (const TablePlanEntry& e : sets) n += e.bytes;
  return n;
}

TablePlan plan_tables(const Show& show, double fps, const atmosphere::lut::PrecomputeOptions& options,
                      const atmosphere::lut::TableCache& cache) {
  TablePlan plan;
  plan.fps = fps;
  plan.frame_count = show.frame_count(fps);
  for (std::uint64_t i = 0; i < plan.frame_count; ++i) {
    const scene::FrameDescription state = show.state_at(show.frame_time_s(i, fps), i, 0);
    for (const scene::AtmosphereTableRef& ref : state.atmospheres) {
      TablePlanEntry* entry = nullptr;
      for (TablePlanEntry& e : plan.sets)
        if (e.version.table_hash == ref.table_hash) entry = &e;
      if (entry == nullptr) {
        const AtmosphereVersion* version = show.find_version(ref.table_hash);
        if (version == nullptr) throw std::logic_error("plan_tables: the show used a version it does not know");
        TablePlanEntry e;
        e.version = *version;
        e.first_frame = i;
        std::error_code ec;
        e.cached = std::filesystem::is_regular_file(
            cache.path_for(atmosphere::lut::table_set_key(version->loaded.model, options)), ec);
        e.bytes = table_set_bytes(options.sizes, version->loaded.model.wavelength_count());
        plan.sets.push_back(std::move(e));
        entry = &plan.sets.back();
      }
      ++entry->frames;
    }
  }
  return plan;
}

std::string budget_warning(const TablePlan& plan, double budget_gib) {
  const double gib = static_cast<double>(plan.total_bytes()) / (1024.0 * 1024.0 * 1024.0);
  if (gib <= budget_gib) return {};
  char text[256];
  std::snprintf(text, sizeof text,
                "warning: the show's %zu lookup-table sets take %.1f GiB, above the budget of %.1f GiB "
                "(--table-budget-gib): the master holds each while it serves it and every node caches it; "
                "a coarser atmosphere track step needs fewer\n",
                plan.sets.size(), gib, budget_gib);
  return text;
}

std::string describe(const TablePlan& plan, double seconds_per_set) {
  std::ostringstream out;
  char line[64];
  out << plan.sets.size() << " lookup-table set" << (plan.sets.size() == 1 ? "" : "s") << " for " << plan.frame_count
      << " frames at " << plan.fps << " fps:\n";
  for (std::size_t i = 0; i < plan.sets.size(); ++i) {
    const TablePlanEntry& e = plan.sets[i];
    std::vector<std::string> changed;
    const nlohmann::json* first_of_body = nullptr;
    for (std::size_t j = 0; j < i && first_of_body == nullptr; ++j)
      if (plan.sets[j].version.body == e.version.body) first_of_body = &plan.sets[j].version.parameters;
    if (first_of_body != nullptr) differences(e.version.parameters, *first_of_body, "", changed);
    std::snprintf(line, sizeof line, "%.1f MiB", static_cast<double>(e.bytes) / (1024.0 * 1024.0));
    out << "  " << e.version.body << " " << core::to_hex(e.version.table_hash).substr(0, 12) << ": frames "
        << e.first_frame << "+ (" << e.frames << "), " << (e.cached ? "cached" : "to compute") << ", " << line;
    if (first_of_body == nullptr) out << ", as first used";
    for (std::size_t k = 0; k < changed.size() && k < 3; ++k) out << (k == 0 ? ", " : "; ") << changed[k];
    if (changed.size() > 3) out << "; ...";
    out << "\n";
  }
  std::snprintf(line, sizeof line, "%.1f MiB", static_cast<double>(plan.total_bytes()) / (1024.0 * 1024.0));
  out << "total " << line << ", " << plan.missing() << " to compute";
  if (seconds_per_set > 0.0 && plan.missing() > 0) {
    std::snprintf(line, sizeof line, "%.0f s", seconds_per_set * static_cast<double>(plan.missing()));
    out << " (about " << line << ")";
  }
  out << "\n";
  return out.str();
}

}  // namespace zenith::show
