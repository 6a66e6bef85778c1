#include "validate/stress_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>

namespace zenith::validate {
namespace {

/// A CSV field: quoted, inner quotes doubled.
std::string quoted(const std::string& text) {
  std::string q = "\"";
  for (char c : text) {
    if (c == '"') q += '"';
    q += c;
  }
  q += '"';
  return q;
}

void region_row(std::ostringstream& csv, const std::string& model, std::string_view region, const RegionStatistics& s) {
  csv << model << ',' << region << ',' << s.samples << ',' << s.health.values << ',' << s.health.nan << ','
      << s.health.inf << ',' << s.health.negative << ',' << s.health.above_one << ',' << s.horizon_jump.value << ','
      << s.reference.count() << ',' << s.reference.median() << ',' << s.reference.quantile(0.95) << ','
      << s.reference.max() << ',' << quoted(s.horizon_jump.where) << ',' << quoted(s.reference.max_where()) << '\n';
}

}  // namespace

RegionTable all_models(const std::vector<ModelResult>& models) {
  RegionTable all;
  for (const ModelResult& m : models) merge(all, m.regions);
  return all;
}

std::string regions_csv(const std::vector<ModelResult>& models) {
  std::ostringstream csv;
  csv.precision(6);
  csv << "model,region,samples,values,nan,inf,negative,transmittance_above_1,max_horizon_jump,reference_samples,"
         "reference_median,reference_p95,reference_max,max_horizon_jump_at,reference_max_at\n";
  for (const ModelResult& m : models) {
    for (Region r : kRegions) region_row(csv, m.model, region_name(r), m.regions[std::size_t(r)]);
    region_row(csv, m.model, "all", total(m.regions));
  }
  const RegionTable all = all_models(models);
  for (Region r : kRegions) region_row(csv, "all", region_name(r), all[std::size_t(r)]);
  region_row(csv, "all", "all", total(all));
  return csv.str();
}

std::string gpu_csv(const std::vector<GpuFrameResult>& frames) {
  std::ostringstream csv;
  csv.precision(6);
  csv << "model,view,altitude_m,sun_zenith_deg,values,nan,inf,negative,max_row_jump,max_row_jump_row,"
         "cpu_compared,max_cpu_difference,seconds\n";
  for (const GpuFrameResult& f : frames)
    csv << f.model << ',' << f.view << ',' << f.altitude_m << ',' << f.sun_zenith_deg << ',' << f.values << ',' << f.nan
        << ',' << f.inf << ',' << f.negative << ',' << f.max_row_jump << ',' << f.max_row_jump_row << ',' << f.compared
        << ',' << f.max_cpu_difference << ',' << f.seconds << '\n';
  return csv.str();
}

std::string summary_table(const std::vector<ModelResult>& models, const std::vector<GpuFrameResult>& frames) {
  std::string out;
  const RegionTable all = all_models(models);
  out += fmt::format("CPU path ({} models): table queries, and single scattering vs the exact quadrature\n",
                     models.size());
  out += fmt::format("{:<9} {:>9} {:>11} {:>5} {:>5} {:>5} {:>5} {:>10} {:>5} {:>10} {:>10} {:>10}\n", "region",
                     "samples", "values", "NaN", "Inf", "neg", "T>1", "max jump", "ref", "median", "p95", "max");
  auto row = [&](std::string_view name, const RegionStatistics& s) {
    out += fmt::format("{:<9} {:>9} {:>11} {:>5} {:>5} {:>5} {:>5} {:>10.3g} {:>5} {:>10.3g} {:>10.3g} {:>10.3g}\n",
                       name, s.samples, s.health.values, s.health.nan, s.health.inf, s.health.negative,
                       s.health.above_one, s.horizon_jump.value, s.reference.count(), s.reference.median(),
                       s.reference.quantile(0.95), s.reference.max());
  };
  for (Region r : kRegions) row(region_name(r), all[std::size_t(r)]);
  const RegionStatistics t = total(all);
  row("all", t);
  out += fmt::format("largest horizon jump: {:.3g} at {}\n", t.horizon_jump.value, t.horizon_jump.where);
  for (Region r : kRegions)
    if (all[std::size_t(r)].reference.count() > 0)
      out += fmt::format("largest {} error: {:.3g} at {}\n", region_name(r), all[std::size_t(r)].reference.max(),
                         all[std::size_t(r)].reference.max_where());
  if (!frames.empty()) {
    std::size_t values = 0, nan = 0, inf = 0, negative = 0;
    const GpuFrameResult* worst_jump = &frames.front();
    const GpuFrameResult* worst_cpu = &frames.front();
    double seconds = 0.0;
    for (const GpuFrameResult& f : frames) {
      values += f.values;
      nan += f.nan;
      inf += f.inf;
      negative += f.negative;
      seconds += f.seconds;
      if (f.max_row_jump > worst_jump->max_row_jump) worst_jump = &f;
      if (f.max_cpu_difference > worst_cpu->max_cpu_difference) worst_cpu = &f;
    }
    out += fmt::format("GPU path: {} frames, {} values, NaN {}, Inf {}, negative {} ({:.1f} s)\n", frames.size(),
                       values, nan, inf, negative, seconds);
    out += fmt::format(
        "  largest row step in a horizon frame: {:.3g} ({} view, {}, altitude {:.4g} m, sun {} deg, row {})\n",
        worst_jump->max_row_jump, worst_jump->view, worst_jump->model, worst_jump->altitude_m,
        worst_jump->sun_zenith_deg, worst_jump->max_row_jump_row);
    out += fmt::format(
        "  largest GPU vs CPU difference (sky pixels): {:.3g} ({} view, {}, altitude {:.4g} m, sun {} deg)\n",
        worst_cpu->max_cpu_difference, worst_cpu->view, worst_cpu->model, worst_cpu->altitude_m,
        worst_cpu->sun_zenith_deg);
  }
  return out;
}

}  // namespace zenith::validate
