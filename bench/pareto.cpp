#include "bench/pareto.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numeric>

namespace zenith::bench {
namespace {

bool usable(const CostError& p) {
  return std::isfinite(p.cost) && std::isfinite(p.error) && p.cost >= 0.0 && p.error >= 0.0;
}

/// A label as a double-quoted gnuplot data field (no quotes inside).
std::string quoted(const std::string& s) {
  std::string q = s;
  std::replace(q.begin(), q.end(), '"', '\'');
  return fmt::format("\"{}\"", q);
}

/// A gnuplot string literal in double quotes ("\n" in `s` stays a line break).
std::string gp_string(const std::string& s) {
  std::string q;
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    q += c == '\n' ? std::string("\\n") : std::string(1, c);
  }
  return fmt::format("\"{}\"", q);
}

/// Tics for a log axis over values in [lo, hi]: 1, 1.5, 2, 3, 5, 7 per decade,
/// or every 1, 1.2, 1.5, 2, 2.5, 3 … 9 when the values span less than a decade
/// (gnuplot's own would label one tic or none).
std::string log_tics(double lo, double hi) {
  const bool dense = hi < 10.0 * lo;
  const std::vector<double> mantissas =
      dense ? std::vector<double>{1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 7, 8, 9} : std::vector<double>{1, 1.5, 2, 3, 5, 7};
  std::string tics;
  for (int decade = -6; decade <= 6; ++decade)
    for (double m : mantissas)
      tics = fmt::format("{}{}{:g}", tics, tics.empty() ? "" : ", ", m * std::pow(10.0, decade));
  return tics;
}

}  // namespace

std::vector<bool> pareto_front(std::span<const CostError> points) {
  std::vector<bool> front(points.size(), false);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!usable(points[i])) continue;
    front[i] = std::none_of(points.begin(), points.end(), [&](const CostError& q) {
      return usable(q) && q.cost < points[i].cost && q.error < points[i].error;
    });
  }
  return front;
}

std::optional<std::size_t> cheapest_within(std::span<const CostError> points, double tolerance) {
  double best = std::numeric_limits<double>::infinity();
  for (const CostError& p : points)
    if (usable(p)) best = std::min(best, p.error);
  if (!std::isfinite(best)) return std::nullopt;
  std::optional<std::size_t> pick;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const CostError& p = points[i];
    if (!usable(p) || p.error > tolerance * best) continue;
    if (!pick || p.cost < points[*pick].cost || (p.cost == points[*pick].cost && p.error < points[*pick].error))
      pick = i;
  }
  return pick;
}

bool write_pareto_chart(const std::filesystem::path& png, const std::vector<ChartPoint>& points,
                        std::optional<std::size_t> recommended, const ChartText& text) {
  std::filesystem::path gp = png;
  gp.replace_extension(".gp");
  std::ofstream s(gp);
  // The data inline (gnuplot 5 datablocks): every point, the front by cost, the pick.
  s << "$points << EOD\n";
  for (const ChartPoint& p : points)
    if (usable(p.value)) s << fmt::format("{:.6g} {:.6g} {}\n", p.value.cost, p.value.error, quoted(p.label));
  s << "EOD\n$front << EOD\n";
  std::vector<const ChartPoint*> front;
  for (const ChartPoint& p : points)
    if (p.front && usable(p.value)) front.push_back(&p);
  std::sort(front.begin(), front.end(),
            [](const ChartPoint* a, const ChartPoint* b) { return a->value.cost < b->value.cost; });
  for (const ChartPoint* p : front)
    s << fmt::format("{:.6g} {:.6g} {}\n", p->value.cost, p->value.error, quoted(p->label));
  s << "EOD\n";
  const bool pick = recommended && *recommended < points.size() && usable(points[*recommended].value);
  if (pick) {
    const ChartPoint& p = points[*recommended];
    s << fmt::format("$pick << EOD\n{:.6g} {:.6g} {}\nEOD\n", p.value.cost, p.value.error, quoted(p.label));
  }
  constexpr double kNone = std::numeric_limits<double>::infinity();
  double cost_lo = kNone, cost_hi = 0.0, error_lo = kNone, error_hi = 0.0;
  for (const ChartPoint& p : points)
    if (usable(p.value) && p.value.cost > 0.0 && p.value.error > 0.0) {
      cost_lo = std::min(cost_lo, p.value.cost);
      cost_hi = std::max(cost_hi, p.value.cost);
      error_lo = std::min(error_lo, p.value.error);
      error_hi = std::max(error_hi, p.value.error);
    }
  s << "set terminal pngcairo size 960,640 font ',10'\n"
    << "set output " << gp_string(png.string()) << "\n"
    << "set termoption noenhanced\nset logscale xy\nset grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
    << "set key top right box opaque\n"
    << "set xlabel " << gp_string(text.cost_label) << "\n"
    << "set ylabel " << gp_string(text.error_label) << "\n"
    << "set title " << gp_string(fmt::format("{}\n{}", text.title, text.subtitle)) << "\n"
    << "set xtics (" << log_tics(cost_lo, cost_hi) << ")\nset ytics (" << log_tics(error_lo, error_hi)
    << ")\nset format xy '%g'\n"
    << "set autoscale fix\nset offsets graph 0.05, graph 0.3, graph 0.1, graph 0.1\n"
    << "plot $points using 1:2 with points pt 7 ps 1.1 lc rgb '#888888' title 'setting', \\\n"
    << "     $points using 1:2:3 with labels left offset 0.9,0.35 font ',8' tc rgb '#444444' notitle, \\\n"
    << "     $front using 1:2 with linespoints lw 2 pt 7 ps 1.4 lc rgb '#d62728' title 'Pareto front'";
  if (pick)
    s << ", \\\n     $pick using 1:2 with points pt 6 ps 3.5 lw 2 lc rgb '#1f77b4' title "
      << gp_string(fmt::format("recommended: {}", points[*recommended].label));
  s << '\n';
  s.close();
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) return false;
  return std::system(fmt::format("gnuplot '{}'", gp.string()).c_str()) == 0;
}

}  // namespace zenith::bench
