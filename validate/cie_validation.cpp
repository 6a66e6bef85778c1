#include "validate/cie_validation.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "atmosphere/constants.h"
#include "atmosphere/named_inputs.h"
#include "atmosphere/parameters.h"
#include "atmosphere/photometry.h"
#include "atmosphere/sky_sampling.h"
#include "core/json_reader.h"
#include "core/strings.h"
#include "core/units.h"
#include "validate/cie_sky.h"
#include "validate/gnuplot.h"

namespace zenith::validate {
namespace {

using core::cat;

using core::kDeg;
constexpr double kObserverAltitude_m = 1.5;  ///< a person standing on the ground
constexpr double kMaxViewZenith_deg = 85.0;
/// Beyond this distance from the sun the sky is outside the aureole (the Mie
/// forward peak), which dominates the error close to the sun: the statistics
/// are also given for χ ≥ 30° alone.
constexpr double kFarFromSun_deg = 30.0;
constexpr std::array<double, 5> kAzimuthsFromSun_deg{0.0, 45.0, 90.0, 135.0, 180.0};

/// A preset as given, or with one of the paper's extensions switched back.
struct Variant {
  std::string preset;
  std::string key;    ///< "as-is", "classic-rayleigh", "geometric-air-mass" (CSV, file names)
  std::string label;  ///< for humans
  nlohmann::json parameters;
  std::string label_full() const { return cat(preset, " (", label, ")"); }
};

/// The object holding the molecular Rayleigh phase: "rayleigh" (standard mode) or "gas" (advanced).
nlohmann::json* rayleigh_object(nlohmann::json& p) {
  for (const char* key : {"rayleigh", "gas"})
    if (p.contains(key) && p[key].is_object()) return &p[key];
  return nullptr;
}

nlohmann::json read_parameters(const std::string& preset_or_file) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(preset_or_file, ec)) {
    std::ifstream in(preset_or_file);
    std::stringstream s;
    s << in.rdbuf();
    return parse_json(s.str(), preset_or_file);
  }
  return atmosphere::preset_parameters(preset_or_file);
}

/// Variants of a preset: as is, then each extension the preset uses switched
/// back (editing its JSON, so the loader validates and derives everything as usual).
std::vector<Variant> variants_of(const std::string& preset, bool with_variants) {
  const nlohmann::json p = read_parameters(preset);
  std::vector<Variant> out{{preset, "as-is", "as is", p}};
  if (!with_variants) return out;
  {
    nlohmann::json v = p;
    nlohmann::json* r = rayleigh_object(v);
    if (r && r->value("phase", std::string("penndorf")) != "classic") {
      (*r)["phase"] = "classic";
      out.push_back({preset, "classic-rayleigh", "classic Rayleigh phase", v});
    }
  }
  if (p.value("air_mass", std::string("geometric")) != "geometric") {
    nlohmann::json v = p;
    v["air_mass"] = "geometric";
    out.push_back({preset, "geometric-air-mass", "geometric air mass", v});
  }
  return out;
}

/// View zenith angles 0, step, …, 85°.
std::vector<double> view_zeniths_deg(double step_deg) {
  std::vector<double> z;
  for (int i = 0;; ++i) {
    const double v = i * step_deg;
    if (v > kMaxViewZenith_deg + 1e-9) break;
    z.push_back(v);
  }
  return z;
}

/// One sample of the comparison.
struct Point {
  double view_zenith_deg, azimuth_deg, sun_distance_deg;
  double ours;              ///< our L/L_z
  std::vector<double> cie;  ///< L/L_z of each CIE type (index = type number − 1)
  bool excluded;            ///< within the sun exclusion radius
};

/// All points of one variant at one sun zenith (every azimuth).
struct SunCase {
  double sun_zenith_deg;
  std::vector<Point> points;
};

struct VariantResult {
  Variant variant;
  std::string table_source;  ///< "cache" or "computed on …"
  std::vector<SunCase> cases;
};

/// RMS and max of |ours − CIE type| over the non-excluded points matching `keep`.
struct ErrorStats {
  std::size_t points = 0;
  double sum_sq = 0.0, sum_sq_rel = 0.0, max_abs = 0.0;
  double max_at_zenith_deg = 0.0, max_at_azimuth_deg = 0.0, max_at_sun_zenith_deg = 0.0;
  void add(const Point& p, std::size_t type_i, double sun_zenith_deg) {
    const double d = p.ours - p.cie[type_i], rel = d / p.cie[type_i];
    ++points;
    sum_sq += d * d;
    sum_sq_rel += rel * rel;
    if (std::abs(d) > max_abs) {
      max_abs = std::abs(d);
      max_at_zenith_deg = p.view_zenith_deg;
      max_at_azimuth_deg = p.azimuth_deg;
      max_at_sun_zenith_deg = sun_zenith_deg;
    }
  }
  double rms() const { return points ? std::sqrt(sum_sq / double(points)) : 0.0; }
  double rms_relative() const { return points ? std::sqrt(sum_sq_rel / double(points)) : 0.0; }
};

template <typename Keep>
ErrorStats stats_for(const std::vector<SunCase>& cases, std::size_t type_i, Keep keep) {
  ErrorStats s;
  for (const SunCase& c : cases)
    for (const Point& p : c.points)
      if (!p.excluded && keep(c, p)) s.add(p, type_i, c.sun_zenith_deg);
  return s;
}

/// The CIE type with the smallest RMS over the points matching `keep`: (type number, RMS).
template <typename Keep>
std::pair<int, double> best_type(const std::vector<CieSkyType>& types, const std::vector<SunCase>& cases, Keep keep) {
  std::pair<int, double> best{0, std::numeric_limits<double>::infinity()};
  for (std::size_t t = 0; t < types.size(); ++t) {
    const double rms = stats_for(cases, t, keep).rms();
    if (rms < best.second) best = {types[t].number, rms};
  }
  return best;
}

/// `keep`, further restricted to directions at least kFarFromSun_deg from the sun.
template <typename Keep>
auto far_from_sun(Keep keep) {
  return [keep](const SunCase& c, const Point& p) { return p.sun_distance_deg >= kFarFromSun_deg && keep(c, p); };
}

std::size_t type_index(const std::vector<CieSkyType>& types, int number) {
  for (std::size_t i = 0; i < types.size(); ++i)
    if (types[i].number == number) return i;
  throw std::out_of_range(cat("no CIE sky type ", number));
}

VariantResult evaluate_variant(const Variant& v, const CieValidationOptions& a, const std::vector<CieSkyType>& types,
                               const TablesFor& tables_for) {
  const atmosphere::LoadedAtmosphere loaded = atmosphere::resolve_atmosphere(v.parameters, cat("preset:", v.preset));
  const ValidationTables t = tables_for(loaded.model);
  const atmosphere::lut::TableQueries queries(loaded.model, t.tables);

  // Luminance weights with the solar spectrum folded in: Y = Σ w_i·E_sun(λ_i)·L_i,
  // L_i per unit solar irradiance (atmosphere/photometry.h, docs/physics.md "Photometry").
  std::vector<double> weights = atmosphere::luminance_weights(loaded.model.wavelengths_nm);
  for (std::size_t i = 0; i < weights.size(); ++i)
    weights[i] *= atmosphere::solar_irradiance_W_m2_nm(loaded.model.wavelengths_nm[i]);
  const auto luminance = [&](const atmosphere::Spectrum& radiance) {
    double y = 0.0;
    for (std::size_t i = 0; i < weights.size(); ++i) y += weights[i] * radiance[i];
    return y;
  };

  VariantResult result{v, t.source, {}};
  const std::vector<double> zeniths = view_zeniths_deg(a.zenith_step_deg);
  for (double sun_zenith : a.sun_zeniths_deg) {
    atmosphere::SkyGeometry geometry;
    geometry.altitude_m = kObserverAltitude_m;
    geometry.sun_zenith_deg = sun_zenith;
    geometry.sun_azimuth_deg = 0.0;  // azimuths are then measured from the sun
    std::vector<atmosphere::ViewDirection> directions{{0.0, 0.0}};
    for (double az : kAzimuthsFromSun_deg)
      for (double z : zeniths) directions.push_back({z, az});
    const std::vector<atmosphere::RadianceSample> samples = atmosphere::sample_radiance(queries, geometry, directions);
    const double zenith_luminance = luminance(samples.front().radiance);
    if (!(zenith_luminance > 0.0))
      throw std::runtime_error(
          cat(v.label_full(), ": zenith luminance is ", zenith_luminance, " at sun zenith ", sun_zenith, " deg"));
    SunCase c{sun_zenith, {}};
    for (std::size_t i = 1; i < samples.size(); ++i) {
      const auto& d = samples[i].direction;
      const double z = d.zenith_deg * kDeg, az = d.azimuth_deg * kDeg, zs = sun_zenith * kDeg;
      Point p{d.zenith_deg,
              d.azimuth_deg,
              cie_sun_distance_rad(z, az, zs) / kDeg,
              luminance(samples[i].radiance) / zenith_luminance,
              {},
              false};
      p.excluded = p.sun_distance_deg < a.exclude_sun_deg - 1e-6;
      for (const CieSkyType& type : types) p.cie.push_back(cie_relative_luminance(type, z, az, zs));
      c.points.push_back(std::move(p));
    }
    result.cases.push_back(std::move(c));
  }
  return result;
}

// ---------------------------------------------------------------- output

std::string number_text(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string("NaN"); }

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out.flush()) throw std::runtime_error(cat("cannot write ", path.string()));
}

/// Every sample: both curves and which points the statistics skip.
std::string samples_csv(const std::vector<VariantResult>& results, std::size_t t12) {
  std::string s =
      "preset,variant,sun_zenith_deg,azimuth_from_sun_deg,view_zenith_deg,sun_distance_deg,"
      "L_rel_ours,L_rel_cie12,excluded\n";
  for (const VariantResult& r : results)
    for (const SunCase& c : r.cases)
      for (const Point& p : c.points)
        s += fmt::format("{},{},{},{},{},{:.4f},{},{},{}\n", r.variant.preset, r.variant.key, c.sun_zenith_deg,
                         p.azimuth_deg, p.view_zenith_deg, p.sun_distance_deg, number_text(p.ours),
                         number_text(p.cie[t12]), p.excluded ? 1 : 0);
  return s;
}

/// One row per case (preset, variant, sun zenith, azimuth).
std::string cases_csv(const std::vector<VariantResult>& results, const std::vector<CieSkyType>& types,
                      std::size_t t12) {
  std::string s =
      "preset,variant,sun_zenith_deg,azimuth_from_sun_deg,points,rms_type12,max_abs_type12,"
      "max_at_view_zenith_deg,rms_rel_type12,rms_type12_far,max_abs_type12_far,best_type,best_type_rms\n";
  for (const VariantResult& r : results)
    for (const SunCase& c : r.cases)
      for (double az : kAzimuthsFromSun_deg) {
        const auto keep = [&](const SunCase& sc, const Point& p) {
          return sc.sun_zenith_deg == c.sun_zenith_deg && p.azimuth_deg == az;
        };
        const ErrorStats e = stats_for(r.cases, t12, keep), far = stats_for(r.cases, t12, far_from_sun(keep));
        const auto best = best_type(types, r.cases, keep);
        s += fmt::format("{},{},{},{},{},{:.5f},{:.5f},{},{:.5f},{:.5f},{:.5f},{},{:.5f}\n", r.variant.preset,
                         r.variant.key, c.sun_zenith_deg, az, e.points, e.rms(), e.max_abs, e.max_at_zenith_deg,
                         e.rms_relative(), far.rms(), far.max_abs, best.first, best.second);
      }
  return s;
}

/// One row per preset and variant, all cases together.
std::string summary_csv(const std::vector<VariantResult>& results, const std::vector<CieSkyType>& types,
                        std::size_t t12) {
  std::string s =
      "preset,variant,points,rms_type12,max_abs_type12,max_at_sun_zenith_deg,max_at_azimuth_deg,"
      "max_at_view_zenith_deg,rms_rel_type12,rms_type12_far,max_abs_type12_far,best_type,best_type_rms\n";
  const auto all = [](const SunCase&, const Point&) { return true; };
  for (const VariantResult& r : results) {
    const ErrorStats e = stats_for(r.cases, t12, all), far = stats_for(r.cases, t12, far_from_sun(all));
    const auto best = best_type(types, r.cases, all);
    s += fmt::format("{},{},{},{:.5f},{:.5f},{},{},{},{:.5f},{:.5f},{:.5f},{},{:.5f}\n", r.variant.preset,
                     r.variant.key, e.points, e.rms(), e.max_abs, e.max_at_sun_zenith_deg, e.max_at_azimuth_deg,
                     e.max_at_zenith_deg, e.rms_relative(), far.rms(), far.max_abs, best.first, best.second);
  }
  return s;
}

/// Table on stdout: a row per (preset, variant, sun zenith), RMS per azimuth.
void print_table(const std::vector<VariantResult>& results, const std::vector<CieSkyType>& types, std::size_t t12) {
  fmt::print(
      "\nL/Lz against CIE type 12: RMS of the difference per azimuth from the sun, over all azimuths, its max, "
      "the RMS {:.0f} deg or more from the sun (far30), and the best-fitting CIE type with its RMS\n",
      kFarFromSun_deg);
  std::string head = fmt::format("{:<16} {:<19} {:>5}", "preset", "variant", "sun");
  for (double az : kAzimuthsFromSun_deg) head += fmt::format(" {:>7}", fmt::format("az{:.0f}", az));
  head += fmt::format(" {:>7} {:>7} {:>7}  {:>4} {:>7}", "all", "max", "far30", "best", "rms");
  fmt::print("{}\n{}\n", head, std::string(head.size(), '-'));
  for (const VariantResult& r : results)
    for (const SunCase& c : r.cases) {
      std::string row = fmt::format("{:<16} {:<19} {:>5.0f}", r.variant.preset, r.variant.key, c.sun_zenith_deg);
      for (double az : kAzimuthsFromSun_deg) {
        const ErrorStats e = stats_for(r.cases, t12, [&](const SunCase& sc, const Point& p) {
          return sc.sun_zenith_deg == c.sun_zenith_deg && p.azimuth_deg == az;
        });
        row += fmt::format(" {:>7.3f}", e.rms());
      }
      const auto same_sun = [&](const SunCase& sc, const Point&) { return sc.sun_zenith_deg == c.sun_zenith_deg; };
      const ErrorStats e = stats_for(r.cases, t12, same_sun), far = stats_for(r.cases, t12, far_from_sun(same_sun));
      const auto best = best_type(types, r.cases, same_sun);
      row += fmt::format(" {:>7.3f} {:>7.3f} {:>7.3f}  {:>4} {:>7.3f}", e.rms(), e.max_abs, far.rms(), best.first,
                         best.second);
      fmt::print("{}\n", row);
    }
}

void print_summary(const std::vector<VariantResult>& results, const std::vector<CieSkyType>& types, std::size_t t12,
                   const CieValidationOptions& a) {
  const auto all = [](const SunCase&, const Point&) { return true; };
  fmt::print(
      "\nSummary: all sun zenith angles and azimuths, view zenith 0-{:.0f} deg every {} deg, "
      "directions within {} deg of the sun left out\n",
      kMaxViewZenith_deg, a.zenith_step_deg, a.exclude_sun_deg);
  fmt::print("{:<16} {:<19} {:>6} {:>9} {:>9} {:>20} {:>8} {:>10} {:>10}  {}\n", "preset", "variant", "points",
             "rms(12)", "max(12)", "max at sun,az,view", "rel.rms", "rms far30", "max far30", "best type (rms)");
  for (const VariantResult& r : results) {
    const ErrorStats e = stats_for(r.cases, t12, all), far = stats_for(r.cases, t12, far_from_sun(all));
    const auto best = best_type(types, r.cases, all);
    fmt::print("{:<16} {:<19} {:>6} {:>9.4f} {:>9.3f} {:>20} {:>7.1f}% {:>10.4f} {:>10.4f}  {} ({:.4f})\n",
               r.variant.preset, r.variant.key, e.points, e.rms(), e.max_abs,
               fmt::format("{:.0f},{:.0f},{:.1f}", e.max_at_sun_zenith_deg, e.max_at_azimuth_deg, e.max_at_zenith_deg),
               100.0 * e.rms_relative(), far.rms(), far.max_abs, best.first, best.second);
  }
  // The paper's case: its advanced model ("as is") against type 12.
  fmt::print("\n");
  for (const VariantResult& r : results) {
    if (r.variant.key != "as-is") continue;
    const ErrorStats e = stats_for(r.cases, t12, all), far = stats_for(r.cases, t12, far_from_sun(all));
    fmt::print(
        "CIE type 12{}, {} as is, {} tables: RMS |dL/Lz| = {:.4f}, max = {:.3f} "
        "(sun zenith {:.0f}, azimuth {:.0f}, view zenith {:.1f} deg), relative RMS {:.1f}%; "
        "{:.0f} deg or more from the sun: RMS {:.4f}, max {:.4f}\n",
        r.variant.preset == "earth-advanced" ? " (the paper's Figure 10 case)" : "", r.variant.preset, a.tables,
        e.rms(), e.max_abs, e.max_at_sun_zenith_deg, e.max_at_azimuth_deg, e.max_at_zenith_deg,
        100.0 * e.rms_relative(), kFarFromSun_deg, far.rms(), far.max_abs);
  }
}

/// Gnuplot data for one sun zenith: three blocks (index 0, 1, 2) for the
/// vertical planes 0°/180°, 45°/225° (= 135° by symmetry), 90°/270°, each
/// with the signed view zenith (negative: the plane's second half) and one
/// column per curve: CIE type 12, then each variant (NaN near the sun).
std::string curves_data(const std::vector<VariantResult>& results, std::size_t t12, std::size_t sun_index,
                        const std::vector<double>& zeniths) {
  const std::array<std::pair<double, double>, 3> planes{{{0.0, 180.0}, {45.0, 135.0}, {90.0, 90.0}}};
  std::string s = "# signed_view_zenith_deg,L_rel_cie12";
  for (const VariantResult& r : results) s += cat(",", r.variant.preset, "/", r.variant.key);
  s += '\n';
  for (const auto& [positive_az, negative_az] : planes) {
    // −85 … −step on the negative side, then 0 … 85 on the positive side.
    std::vector<std::pair<double, double>> xs;  // (signed x, azimuth)
    for (auto it = zeniths.rbegin(); it != zeniths.rend(); ++it)
      if (*it > 0.0) xs.push_back({-*it, negative_az});
    for (double z : zeniths) xs.push_back({z, positive_az});
    for (const auto& [x, az] : xs) {
      const double z = std::abs(x);
      const auto find = [&](const SunCase& c) -> const Point& {
        for (const Point& p : c.points)
          if (p.azimuth_deg == az && std::abs(p.view_zenith_deg - z) < 1e-9) return p;
        throw std::logic_error("missing sample");
      };
      const Point& first = find(results.front().cases[sun_index]);
      s += fmt::format("{},{}", x, number_text(first.cie[t12]));
      for (const VariantResult& r : results) {
        const Point& p = find(r.cases[sun_index]);
        s += cat(",", number_text(p.excluded ? std::numeric_limits<double>::quiet_NaN() : p.ours));
      }
      s += '\n';
    }
    s += "\n\n";
  }
  return s;
}

/// Line colour per preset, dash type per variant.
std::string line_style(const VariantResult& r, const std::vector<std::string>& presets) {
  static constexpr std::array<const char*, 6> kColours{"#1a9850", "#d95f02", "#7570b3",
                                                       "#e7298a", "#66a61e", "#a6761d"};
  const auto it = std::find(presets.begin(), presets.end(), r.variant.preset);
  const std::size_t colour = std::size_t(it - presets.begin()) % kColours.size();
  const int dash = r.variant.key == "as-is" ? 1 : r.variant.key == "classic-rayleigh" ? 2 : 3;
  return fmt::format("lw {} lc rgb '{}' dt {}", dash == 1 ? 2.5 : 1.5, kColours[colour], dash);
}

/// Writes the gnuplot script for one sun zenith and runs gnuplot when present.
/// Returns the PNG path when one was made.
std::optional<std::filesystem::path> write_plot(const std::filesystem::path& dir, const std::string& stem,
                                                double sun_zenith_deg, const std::vector<VariantResult>& results,
                                                const std::vector<std::string>& presets, const std::string& tables,
                                                double exclude_sun_deg) {
  const std::filesystem::path data = dir / (stem + ".dat"), gp = dir / (stem + ".gp"), png = dir / (stem + ".png");
  std::ofstream s(gp);
  // Paths relative to the script's directory, so the script can be rerun there.
  s << "# L/Lz against the CIE standard general sky type 12 (zenith validate cie; docs/validation.md)\n"
    << "# rerun: cd " << dir.string() << " && gnuplot " << gp.filename().string() << "\n"
    << "cd '" << std::filesystem::absolute(dir).string() << "'\n"
    << "set terminal pngcairo size 1500,520 font ',10'\nset output '" << png.filename().string() << "'\n"
    << "set datafile separator ','\nset datafile missing 'NaN'\nset grid\nset key top left font ',8'\n"
    << "set xrange [-90:90]\nset xtics 15\n"
    << "set multiplot layout 1,3 title \"L/Lz seen from 1.5 m above the ground, sun zenith " << sun_zenith_deg
    << " deg: CIE type 12 (blue) and zenith presets (" << tables << " tables; directions within " << exclude_sun_deg
    << " deg of the sun left out)\" noenhanced\n";
  const std::array<const char*, 3> titles{"solar meridian: view zenith [deg] (- away from the sun, + toward it)",
                                          "plane 45/225 deg from the sun: view zenith [deg] (- 135 deg side)",
                                          "plane 90/270 deg from the sun: view zenith [deg]"};
  for (std::size_t plane = 0; plane < titles.size(); ++plane) {
    // The solar meridian passes through the aureole: log scale there.
    s << (plane == 0 ? "set logscale y\nset yrange [0.3:*]\n" : "unset logscale y\nset yrange [0:*]\n")
      << "set xlabel '" << titles[plane] << "' noenhanced\nset ylabel 'L / L_{zenith}" << (plane == 0 ? " (log)" : "")
      << "'\n"
      << (plane == 0 ? "set key top left\n" : "unset key\n") << "plot '" << data.filename().string() << "' index "
      << plane << " using 1:2 with lines lw 3 lc rgb '#2166ac' title 'CIE type 12'";
    for (std::size_t i = 0; i < results.size(); ++i)
      s << ", \\\n     '' index " << plane << " using 1:" << i + 3 << " with lines " << line_style(results[i], presets)
        << " title '" << results[i].variant.preset << ", " << results[i].variant.label << "'";
    s << '\n';
  }
  s << "unset multiplot\n";
  s.close();
  if (!s) throw std::runtime_error(cat("cannot write ", gp.string()));
  if (!run_gnuplot(gp)) return std::nullopt;
  return png;
}

}  // namespace

void validate_cie(const CieValidationOptions& options, const TablesFor& tables_for) {
  CieValidationOptions a = options;
  if (a.presets.empty()) a.presets = {"earth-advanced", "earth-standard"};  // the paper's case first
  std::sort(a.sun_zeniths_deg.begin(), a.sun_zeniths_deg.end());
  a.sun_zeniths_deg.erase(std::unique(a.sun_zeniths_deg.begin(), a.sun_zeniths_deg.end()), a.sun_zeniths_deg.end());

  const std::vector<CieSkyType> types = cie_general_sky_types();
  const std::size_t t12 = type_index(types, kCieStandardClearSkyType);

  std::vector<Variant> variants;
  for (const std::string& p : a.presets)
    for (Variant& v : variants_of(p, !a.no_variants)) variants.push_back(std::move(v));

  std::vector<VariantResult> results;
  for (std::size_t i = 0; i < variants.size(); ++i) {
    spdlog::info("[{}/{}] {}: tables ({}) and {} sun positions", i + 1, variants.size(), variants[i].label_full(),
                 a.tables, a.sun_zeniths_deg.size());
    results.push_back(evaluate_variant(variants[i], a, types, tables_for));
  }

  const std::filesystem::path dir(a.out_dir);
  std::filesystem::create_directories(dir);
  write_file(dir / "cie_samples.csv", samples_csv(results, t12));
  write_file(dir / "cie_cases.csv", cases_csv(results, types, t12));
  write_file(dir / "cie_summary.csv", summary_csv(results, types, t12));

  std::vector<std::string> pngs;
  const std::vector<double> zeniths = view_zeniths_deg(a.zenith_step_deg);
  for (std::size_t s = 0; s < a.sun_zeniths_deg.size(); ++s) {
    const std::string stem = fmt::format("cie_sun_zenith_{:02.0f}", a.sun_zeniths_deg[s]);
    write_file(dir / (stem + ".dat"), curves_data(results, t12, s, zeniths));
    if (a.no_plots) continue;
    if (auto png = write_plot(dir, stem, a.sun_zeniths_deg[s], results, a.presets, a.tables, a.exclude_sun_deg))
      pngs.push_back(png->string());
  }

  if (a.csv_stdout) {
    fmt::print("{}", cases_csv(results, types, t12));
  } else {
    for (const VariantResult& r : results) fmt::print("{:<48} tables: {}\n", r.variant.label_full(), r.table_source);
    print_table(results, types, t12);
    print_summary(results, types, t12, a);
  }
  spdlog::info("wrote {}/cie_summary.csv, cie_cases.csv, cie_samples.csv and {} gnuplot scripts", dir.string(),
               a.sun_zeniths_deg.size());
  if (!a.no_plots && pngs.empty())
    spdlog::info("gnuplot not found or failed: the .gp scripts are left in {}", dir.string());
  for (const std::string& p : pngs) spdlog::info("plot: {}", p);
}

}  // namespace zenith::validate
