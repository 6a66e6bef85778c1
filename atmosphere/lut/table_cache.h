#pragma once
// On-disk cache of lookup-table sets as OpenEXR (float32, ZIP-compressed,
// one multi-part file per set: transmittance, irradiance, single Rayleigh,
// single Mie, multiple scattering). Each part's header carries the format
// version, the model's lookup-table hash, the table sizes, the precompute
// settings, the canonical parameter description, the orders used and a
// SHA-256 of its pixels. A file that is unreadable, truncated, mismatching or
// whose pixels do not match their checksum (or are not finite) is reported and
// never used; the caller recomputes.
#include <filesystem>
#include <optional>
#include <string>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/lut/precompute_options.h"

namespace zenith::atmosphere::lut {

/// Bumped when the file layout changes.
inline constexpr int kCacheFormatVersion = 1;

/// $ZENITH_CACHE_DIR, else $XDG_CACHE_HOME/zenith, else $HOME/.cache/zenith, else ./.zenith-cache.
std::filesystem::path default_cache_directory();

/// Identity of a table set: the model's hash plus everything in the options
/// that changes the tables (sizes, orders or tolerance, quadrature samples).
std::string table_set_key(const AtmosphereModel& model, const PrecomputeOptions& options);

class TableCache {
 public:
  explicit TableCache(std::filesystem::path directory);
  const std::filesystem::path& directory() const { return directory_; }
  std::filesystem::path path_for(const std::string& key) const;

  /// Loads a table set; std::nullopt if absent. If present but invalid, `problem`
  /// (when given) receives the reason and std::nullopt is returned.
  std::optional<LookupTables> load(const AtmosphereModel& model, const PrecomputeOptions& options,
                                   std::string* problem = nullptr) const;
  /// Writes atomically (temporary file + rename). Returns the file path.
  std::filesystem::path store(const AtmosphereModel& model, const PrecomputeOptions& options,
                              const LookupTables& tables) const;

 private:
  std::filesystem::path directory_;
};

/// Writes / reads a table set to an explicit path (used by the cache and by
/// `zenith precompute --out`).
void write_tables_exr(const std::filesystem::path& path, const AtmosphereModel& model, const std::string& key,
                      const LookupTables& tables);
/// Throws std::runtime_error describing the problem if the file is not a valid
/// table set for `model` and `key`.
LookupTables read_tables_exr(const std::filesystem::path& path, const AtmosphereModel& model, const std::string& key);

}  // namespace zenith::atmosphere::lut
