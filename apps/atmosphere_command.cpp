// `zenith atmosphere show` prints every derived per-wavelength coefficient with
// its unit, the zenith optical depths, the lookup-table hash and any warnings;
// `zenith atmosphere import-phase` turns a measured phase function into the
// tabulated phase object of an atmosphere file.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "atmosphere/aeronet_phase_file.h"
#include "atmosphere/model_hash.h"
#include "atmosphere/parameters.h"

namespace zenith::app {
namespace {

using atmosphere::AtmosphereModel;
using atmosphere::LoadedAtmosphere;
using atmosphere::Spectrum;

struct ShowOptions {
  std::string preset, file;
  std::vector<double> wavelengths_nm;
  bool json = false;
};

std::string phase_name(const AtmosphereModel& m) {
  switch (m.mie_phase.model) {
    case atmosphere::MiePhase::Model::HenyeyGreenstein: return "Henyey-Greenstein";
    case atmosphere::MiePhase::Model::DoubleHenyeyGreenstein: return "double Henyey-Greenstein (eq. 16)";
    case atmosphere::MiePhase::Model::CornetteShanks: return "Cornette-Shanks";
    case atmosphere::MiePhase::Model::Tabulated:
      return fmt::format("tabulated, {} samples of sin(theta/2)", atmosphere::TabulatedPhase::kSamples);
  }
  return "";
}

std::string profile_text(const atmosphere::DensityProfile& p) {
  if (p.kind() == atmosphere::DensityProfile::Kind::Exponential)
    return fmt::format("exponential, H = {:.1f} m", p.scale_height_m());
  return fmt::format("tabulated ({} knots, monotone cubic): {}", p.table().knots_x().size(), p.source());
}

nlohmann::json to_json(const LoadedAtmosphere& a, const std::string& hash) {
  const AtmosphereModel& m = a.model;
  const auto tau = m.zenith_optical_depth();
  auto spec = [](const Spectrum& s) { return std::vector<double>(s.begin(), s.end()); };
  nlohmann::json j;
  j["name"] = m.name;
  j["mode"] = a.mode;
  j["lut_hash"] = hash;
  j["wavelengths_nm"] = m.wavelengths_nm;
  j["ground_radius_m"] = m.ground_radius_m;
  j["top_radius_m"] = m.top_radius_m;
  j["ground_albedo"] = spec(m.ground_albedo);
  j["rayleigh"] = {{"scattering_m1", spec(m.rayleigh_scattering_m1)},
                   {"density", profile_text(m.rayleigh_density)},
                   {"phase", atmosphere::rayleigh_phase_name(m.rayleigh_phase)}};
  j["mie"] = {{"scattering_m1", spec(m.mie_scattering_m1)},
              {"extinction_m1", spec(m.mie_extinction_m1)},
              {"density", profile_text(m.mie_density)},
              {"phase", phase_name(m)},
              {"g1", spec(m.mie_phase.g1)},
              {"g2", spec(m.mie_phase.g2)},
              {"alpha", spec(m.mie_phase.alpha)}};
  for (const auto& ab : m.absorbers)
    j["absorbers"].push_back(
        {{"name", ab.name}, {"absorption_m1", spec(ab.absorption_m1)}, {"density", profile_text(ab.profile)}});
  j["zenith_optical_depth"] = {{"rayleigh", spec(tau.rayleigh)},
                               {"mie_scattering", spec(tau.mie_scattering)},
                               {"mie_absorption", spec(tau.mie_absorption)},
                               {"total", spec(tau.total)}};
  for (const auto& [name, t] : tau.absorbers) j["zenith_optical_depth"][name] = spec(t);
  j["air_mass"] = m.air_mass.enabled() ? "pickering" : "geometric";
  j["derivation"] = a.derivation;
  j["warnings"] = a.warnings;
  return j;
}

void print_text(const LoadedAtmosphere& a, const std::string& hash) {
  const AtmosphereModel& m = a.model;
  auto row = [&](const std::string& label, const Spectrum& s, const std::string& unit, const char* f = "{:>12.5g}") {
    std::string line = fmt::format("  {:<34}", label);
    for (double v : s) line += fmt::format(fmt::runtime(f), v);
    fmt::print("{}  {}\n", line, unit);
  };
  fmt::print("{}  [{} mode]\n", m.name, a.mode);
  fmt::print("  lookup-table hash: {}\n", hash);
  fmt::print("  ground radius {:.1f} km, atmosphere top {:.1f} km (thickness {:.1f} km), air mass: {}\n",
             m.ground_radius_m / 1e3, m.top_radius_m / 1e3, m.atmosphere_height_m() / 1e3,
             m.air_mass.enabled() ? "Pickering (eq. 21)" : "geometric");
  std::string header = fmt::format("  {:<34}", "wavelength");
  for (double w : m.wavelengths_nm) header += fmt::format("{:>9.1f} nm", w);
  fmt::print("\n{}\n", header);
  row("ground albedo", m.ground_albedo, "");
  const char* rayleigh_phase_text[] = {"classic eq. 9", "Penndorf eq. 10", "depolarized"};
  fmt::print("  Rayleigh ({} phase{}; {})\n", rayleigh_phase_text[int(m.rayleigh_phase)],
             m.rayleigh_phase == atmosphere::RayleighPhaseModel::Depolarized
                 ? fmt::format(", delta = {}", m.rayleigh_depolarization)
                 : "",
             profile_text(m.rayleigh_density));
  row("  beta_R^scat (ground)", m.rayleigh_scattering_m1, "m^-1");
  if (m.has_mie()) {
    fmt::print("  Mie ({}; {})\n", phase_name(m), profile_text(m.mie_density));
    row("  beta_M^scat (ground)", m.mie_scattering_m1, "m^-1");
    row("  beta_M^ext (ground)", m.mie_extinction_m1, "m^-1");
    Spectrum ssa(m.wavelength_count());
    for (std::size_t i = 0; i < ssa.size(); ++i) ssa[i] = m.mie_scattering_m1[i] / m.mie_extinction_m1[i];
    row("  single-scattering albedo", ssa, "");
    row(m.mie_phase.model == atmosphere::MiePhase::Model::Tabulated ? "  g (the table's)" : "  g1", m.mie_phase.g1, "");
    if (m.mie_phase.model == atmosphere::MiePhase::Model::DoubleHenyeyGreenstein) {
      row("  g2", m.mie_phase.g2, "");
      row("  alpha", m.mie_phase.alpha, "");
    }
  } else {
    fmt::print("  Mie: none\n");
  }
  for (const auto& ab : m.absorbers) {
    fmt::print("  {} ({})\n", ab.name, profile_text(ab.profile));
    row("  beta^abs (reference density)", ab.absorption_m1, "m^-1");
  }
  const auto tau = m.zenith_optical_depth();
  fmt::print("\n  zenith optical depth (ground to top)\n");
  row("  Rayleigh", tau.rayleigh, "");
  if (m.has_mie()) {
    row("  Mie scattering", tau.mie_scattering, "");
    row("  Mie absorption", tau.mie_absorption, "");
  }
  for (const auto& [name, t] : tau.absorbers) row("  " + name, t, "");
  row("  total", tau.total, "");
  Spectrum transmittance(tau.total.size());
  for (std::size_t i = 0; i < tau.total.size(); ++i) transmittance[i] = std::exp(-tau.total[i]);
  row("  zenith transmittance", transmittance, "");
  if (!a.derivation.empty()) {
    fmt::print("\n  derived quantities\n");
    for (const auto& d : a.derivation) fmt::print("    {}\n", d);
  }
  for (const auto& w : a.warnings) spdlog::warn("{}", w);
}

void run_show(const ShowOptions& o) {
  atmosphere::LoadOptions load;
  if (!o.wavelengths_nm.empty()) load.wavelengths_nm = o.wavelengths_nm;
  const LoadedAtmosphere a =
      o.file.empty() ? atmosphere::load_preset(o.preset, load) : atmosphere::load_atmosphere_file(o.file, load);
  const std::string hash = atmosphere::lookup_table_hash(a.model);
  if (o.json)
    fmt::print("{}\n", to_json(a, hash).dump(2));
  else
    print_text(a, hash);
}

/// The phase object of an atmosphere file ("model": "tabulated") from an
/// AERONET phase-function file: the mean of its retrievals at each wavelength.
nlohmann::json tabulated_phase_object(const std::string& path) {
  const atmosphere::AeronetPhaseFunctions a = atmosphere::read_aeronet_phase_functions(path);
  std::string times;
  for (const auto& r : a.retrievals) times += (times.empty() ? "" : ", ") + r.time;
  // The retrievals' own aerosol optical depth and Ångström exponent, where the file has them.
  std::string aerosol;
  for (const char* column : {"tau440(measured)", "alpha440-870"}) {
    std::string values;
    for (const auto& r : a.retrievals)
      if (const auto it = r.diagnostics.find(column); it != r.diagnostics.end())
        values += (values.empty() ? "" : " ") + it->second;
    if (!values.empty()) aerosol += fmt::format("; {} {}", column, values);
  }
  nlohmann::json phase;
  phase["model"] = "tabulated";
  phase["source"] = fmt::format("AERONET, {}, site {}, {}: the mean of {} retrievals ({} UTC), total mode ({}){}",
                                a.level, a.site, a.retrievals.front().date, a.retrievals.size(), times,
                                std::filesystem::path(path).filename().string(), aerosol);
  phase["scattering_angle_deg"] = a.angles_deg;
  for (const auto& c : a.mean_columns()) phase["values"][fmt::format("{}", c.wavelength_nm)] = c.values;
  return phase;
}

}  // namespace

void register_atmosphere_command(CLI::App& app) {
  CLI::App* atm = app.add_subcommand("atmosphere", "Inspect atmosphere parameter sets and presets");
  atm->require_subcommand(1);

  auto options = std::make_shared<ShowOptions>();
  CLI::App* show = atm->add_subcommand("show", "Print derived coefficients, optical depths and the lookup-table hash");
  auto* preset = show->add_option("--preset", options->preset, "Built-in preset name (see `zenith atmosphere list`)");
  auto* file = show->add_option("--file", options->file, "Atmosphere JSON file")->check(CLI::ExistingFile);
  preset->excludes(file);
  show->add_option("--wavelengths", options->wavelengths_nm, "Override the working wavelengths [nm]")
      ->check(CLI::Range(200.0, 2500.0));
  show->add_flag("--json", options->json, "Machine-readable output");
  show->callback([options, preset, file] {
    if (preset->count() + file->count() != 1) throw CLI::ValidationError("give exactly one of --preset or --file");
    run_show(*options);
  });

  auto aeronet = std::make_shared<std::string>();
  CLI::App* import_phase = atm->add_subcommand(
      "import-phase", "Print a tabulated Mie phase object (docs/atmosphere-config.md) from a measured phase function");
  import_phase
      ->add_option("--aeronet", *aeronet, "AERONET almucantar phase-function file (.pfn); the mean of its retrievals")
      ->required()
      ->check(CLI::ExistingFile);
  import_phase->callback([aeronet] { fmt::print("{}\n", tabulated_phase_object(*aeronet).dump(1)); });

  CLI::App* list = atm->add_subcommand("list", "List the built-in presets");
  list->callback([] {
    for (const auto& name : atmosphere::preset_names()) {
      const auto a = atmosphere::load_preset(name);
      fmt::print("{:<16} {}\n", name, a.model.name);
    }
  });
}

}  // namespace zenith::app
