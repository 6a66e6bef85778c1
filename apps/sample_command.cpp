// `zenith sample`: sky radiance (and luminance) for view directions from a
// point at a given altitude, from the lookup tables or the reference solver;
// also transmittance and ground irradiance. Output: CSV with a header.
#include <fmt/format.h>
#include <fmt/os.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "apps/cli_options.h"
#include "apps/commands.h"
#include "apps/sampling.h"
#include "astro/civil_time.h"
#include "astro/sky_positions.h"
#include "astro/solar_eclipse.h"
#include "atmosphere/named_inputs.h"
#include "core/json_reader.h"
#include "image/colour.h"
#include "render/lut/table_provider.h"

namespace zenith::app {
namespace {

struct SampleArgs {
  std::string atmosphere, directions_file, grid, method = "lut", out = "-", tables = "paper", quantity = "radiance",
                                                 cache_dir, eclipse_at;
  std::vector<double> site;  ///< latitude, longitude [deg] with eclipse_at
  double altitude_m = 0.0, sun_zenith_deg = 30.0, sun_azimuth_deg = 0.0, sun_radius_deg = 0.2666;
  std::uint64_t seed = 1;
  std::size_t samples = 4096;
  int orders = atmosphere::lut::kDefaultScatteringOrders;
  bool cpu = false, colour = false, polarized = false, stokes = false, aerosol_depolarizes = false;
  std::vector<double> colour_band_nm = {410.0, 800.0};
  std::vector<int> reference_orders;  ///< first, last scattering order of --method reference (empty: all)
  int shadow_passes = 0;              ///< the tables' Moon's shadow: passes (0: MoonShadowOptions' own)
  bool scalar_shadow = false;
  unsigned threads = 0;
};

using atmosphere::ViewDirection;

std::vector<ViewDirection> read_directions(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path, "", "cannot open file");
  std::vector<ViewDirection> dirs;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#' || line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (line.find_first_of("abcdefghijklmnopqrstuvwxyz") != std::string::npos) continue;  // header
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    ViewDirection d{};
    if (!(s >> d.zenith_deg >> d.azimuth_deg) || d.zenith_deg < 0.0 || d.zenith_deg > 180.0)
      throw ConfigError(path, "line " + std::to_string(line_no),
                        "expected 'zenith_deg,azimuth_deg' with zenith in [0, 180] degrees, got '" + line + "'");
    dirs.push_back(d);
  }
  if (dirs.empty()) throw ConfigError(path, "", "no directions");
  return dirs;
}

std::vector<ViewDirection> grid_directions(const std::string& grid) {
  unsigned nz = 0, na = 0;
  char x = 0;
  std::istringstream s(grid);
  if (!(s >> nz >> x >> na) || x != 'x' || nz < 1 || na < 1 || nz * na > 1000000)
    throw std::invalid_argument("--grid must be ZxA (zenith steps x azimuth steps), e.g. 19x8");
  std::vector<ViewDirection> dirs;
  for (unsigned a = 0; a < na; ++a)
    for (unsigned z = 0; z < nz; ++z) dirs.push_back({nz == 1 ? 0.0 : 90.0 * z / (nz - 1), 360.0 * a / na});
  return dirs;
}

/// `a.eclipse_at` seen from `a.site` (sampling.h's place_sun_and_moon), after the command line's checks.
void place_eclipse(const SampleArgs& a, const atmosphere::AtmosphereModel& model, SamplingRequest& r) {
  if (a.site.size() != 2) throw std::invalid_argument("--eclipse-at needs --site LATITUDE,LONGITUDE [deg]");
  if (a.method != "reference" && a.quantity == "irradiance")
    throw std::invalid_argument(
        "--eclipse-at with --method lut gives radiance and transmittance; the eclipsed ground irradiance is "
        "--method reference's (the path tracer)");
  const astro::Site site{a.site[0], a.site[1], std::min(a.altitude_m, 10000.0)};
  const astro::SkyPositions sky(astro::AstroTime::from_utc(astro::parse_utc_time(a.eclipse_at)), site);
  place_sun_and_moon(sky, model, r);
  const astro::SolarEclipseView v = astro::solar_eclipse_view(sky);
  spdlog::info(
      "{} at {:.4f}, {:.4f}: sun {:.2f}° up, azimuth {:.2f}°; eclipse {}, magnitude {:.4f}, obscuration {:.4f}",
      a.eclipse_at, a.site[0], a.site[1], 90.0 - r.geometry.sun_zenith_deg, r.geometry.sun_azimuth_deg,
      astro::to_string(v.kind), v.magnitude, v.obscuration);
}

void run_sample(const SampleArgs& a) {
  const auto loaded = atmosphere::load_atmosphere_argument(a.atmosphere);
  SamplingRequest r;
  r.geometry.altitude_m = a.altitude_m;
  r.geometry.sun_zenith_deg = a.sun_zenith_deg;
  r.geometry.sun_azimuth_deg = a.sun_azimuth_deg;
  r.sun_angular_radius_deg = a.sun_radius_deg;
  if (!a.eclipse_at.empty()) place_eclipse(a, loaded.model, r);
  if (a.colour) {
    if (a.quantity != "radiance")
      throw std::invalid_argument("--colour is the colour of the sky's radiance; it does not apply to --quantity " +
                                  a.quantity);
    if (const std::string why = image::colour_spectrum_problem(loaded.model.wavelengths_nm); !why.empty())
      throw ConfigError(a.atmosphere, "wavelengths_nm", "--colour: " + why);
    check_wavelength_band("--colour-band-nm", a.colour_band_nm);
    const auto in_band =
        std::count_if(loaded.model.wavelengths_nm.begin(), loaded.model.wavelengths_nm.end(),
                      [&](double nm) { return nm >= a.colour_band_nm[0] && nm <= a.colour_band_nm[1]; });
    if (in_band < 3)
      throw ConfigError(a.atmosphere, "wavelengths_nm",
                        fmt::format("--colour-band-nm {},{} holds {} of the wavelengths (an effective temperature "
                                    "needs at least 3)",
                                    a.colour_band_nm[0], a.colour_band_nm[1], in_band));
    r.colour = true;
    r.colour_band_nm = {a.colour_band_nm[0], a.colour_band_nm[1]};
  }
  if (a.polarized && a.method != "reference")
    throw std::invalid_argument(
        "--polarized is the reference solver's vector radiative transfer; it needs --method "
        "reference (the tables are scalar)");
  r.polarized = a.polarized;
  if (a.stokes && !(a.polarized && a.quantity == "radiance"))
    throw std::invalid_argument(
        "--stokes is the polarization of the sky's radiance in the reference solver's vector transfer; it needs "
        "--method reference --polarized (and --quantity radiance)");
  r.stokes = a.stokes;
  if (a.aerosol_depolarizes && !a.polarized)
    throw std::invalid_argument(
        "--aerosol-depolarizes bounds the aerosols' share of the reference solver's vector transfer; it needs "
        "--method reference --polarized");
  r.aerosol_depolarizes = a.aerosol_depolarizes;
  if (!a.reference_orders.empty()) {
    if (a.method != "reference")
      throw std::invalid_argument(
          "--reference-orders splits the reference solver's light by order; it needs "
          "--method reference (the tables sum their orders)");
    if (!(a.reference_orders[0] >= 1 && a.reference_orders[0] <= a.reference_orders[1]))
      throw std::invalid_argument(
          fmt::format("--reference-orders {},{}: the first order must be at least 1 and not "
                      "above the last",
                      a.reference_orders[0], a.reference_orders[1]));
    r.reference_orders = {a.reference_orders[0], a.reference_orders[1]};
  }
  if ((a.shadow_passes > 0 || a.scalar_shadow) && (a.method != "lut" || a.eclipse_at.empty()))
    throw std::invalid_argument(
        "--shadow-passes and --scalar-shadow shape the Moon's shadow over the tables; they need --method lut and "
        "--eclipse-at");
  if (a.shadow_passes > 0) r.shadow.iterations = a.shadow_passes;
  r.shadow.polarized = !a.scalar_shadow;
  r.seed = a.seed;
  r.directions = a.directions_file.empty() ? grid_directions(a.grid.empty() ? "10x4" : a.grid)
                                           : read_directions(a.directions_file);
  r.method = a.method == "reference" ? SamplingMethod::Reference : SamplingMethod::Tables;
  r.reference_samples = a.samples;
  r.threads = a.threads;
  atmosphere::apply_table_set(a.tables, r.tables.options);
  r.tables.options.max_orders = a.orders;
  r.tables.options.threads = a.threads;
  r.tables.backend = a.cpu ? render::PrecomputeBackend::Cpu : render::PrecomputeBackend::Gpu;
  if (!a.cache_dir.empty()) r.tables.cache_directory = a.cache_dir;

  std::string csv;
  if (a.quantity == "radiance")
    csv = sample_radiance_csv(loaded.model, r);
  else if (a.quantity == "transmittance")
    csv = sample_transmittance_csv(loaded.model, r);
  else
    csv = sample_irradiance_csv(loaded.model, r);
  if (a.out == "-") {
    fmt::print("{}", csv);
  } else {
    std::ofstream out(a.out);
    if (!out) throw std::runtime_error("cannot write " + a.out);
    out << csv;
    spdlog::info("wrote {} ({} rows)", a.out, std::count(csv.begin(), csv.end(), '\n') - 1);
  }
}

}  // namespace

void register_sample_command(CLI::App& app) {
  auto args = std::make_shared<SampleArgs>();
  CLI::App* cmd = app.add_subcommand("sample", "Query sky radiance, transmittance or ground irradiance (CSV)");
  cmd->add_option("--atmosphere", args->atmosphere, "Preset name or atmosphere JSON file")->required();
  cmd->add_option("--altitude-m", args->altitude_m, "Observer altitude above the ground [m]")
      ->check(CLI::Range(0.0, 1e13));
  auto* sun_zenith = cmd->add_option("--sun-zenith-deg", args->sun_zenith_deg, "Sun zenith angle [deg]")
                         ->check(CLI::Range(0.0, 180.0));
  auto* sun_azimuth = cmd->add_option("--sun-azimuth-deg", args->sun_azimuth_deg, "Sun azimuth [deg]")
                          ->check(CLI::Range(-360.0, 360.0));
  auto* eclipse = cmd->add_option(
      "--eclipse-at", args->eclipse_at,
      "UTC instant (YYYY-MM-DDThh:mm[:ss]Z): the Sun and the Moon then, seen from --site, with the "
      "Moon in front of the limb-darkened disc (a solar eclipse's sky: the tables with the Moon's shadow, or the "
      "path tracer with --method reference); azimuths "
      "count from north through east");
  eclipse->excludes(sun_zenith)->excludes(sun_azimuth);
  cmd->add_option("--site", args->site, "LATITUDE,LONGITUDE [deg] of --eclipse-at")
      ->delimiter(',')
      ->expected(2)
      ->needs(eclipse);
  auto* dirs = cmd->add_option("--directions", args->directions_file, "CSV of zenith_deg,azimuth_deg per line")
                   ->check(CLI::ExistingFile);
  auto* grid = cmd->add_option("--grid", args->grid, "ZxA: zenith angles 0..90 in Z steps, A azimuths (default 10x4)");
  dirs->excludes(grid);
  cmd->add_option("--method", args->method, "lut (tables) or reference (independent solver)")
      ->check(CLI::IsMember({"lut", "reference"}));
  cmd->add_option("--quantity", args->quantity, "radiance (default), transmittance or irradiance")
      ->check(CLI::IsMember({"radiance", "transmittance", "irradiance"}));
  cmd->add_option("--sun-angular-radius-deg", args->sun_radius_deg, "Apparent radius of the sun's disc [deg]")
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--seed", args->seed, "Random seed of the reference method");
  cmd->add_option("--samples", args->samples, "Monte Carlo paths per direction for --method reference")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}));
  cmd->add_flag("--polarized", args->polarized,
                "--method reference: vector radiative transfer, the light's linear polarization carried through "
                "every scattering (default: scalar, as the tables)");
  cmd->add_flag("--stokes", args->stokes,
                "--method reference --polarized: add each direction's linear polarization per wavelength — Stokes "
                "Q_rel and U_rel against the vertical (U > 0: the E-vector leaning toward increasing azimuth; at "
                "the zenith the vertical points away from the row's azimuth), the degree P with its standard error "
                "se_P, and chi, the E-vector's angle from the vertical [deg]");
  cmd->add_flag("--aerosol-depolarizes", args->aerosol_depolarizes,
                "--method reference --polarized: the aerosols send their light on unpolarized, the other bound of "
                "their scattering matrix (default: the polarization carried through unchanged)");
  cmd->add_option("--reference-orders", args->reference_orders,
                  "--method reference: only the light scattered FIRST to LAST times, as FIRST,LAST in [1, 1000] "
                  "(1: single scattering and the direct sun the ground reflects; default: all)")
      ->delimiter(',')
      ->expected(2)
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--shadow-passes", args->shadow_passes,
                  "--eclipse-at with the tables: passes of the Moon's shadow over the light arriving at its nodes, "
                  "in [1, 4] (1: the once-scattered light's share for every order; default 2)")
      ->check(CLI::Range(1, 4));
  cmd->add_flag("--scalar-shadow", args->scalar_shadow,
                "--eclipse-at with the tables: the Moon's shadow without the light's polarization (scalar "
                "transfer, as the reference solver without --polarized)");
  cmd->add_option("--orders", args->orders, "Scattering orders of the tables")->check(CLI::Range(1, 50));
  cmd->add_option("--tables", args->tables,
                  "Table sizes: paper (default), twilight (128 mu_s texels and 200 ray samples, for dusk and night), "
                  "small, large")
      ->check(CLI::IsMember(atmosphere::table_size_names()));
  cmd->add_flag("--colour", args->colour,
                "Radiance: add each direction's colour under the Kurucz sun — CIE 1931 x, y, correlated colour "
                "temperature CCT_K and Duv, effective blackbody temperature T_eff_K over --colour-band-nm (the "
                "atmosphere needs at least 16 wavelengths spanning 400-700 nm)");
  add_wavelength_band_option(cmd, "--colour-band-nm", args->colour_band_nm,
                             "--colour: the effective temperature's band, first,last wavelength [nm] (default "
                             "410,800, as Dandekar & Turtle 1971; at least 3 of the atmosphere's wavelengths inside)");
  cmd->add_flag("--cpu", args->cpu, "Precompute tables on the CPU");
  cmd->add_option("--cache", args->cache_dir, "Table cache directory (default $XDG_CACHE_HOME/zenith)");
  cmd->add_option("--threads", args->threads, "CPU threads (default: all)");
  cmd->add_option("--out", args->out, "Output CSV file ('-' for standard output)");
  cmd->callback([args] { run_sample(*args); });
}

}  // namespace zenith::app
