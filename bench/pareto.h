#pragma once
// Pareto front of settings measured by their cost (precompute time, frame
// time) and their error (RMS relative error against the reference solver),
// the rule that picks a recommended default from it, and its gnuplot chart.
// Used by bench/lut_accuracy_bench.cpp; no GL, no atmosphere.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace zenith::bench {

/// One measured setting: cost (seconds or milliseconds: any unit, lower is
/// better) and error (lower is better).
struct CostError {
  double cost = 0.0;
  double error = 0.0;
};

/// front[i] is true when no other point has both a lower cost and a lower
/// error (strictly, in both). Points with a non-finite or negative value are
/// never on the front and dominate nothing.
std::vector<bool> pareto_front(std::span<const CostError> points);

/// The recommendation rule: among the points whose error is at most
/// `tolerance` × the lowest error, the cheapest (on equal cost, the lower
/// error). Such a point is always on the front. nullopt when no point is finite.
std::optional<std::size_t> cheapest_within(std::span<const CostError> points, double tolerance);

/// A labelled point of a chart.
struct ChartPoint {
  CostError value;
  std::string label;
  bool front = false;
};

struct ChartText {
  std::string title, subtitle;  ///< subtitle: the machine, the command
  std::string cost_label;       ///< x axis, with its unit
  std::string error_label;      ///< y axis
};

/// Writes a gnuplot script (data inline) next to `png` (same name, .gp) and
/// runs gnuplot: pngcairo, log–log axes, every point labelled, the front as a
/// line, the recommended point circled. Returns false when gnuplot is missing
/// or fails (the script stays for later).
bool write_pareto_chart(const std::filesystem::path& png, const std::vector<ChartPoint>& points,
                        std::optional<std::size_t> recommended, const ChartText& text);

}  // namespace zenith::bench
