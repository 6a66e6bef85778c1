#include "cluster/check/link_check_report.h"

#include <fmt/format.h>

#include <algorithm>

namespace zenith::cluster {

LinkCheckReport make_report(const LinkCheckOptions& options, std::vector<LinkMeasurement> links) {
  LinkCheckReport r;
  r.cluster = options.config.name;
  r.target.frame_rate_hz = options.config.frame_rate_hz;
  r.target.lookahead_frames = options.config.lookahead_frames;
  r.seconds = std::chrono::duration<double>(options.duration).count();
  r.ping_interval_ms = std::chrono::duration<double, std::milli>(options.ping_interval).count();
  r.fill_bytes = options.fill_bytes;
  r.links = std::move(links);
  for (const LinkMeasurement& link : r.links) r.verdicts.push_back(judge(link, r.target));
  return r;
}

namespace {
std::string percent(std::optional<double> fraction) {
  return fraction ? fmt::format("{:.1f} %", 100 * *fraction) : std::string("–");
}
}  // namespace

std::string format_table(const LinkCheckReport& r) {
  std::string out = fmt::format(
      "cluster '{}': {:g} Hz, lookahead {} frame{} ({}); {:g} s of pings every {:g} ms and {:.0f} MiB to each node\n\n",
      r.cluster, r.target.frame_rate_hz, r.target.lookahead_frames, r.target.lookahead_frames == 1 ? "" : "s",
      r.target.lookahead_frames == 0
          ? "the barrier"
          : fmt::format("{:.1f} ms", r.target.lookahead_frames * 1000.0 / r.target.frame_rate_hz),
      r.seconds, r.ping_interval_ms, static_cast<double>(r.fill_bytes) / (1 << 20));
  // Columns as wide as their longest entry: node names are the config's, up to 64 bytes.
  std::size_t node_w = 4, address_w = 7;
  for (const LinkMeasurement& m : r.links) {
    node_w = std::max(node_w, m.node.size());
    address_w = std::max(address_w, m.address.size());
  }
  const auto row = [&](const std::string& node, const std::string& address, const std::string& round_trip,
                       const std::string& jitter, const std::string& loss, const std::string& mbit,
                       const std::string& clock, const std::string& steps, const std::string& wall,
                       const std::string& verdict) {
    return fmt::format("{:<{}}  {:<{}}  {:>25}  {:>9}  {:>17}  {:>7}  {:>15}  {:>5}  {:>9}  {}\n", node, node_w,
                       address, address_w, round_trip, jitter, loss, mbit, clock, steps, wall, verdict);
  };
  out += row("node", "address", "round trip ms min/p50/p99", "jitter ms", "lost to/from node", "Mbit/s",
             "clock ±ms, ppm", "steps", "wall Δ ms", "verdict");
  for (std::size_t i = 0; i < r.links.size(); ++i) {
    const LinkMeasurement& m = r.links[i];
    const LinkVerdict& v = r.verdicts[i];
    if (!m.reported) {
      out += row(m.node, m.address.empty() ? "–" : m.address, "–", "–", "–", "–", "–", "–", "–", to_string(v.grade));
      continue;
    }
    out += row(m.node, m.address,
               fmt::format("{:.2f}/{:.2f}/{:.2f}", m.round_trip_min_ms, m.round_trip_p50_ms, m.round_trip_p99_ms),
               fmt::format("{:.2f}", m.jitter_ms()),
               fmt::format("{} / {}", percent(m.loss_to_node()), percent(m.loss_from_node())),
               m.throughput_bits_per_s ? fmt::format("{:.0f}", *m.throughput_bits_per_s / 1e6) : std::string("–"),
               fmt::format("{:.3f}, {:+.1f}", m.clock_uncertainty_ms, m.clock_drift_ppm),
               fmt::format("{}", m.clock_steps), fmt::format("{:.1f}", m.wall_clock_offset_ms), to_string(v.grade));
  }
  bool any = false;
  for (std::size_t i = 0; i < r.links.size(); ++i)
    for (const std::string& reason : r.verdicts[i].reasons) {
      out += fmt::format("{}{}: {}\n", any ? "" : "\n", r.links[i].node, reason);
      any = true;
    }
  const LinkGrade g = r.grade();
  out += fmt::format("\nverdict: {}\n", g == LinkGrade::ok     ? "ok: the cluster can hold its frame rate"
                                        : g == LinkGrade::warn ? "warn: the show can run; see the lines above"
                                                               : "FAIL: fix the lines above before the show");
  return out;
}

nlohmann::json to_json(const LinkCheckReport& r) {
  using nlohmann::json;
  const auto optional = [](std::optional<double> v) { return v ? json(*v) : json(nullptr); };
  json nodes = json::array();
  for (std::size_t i = 0; i < r.links.size(); ++i) {
    const LinkMeasurement& m = r.links[i];
    const LinkVerdict& v = r.verdicts[i];
    json n = {{"name", m.node},
              {"address", m.address},
              {"connected", m.connected},
              {"reported", m.reported},
              {"verdict", v.grade == LinkGrade::fail ? "fail" : to_string(v.grade)},
              {"reasons", v.reasons}};
    if (m.reported) {
      n["round_trip_ms"] = {{"min", m.round_trip_min_ms},
                            {"p50", m.round_trip_p50_ms},
                            {"p99", m.round_trip_p99_ms},
                            {"max", m.round_trip_max_ms}};
      n["jitter_ms"] = m.jitter_ms();
      n["datagrams"] = {{"pings_sent", m.pings_sent},
                        {"pings_heard", m.pings_heard},
                        {"pongs", m.pongs},
                        {"loss_to_node", optional(m.loss_to_node())},
                        {"loss_from_node", optional(m.loss_from_node())}};
      n["throughput_mbit_s"] =
          optional(m.throughput_bits_per_s ? std::optional<double>(*m.throughput_bits_per_s / 1e6) : std::nullopt);
      n["fill"] = {{"bytes", m.fill_bytes}, {"seconds", m.fill_seconds}};
      n["clock"] = {{"uncertainty_ms", m.clock_uncertainty_ms},
                    {"drift_ppm", m.clock_drift_ppm},
                    {"steps", m.clock_steps},
                    {"steady_offset_ms", m.clock_offset_ms},
                    {"wall_offset_ms", m.wall_clock_offset_ms}};
      n["copies_in_time"] = v.copies_in_time;
      n["held_frames_per_hour"] = v.held_frames_per_hour;
      n["lookahead_for_two_copies"] = v.lookahead_for_two_copies ? json(*v.lookahead_for_two_copies) : json(nullptr);
    } else {
      n["problem"] = m.problem;
    }
    nodes.push_back(std::move(n));
  }
  const LinkGrade g = r.grade();
  return {{"cluster", r.cluster},
          {"frame_rate_hz", r.target.frame_rate_hz},
          {"lookahead_frames", r.target.lookahead_frames},
          {"check", {{"seconds", r.seconds}, {"ping_interval_ms", r.ping_interval_ms}, {"fill_bytes", r.fill_bytes}}},
          {"verdict", g == LinkGrade::fail ? "fail" : to_string(g)},
          {"nodes", std::move(nodes)}};
}

}  // namespace zenith::cluster

namespace zenith::cluster {
std::string LinkCheckReport::to_json_text() const { return to_json(*this).dump(2) + "\n"; }
}  // namespace zenith::cluster
