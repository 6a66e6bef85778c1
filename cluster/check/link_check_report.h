#pragma once
// What `zenith cluster check` prints (docs/cluster.md, "Checking the
// network"): one table of every node's link with its verdict and the
// cluster's, or the same as JSON for scripts.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cluster/check/link_check.h"
#include "cluster/check/link_verdict.h"

namespace zenith::cluster {

/// The links checked, their verdicts (one per link, same order) and the target.
struct LinkCheckReport {
  std::string cluster;
  LinkTarget target;
  double seconds = 0, ping_interval_ms = 0;
  std::uint64_t fill_bytes = 0;
  std::vector<LinkMeasurement> links;
  std::vector<LinkVerdict> verdicts;

  LinkGrade grade() const { return worst(verdicts); }
  /// to_json(), indented, with a final newline.
  std::string to_json_text() const;
};

/// Judges every link of `links` against `target`.
LinkCheckReport make_report(const LinkCheckOptions& options, std::vector<LinkMeasurement> links);
/// The table, the reasons under it and the cluster's verdict, for a terminal.
std::string format_table(const LinkCheckReport& report);
/// docs/cluster.md, "Checking the network", names every key.
nlohmann::json to_json(const LinkCheckReport& report);

}  // namespace zenith::cluster
