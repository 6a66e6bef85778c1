#include "atmosphere/parameters.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>

#include "atmosphere/air_mass.h"
#include "atmosphere/constants.h"
#include "atmosphere/mie.h"
#include "atmosphere/rayleigh.h"
#include "atmosphere/reference_data.h"
#include "core/json_reader.h"

namespace zenith::atmosphere {
namespace {

constexpr int kFormatVersion = 1;

/// Allowed ranges of the physical inputs, in one place (docs/atmosphere-config.md lists them).
struct Range {
  double lo, hi;
  const char* unit;
};
constexpr Range kWavelength{200.0, 2500.0, "nm"};
constexpr Range kPlanetRadius{1e3, 1e9, "m"};
constexpr Range kAtmosphereHeight{1.0, 1e7, "m"};
constexpr Range kAlbedo{0.0, 1.0, ""};
constexpr Range kScaleHeight{1.0, 1e6, "m"};
constexpr Range kCoefficient{0.0, 1.0, "m^-1"};
constexpr Range kGravity{0.01, 1000.0, "m/s^2"};
constexpr Range kNumberDensity{1e10, 1e30, "m^-3"};
constexpr Range kPressure{1e-6, 1e9, "Pa"};
constexpr Range kTemperature{1.0, 5000.0, "K"};
constexpr Range kMolarMass{1e-3, 1.0, "kg/mol"};
constexpr Range kMassDensity{1e-12, 1e3, "kg/m^3"};
constexpr Range kGasIndex{1.0, 1.1, ""};
constexpr Range kDepolarization{0.0, 0.5, ""};
constexpr Range kCrossSection{0.0, 1e-18, "m^2"};
constexpr Range kMoleculeRadius{1e-12, 1e-8, "m"};
constexpr Range kImagIndex{0.0, 10.0, ""};
constexpr Range kParticleIndex{1.0001, 3.0, ""};
constexpr Range kParticleRadius{1e-9, 1e-3, "m"};
constexpr Range kParticleDensity{0.0, 1e15, "m^-3"};
constexpr Range kTurbidity{1.0, 64.0, ""};
constexpr Range kJunge{2.0, 6.0, ""};
constexpr Range kGoetzK{0.0, 10.0, ""};
constexpr Range kAsymmetry{-0.999, 0.999, ""};
constexpr Range kFraction{0.0, 1.0, ""};
constexpr Range kOzoneTemperature{233.0, 293.0, "K"};
constexpr Range kColumnDU{0.0, 1e4, "DU"};

/// Everything the readers below share: the working wavelengths and the output notes.
struct Context {
  std::vector<double> wavelengths_nm;
  std::vector<std::string>* warnings;
  std::vector<std::string>* derivation;
};

std::string format_nm(double wavelength_nm) {
  std::ostringstream s;
  s << wavelength_nm << " nm";
  return s.str();
}

double number(JsonReader& r, const std::string& key, const Range& range) {
  return r.number(key, range.lo, range.hi, range.unit);
}

/// A spectral quantity: either one number for all wavelengths, or an object
/// {"680": v, "550": v, ...} sampled at wavelengths in nm, interpolated
/// linearly to the working wavelengths (nearest sample outside, with a warning).
SpectralTable spectral_table(JsonReader& r, const std::string& key, const Range& range) {
  const nlohmann::json& v = r.raw(key);
  auto check_value = [&](const nlohmann::json& x, const std::string& at) {
    if (!x.is_number() || !std::isfinite(x.get<double>()) || x.get<double>() < range.lo || x.get<double>() > range.hi)
      r.fail(key, at + "= " + x.dump() + ": " + JsonReader::range_text(range.lo, range.hi, range.unit));
    return x.get<double>();
  };
  if (v.is_number()) return SpectralTable::constant(check_value(v, ""));
  if (!v.is_object() || v.empty())
    r.fail(key, "must be a number or an object {\"<wavelength nm>\": value, ...}, got " + v.dump());
  std::vector<std::pair<double, double>> samples;
  for (const auto& [wl_text, x] : v.items())
    samples.emplace_back(config::wavelength_key(r, key, wl_text), check_value(x, "[\"" + wl_text + "\"] "));
  std::sort(samples.begin(), samples.end());
  for (std::size_t i = 1; i < samples.size(); ++i)
    if (samples[i].first == samples[i - 1].first) r.fail(key, "wavelength listed twice");
  return SpectralTable(samples);
}

Spectrum spectral(JsonReader& r, const std::string& key, const Range& range, const Context& ctx) {
  const SpectralTable table = spectral_table(r, key, range);
  for (double wl : ctx.wavelengths_nm)
    if (!table.covers(wl)) {
      std::ostringstream s;
      s << r.file() << ": " << r.key_path(key) << " is sampled from " << table.samples().front().first << " to "
        << table.samples().back().first << " nm; " << wl << " nm uses the nearest sample";
      ctx.warnings->push_back(s.str());
    }
  return table.sample(ctx.wavelengths_nm);
}

/// The working wavelengths: from the file, or overridden by the caller (then
/// checked by the same rules and reported under the same key).
std::vector<double> read_wavelengths(JsonReader& r, const std::optional<std::vector<double>>& override_nm) {
  if (!r.has("wavelengths_nm") && !override_nm) return kDefaultWavelengths_nm;
  const nlohmann::json v = override_nm ? nlohmann::json(*override_nm) : r.raw("wavelengths_nm");
  if (override_nm && r.has("wavelengths_nm")) r.raw("wavelengths_nm");  // overridden, not unknown
  if (!v.is_array() || v.empty() || v.size() > 64)
    r.fail("wavelengths_nm", "must be an array of 1 to 64 wavelengths in nm, got " + v.dump());
  std::vector<double> wl;
  for (const auto& x : v) {
    if (!x.is_number() || !(x.get<double>() >= kWavelength.lo && x.get<double>() <= kWavelength.hi))
      r.fail("wavelengths_nm",
             "value " + x.dump() + " " + JsonReader::range_text(kWavelength.lo, kWavelength.hi, "nm"));
    if (std::find(wl.begin(), wl.end(), x.get<double>()) != wl.end())
      r.fail("wavelengths_nm", "wavelength " + x.dump() + " listed twice");
    wl.push_back(x.get<double>());
  }
  return wl;
}

struct Planet {
  double radius_m, top_radius_m;
  Spectrum albedo;
  std::optional<double> gravity_m_s2;
};

Planet read_planet(JsonReader& root, const Context& ctx) {
  JsonReader r = root.object("planet");
  Planet p;
  p.radius_m = number(r, "radius_m", kPlanetRadius);
  const bool by_height = r.has("atmosphere_height_m"), by_top = r.has("top_radius_m");
  if (by_height == by_top) r.fail("", "give exactly one of \"atmosphere_height_m\" and \"top_radius_m\"");
  if (by_height) {
    p.top_radius_m = p.radius_m + number(r, "atmosphere_height_m", kAtmosphereHeight);
  } else {
    p.top_radius_m = r.number("top_radius_m", 0.0, kPlanetRadius.hi * 2, "m");
    if (!(p.top_radius_m > p.radius_m + kAtmosphereHeight.lo)) {
      std::ostringstream s;
      s << "= " << p.top_radius_m << ": the atmosphere top is below the ground; must be in (" << p.radius_m << ", "
        << p.radius_m + kAtmosphereHeight.hi << "] m (radius_m + [1 m, 10000 km])";
      r.fail("top_radius_m", s.str());
    }
    if (p.top_radius_m - p.radius_m > kAtmosphereHeight.hi) r.fail("top_radius_m", "atmosphere thicker than 10000 km");
  }
  p.albedo = spectral(r, "ground_albedo", kAlbedo, ctx);
  if (r.has("surface_gravity_m_s2")) p.gravity_m_s2 = number(r, "surface_gravity_m_s2", kGravity);
  r.finish();
  return p;
}

RayleighPhaseModel read_rayleigh_phase(JsonReader& r) {
  const std::string phase = r.string_or("phase", "penndorf", {"penndorf", "classic", "depolarized"});
  if (phase == "classic") return RayleighPhaseModel::Classic;
  if (phase == "depolarized") return RayleighPhaseModel::Depolarized;
  return RayleighPhaseModel::Penndorf;
}

/// A phase function as a table (TabulatedPhase): "scattering_angle_deg", an
/// array strictly increasing from 0 to 180, and "values", {"<nm>": [P at each
/// angle, any positive scale], ...}; an optional "source" line.
std::shared_ptr<const TabulatedPhase> read_phase_table(JsonReader& r, const Context& ctx) {
  const nlohmann::json& angles = r.raw("scattering_angle_deg");
  if (!angles.is_array() || angles.size() < 2)
    r.fail("scattering_angle_deg", "must be an array of at least 2 angles in degrees, from 0 to 180");
  std::vector<double> angles_deg;
  for (std::size_t j = 0; j < angles.size(); ++j) {
    const nlohmann::json& a = angles[j];
    const std::string at = "[" + std::to_string(j) + "] = " + a.dump() + ": ";
    if (!a.is_number() || !(a.get<double>() >= 0.0 && a.get<double>() <= 180.0))
      r.fail("scattering_angle_deg", at + "must be in [0, 180] deg");
    if (!angles_deg.empty() && !(a.get<double>() > angles_deg.back()))
      r.fail("scattering_angle_deg", at + "must be greater than the angle before it");
    angles_deg.push_back(a.get<double>());
  }
  if (angles_deg.front() != 0.0 || angles_deg.back() != 180.0)
    r.fail("scattering_angle_deg", "must start at 0 and end at 180 deg (the whole range of the scattering angle)");

  const nlohmann::json& values = r.raw("values");
  if (!values.is_object() || values.empty())
    r.fail("values", "must be an object {\"<wavelength nm>\": [one value per angle], ...}");
  std::vector<TabulatedPhase::Column> columns;
  for (const auto& [wl_text, column] : values.items()) {
    const double wl = config::wavelength_key(r, "values", wl_text);
    const std::string at = "[\"" + wl_text + "\"]";
    if (!column.is_array() || column.size() != angles_deg.size())
      r.fail("values", at + " must be an array of " + std::to_string(angles_deg.size()) +
                           " values, one per scattering_angle_deg");
    TabulatedPhase::Column c{wl, {}};
    for (std::size_t j = 0; j < column.size(); ++j) {
      const nlohmann::json& v = column[j];
      if (!v.is_number() || !std::isfinite(v.get<double>()) || !(v.get<double>() > 0.0))
        r.fail("values", at + "[" + std::to_string(j) + "] = " + v.dump() + ": must be a finite number > 0");
      c.values.push_back(v.get<double>());
    }
    for (const TabulatedPhase::Column& other : columns)
      if (other.wavelength_nm == wl) r.fail("values", "wavelength " + wl_text + " listed twice");
    columns.push_back(std::move(c));
  }
  if (r.has("source")) r.string("source");
  const auto [lo, hi] = std::minmax_element(
      columns.begin(), columns.end(), [](const auto& a, const auto& b) { return a.wavelength_nm < b.wavelength_nm; });
  std::ostringstream outside;
  for (double wl : ctx.wavelengths_nm)
    if (wl < lo->wavelength_nm || wl > hi->wavelength_nm) outside << (outside.tellp() > 0 ? ", " : "") << wl;
  if (outside.tellp() > 0) {
    std::ostringstream s;
    s << r.file() << ": " << r.key_path("values") << " is given from " << lo->wavelength_nm << " to "
      << hi->wavelength_nm << " nm; " << outside.str() << " nm use the nearest column";
    ctx.warnings->push_back(s.str());
  }
  auto table = std::make_shared<const TabulatedPhase>(angles_deg, columns, ctx.wavelengths_nm);
  if (ctx.derivation) {
    std::ostringstream s;
    s << "Mie phase table: " << angles_deg.size() << " angles at " << columns.size() << " wavelengths, resampled on "
      << TabulatedPhase::kSamples << " samples of sin(theta/2); integral of P over "
      << "the sphere as given " << table->integral_as_given(0) << " at " << ctx.wavelengths_nm.front()
      << " nm (normalised to 1); asymmetry g " << table->asymmetry(0) << " there";
    ctx.derivation->push_back(s.str());
  }
  return table;
}

MiePhase read_mie_phase(JsonReader& parent, const Context& ctx) {
  JsonReader r = parent.object("phase");
  MiePhase phase;
  const std::string model =
      r.string("model", {"henyey_greenstein", "double_henyey_greenstein", "cornette_shanks", "tabulated"});
  const std::size_t n = ctx.wavelengths_nm.size();
  if (model == "tabulated") {
    phase.model = MiePhase::Model::Tabulated;
    phase.table = read_phase_table(r, ctx);
    phase.g1 = Spectrum(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) phase.g1[i] = phase.table->asymmetry(i);
    phase.g2 = Spectrum(n, 0.0);
    phase.alpha = Spectrum(n, 1.0);
  } else if (model == "double_henyey_greenstein") {
    phase.model = MiePhase::Model::DoubleHenyeyGreenstein;
    phase.g1 = spectral(r, "g1", kAsymmetry, ctx);
    phase.g2 = spectral(r, "g2", kAsymmetry, ctx);
    phase.alpha = spectral(r, "alpha", kFraction, ctx);
  } else {
    phase.model = model == "cornette_shanks" ? MiePhase::Model::CornetteShanks : MiePhase::Model::HenyeyGreenstein;
    phase.g1 = spectral(r, "g", kAsymmetry, ctx);
    phase.g2 = Spectrum(n, 0.0);
    phase.alpha = Spectrum(n, 1.0);
  }
  r.finish();
  return phase;
}

DensityProfile read_profile(JsonReader& parent, const std::string& key, double* reference_density_m3) {
  JsonReader r = parent.object(key);
  const std::string type = r.string("type", {"exponential", "us_standard_1976", "table"});
  DensityProfile p = DensityProfile::exponential(1.0);
  if (reference_density_m3) *reference_density_m3 = 0.0;
  if (type == "exponential") {
    p = DensityProfile::exponential(number(r, "scale_height_m", kScaleHeight));
  } else if (type == "us_standard_1976") {
    const std::string species = r.string("species", {"air", "o3", "o2", "h2o", "co2", "no2"});
    p = us_standard_1976_profile(species, reference_density_m3);
  } else {
    auto read_array = [&](const std::string& k, double lo, double hi) {
      const nlohmann::json& v = r.raw(k);
      if (!v.is_array() || v.size() < 2) r.fail(k, "must be an array of at least 2 numbers");
      std::vector<double> out;
      for (const auto& x : v) {
        if (!x.is_number() || !(x.get<double>() >= lo && x.get<double>() <= hi))
          r.fail(k, "value " + x.dump() + " " + JsonReader::range_text(lo, hi, ""));
        out.push_back(x.get<double>());
      }
      return out;
    };
    std::vector<double> alt = read_array("altitude_m", -1e4, 1e7);
    std::vector<double> rho = read_array("relative_density", 0.0, 1e6);
    if (alt.size() != rho.size()) r.fail("relative_density", "must have as many values as altitude_m");
    for (std::size_t i = 1; i < alt.size(); ++i)
      if (!(alt[i] > alt[i - 1])) r.fail("altitude_m", "must increase strictly");
    p = DensityProfile::tabulated(alt, rho, r.file() + r.path());
  }
  r.finish();
  return p;
}

AirMassStretch read_air_mass(JsonReader& root, const AtmosphereModel& m) {
  if (root.string_or("air_mass", "geometric", {"geometric", "pickering"}) == "geometric") return {};
  AirMassStretch stretch = AirMassStretch::pickering(m.ground_radius_m, m.top_radius_m, m.rayleigh_density);
  // Pickering's formula is Earth's refraction; it is a small correction only for
  // Earth-like ratios of radius to scale height (Earth: stretch 1 to ~1.09).
  if (stretch.max_stretch() > 1.5 || stretch.geometric_air_mass(0.0) > 1.5 * pickering_air_mass(0.0)) {
    std::ostringstream s;
    s << "= \"pickering\": Pickering's air mass is fitted to Earth (horizon air mass 38.7); this planet's "
         "straight-ray horizon air mass is "
      << stretch.geometric_air_mass(0.0) << ", so the optical-depth stretch would be " << stretch.max_stretch()
      << "; it must stay in [1, 1.5]. Use \"geometric\" for this atmosphere";
    root.fail("air_mass", s.str());
  }
  return stretch;
}

void check_mie_consistency(JsonReader& r, const std::string& key, const AtmosphereModel& m) {
  for (std::size_t i = 0; i < m.wavelength_count(); ++i)
    if (m.mie_scattering_m1[i] > m.mie_extinction_m1[i] * (1.0 + 1e-9)) {
      std::ostringstream s;
      s << "Mie scattering " << m.mie_scattering_m1[i] << " m^-1 exceeds Mie extinction " << m.mie_extinction_m1[i]
        << " m^-1 at " << m.wavelengths_nm[i]
        << " nm: scattering must be in [0, extinction] (single-scattering albedo <= 1)";
      r.fail(key, s.str());
    }
}

// ---------------------------------------------------------------- standard mode

void resolve_standard(JsonReader& root, AtmosphereModel& m, const Context& ctx) {
  {
    JsonReader r = root.object("rayleigh");
    m.rayleigh_scattering_m1 = spectral(r, "scattering_m1", kCoefficient, ctx);
    m.rayleigh_density = DensityProfile::exponential(number(r, "scale_height_m", kScaleHeight));
    m.rayleigh_phase = read_rayleigh_phase(r);
    if (m.rayleigh_phase == RayleighPhaseModel::Depolarized || r.has("depolarization"))
      m.rayleigh_depolarization = number(r, "depolarization", kDepolarization);
    r.finish();
  }
  const std::size_t n = ctx.wavelengths_nm.size();
  m.mie_scattering_m1 = m.mie_extinction_m1 = Spectrum(n, 0.0);
  m.mie_phase = {MiePhase::Model::HenyeyGreenstein, Spectrum(n, 0.0), Spectrum(n, 0.0), Spectrum(n, 1.0), nullptr};
  if (auto r = root.optional_object("mie")) {
    m.mie_scattering_m1 = spectral(*r, "scattering_m1", kCoefficient, ctx);
    m.mie_extinction_m1 = spectral(*r, "extinction_m1", kCoefficient, ctx);
    m.mie_density = DensityProfile::exponential(number(*r, "scale_height_m", kScaleHeight));
    m.mie_phase = read_mie_phase(*r, ctx);
    check_mie_consistency(*r, "scattering_m1", m);
    r->finish();
  }
  if (root.has("absorbers")) {
    const nlohmann::json& list = root.raw("absorbers");
    if (!list.is_array()) root.fail("absorbers", "must be an array of absorber objects");
    for (std::size_t i = 0; i < list.size(); ++i) {
      JsonReader r(list[i], root.file(), "/absorbers/" + std::to_string(i));
      Absorber a;
      a.name = r.string("name");
      a.absorption_m1 = spectral(r, "absorption_m1", kCoefficient, ctx);
      a.profile = read_profile(r, "profile", nullptr);
      r.finish();
      m.absorbers.push_back(std::move(a));
    }
  }
}

// ---------------------------------------------------------------- advanced mode

struct Gas {
  double number_density_m3;
  DensityProfile profile = DensityProfile::exponential(1.0);
};

Gas resolve_gas(JsonReader& root, AtmosphereModel& m, const Planet& planet, const Context& ctx) {
  JsonReader r = root.object("gas");
  Gas gas;
  std::ostringstream note;
  // Optional state variables; NaN when absent (GCC 12 misdiagnoses std::optional<double> here).
  const double kAbsent = std::numeric_limits<double>::quiet_NaN();
  const double temperature = r.has("temperature_K") ? number(r, "temperature_K", kTemperature) : kAbsent;
  const double molar_mass = r.has("molar_mass_kg_mol") ? number(r, "molar_mass_kg_mol", kMolarMass) : kAbsent;
  const double gravity = planet.gravity_m_s2.value_or(kAbsent);

  // Number density N: given, or p/(k_B T), or N_A ρ/M.
  const int ways = int(r.has("number_density_m3")) + int(r.has("pressure_Pa")) + int(r.has("mass_density_kg_m3"));
  if (ways != 1)
    r.fail("",
           "give exactly one of \"number_density_m3\", \"pressure_Pa\" (with temperature_K) or "
           "\"mass_density_kg_m3\" (with molar_mass_kg_mol)");
  if (r.has("number_density_m3")) {
    gas.number_density_m3 = number(r, "number_density_m3", kNumberDensity);
  } else if (r.has("pressure_Pa")) {
    const double p = number(r, "pressure_Pa", kPressure);
    if (std::isnan(temperature))
      r.fail("temperature_K", "missing required key (needed with pressure_Pa: N = p/(k_B T))");
    gas.number_density_m3 = number_density_from_pressure(p, temperature);
    note << "N = p/(k_B T) = " << gas.number_density_m3 << " m^-3; ";
  } else {
    const double rho = number(r, "mass_density_kg_m3", kMassDensity);
    if (std::isnan(molar_mass))
      r.fail("molar_mass_kg_mol", "missing required key (needed with mass_density_kg_m3: N = N_A rho/M)");
    gas.number_density_m3 = number_density_from_mass_density(rho, molar_mass);
    note << "N = N_A rho/M = " << gas.number_density_m3 << " m^-3; ";
  }
  if (!(gas.number_density_m3 >= kNumberDensity.lo && gas.number_density_m3 <= kNumberDensity.hi))
    r.fail("", "derived number density out of range [1e10, 1e30] m^-3");

  // Scale height: given, or H = R T/(M g).
  double H = 0.0;
  if (r.has("scale_height_m")) {
    H = number(r, "scale_height_m", kScaleHeight);
  } else {
    if (std::isnan(temperature) || std::isnan(molar_mass) || std::isnan(gravity))
      r.fail("scale_height_m",
             "missing: give scale_height_m, or temperature_K, molar_mass_kg_mol and planet.surface_gravity_m_s2 "
             "(H = R T/(M g))");
    H = scale_height(temperature, molar_mass, gravity);
    if (!(H >= kScaleHeight.lo && H <= kScaleHeight.hi)) r.fail("scale_height_m", "derived scale height out of range");
    note << "H = R T/(M g) = " << H << " m; ";
  }
  gas.profile = DensityProfile::exponential(H);
  m.rayleigh_density = gas.profile;

  // Refractive index (real part) and the density it was measured at.
  const std::size_t n = ctx.wavelengths_nm.size();
  Spectrum index(n);
  double index_density = gas.number_density_m3;
  if (r.has("refractive_index") && r.raw("refractive_index").is_string()) {
    r.string("refractive_index", {"standard_air"});
    for (std::size_t i = 0; i < n; ++i) {
      index[i] = standard_air_refractive_index(ctx.wavelengths_nm[i]);
      if (ctx.wavelengths_nm[i] > 2000.0)
        ctx.warnings->push_back(r.file() + ": " + r.key_path("refractive_index") +
                                ": Edlen's standard-air formula is valid to 2000 nm; extrapolated to " +
                                format_nm(ctx.wavelengths_nm[i]));
    }
    index_density = kStandardAirNumberDensity_m3;
  } else {
    index = spectral(r, "refractive_index", kGasIndex, ctx);
  }
  if (r.has("refractive_index_number_density_m3"))
    index_density = number(r, "refractive_index_number_density_m3", kNumberDensity);
  const double depolarization = number(r, "depolarization", kDepolarization);

  // Rayleigh scattering, eq. (11), with (n − 1) scaled to the gas density.
  m.rayleigh_scattering_m1 = Spectrum(n);
  for (std::size_t i = 0; i < n; ++i)
    m.rayleigh_scattering_m1[i] = rayleigh_scattering_coefficient_scaled(ctx.wavelengths_nm[i], index[i], index_density,
                                                                         gas.number_density_m3, depolarization);
  note << "f(delta) = " << king_factor(depolarization);
  for (std::size_t i = 0; i < n; ++i)
    if (!(m.rayleigh_scattering_m1[i] <= kCoefficient.hi)) {
      std::ostringstream s;
      s << "derived Rayleigh scattering " << m.rayleigh_scattering_m1[i] << " m^-1 at " << ctx.wavelengths_nm[i]
        << " nm must be in [0, 1] m^-1 (an opaque gas: check the number density and refractive index)";
      r.fail("", s.str());
    }
  m.rayleigh_phase = read_rayleigh_phase(r);
  m.rayleigh_depolarization = depolarization;

  // Molecular absorption: cross section × N, or eq. (12) from the complex index.
  if (auto a = r.optional_object("absorption")) {
    Absorber abs;
    abs.name = "molecular absorption";
    abs.profile = gas.profile;
    if (a->has("cross_section_m2")) {
      abs.absorption_m1 = spectral(*a, "cross_section_m2", kCrossSection, ctx) * gas.number_density_m3;
    } else {
      const Spectrum k = spectral(*a, "refractive_index_imag", kImagIndex, ctx);
      const double radius = number(*a, "molecule_radius_m", kMoleculeRadius);
      abs.absorption_m1 = Spectrum(n);
      for (std::size_t i = 0; i < n; ++i) {
        // Real part of the index at the gas's own density ((n − 1) ∝ N).
        const double n_gas = 1.0 + (index[i] - 1.0) * gas.number_density_m3 / index_density;
        abs.absorption_m1[i] =
            small_particle_absorption_coefficient(ctx.wavelengths_nm[i], {n_gas, k[i]}, radius, gas.number_density_m3);
      }
    }
    a->finish();
    m.absorbers.push_back(std::move(abs));
  }
  r.finish();
  ctx.derivation->push_back("gas: " + note.str());
  return gas;
}

void resolve_ozone(JsonReader& root, AtmosphereModel& m, const Context& ctx) {
  auto r = root.optional_object("ozone");
  if (!r) return;
  Absorber a;
  a.name = "ozone";
  double peak_m3 = 0.0;
  const std::string profile = r->string("profile", {"us_standard_1976"});
  (void)profile;
  a.profile = us_standard_1976_profile("o3", &peak_m3);
  // Optionally rescale the profile to a given total column (Dobson units).
  const double native_DU = peak_m3 * a.profile.column_m(0.0, 1.2e5) / kDobsonUnit_per_m2;
  double scale = 1.0;
  if (r->has("column_DU")) scale = number(*r, "column_DU", kColumnDU) / native_DU;

  const std::size_t n = ctx.wavelengths_nm.size();
  Spectrum sigma(n);
  if (r->has("cross_section_m2")) {
    sigma = spectral(*r, "cross_section_m2", kCrossSection, ctx);
  } else {
    r->string("cross_sections", {"bogumil2003"});
    const double T = number(*r, "temperature_K", kOzoneTemperature);
    for (std::size_t i = 0; i < n; ++i) {
      bool covered = true;
      sigma[i] = ozone_cross_section_m2(ctx.wavelengths_nm[i], T, &covered);
      if (!covered)
        ctx.warnings->push_back(r->file() + ": " + r->key_path("cross_sections") + ": table covers 360-830 nm; " +
                                format_nm(ctx.wavelengths_nm[i]) + " uses the nearest bin");
    }
  }
  // Eq. (15): β_O3^abs(h, λ) = σ(λ) ρ_O3(h).
  a.absorption_m1 = sigma * (peak_m3 * scale);
  std::ostringstream note;
  note << "ozone: peak " << peak_m3 * scale << " m^-3, column " << native_DU * scale << " DU";
  ctx.derivation->push_back(note.str());
  r->finish();
  m.absorbers.push_back(std::move(a));
}

void resolve_oxygen(JsonReader& root, AtmosphereModel& m, const Gas& gas, const Context& ctx) {
  auto r = root.optional_object("oxygen");
  if (!r) return;
  Absorber a;
  a.name = "oxygen";
  const Spectrum sigma = spectral(*r, "cross_section_m2", kCrossSection, ctx);
  const double fraction = number(*r, "volume_fraction", kFraction);
  // Eq. (14) with the sign of the exponent corrected (density falls with height):
  //   ρ_O2(h) = O2% · N0 · exp(−h/H_O2);  eq. (13): β = σ_O2 ρ_O2.
  a.profile =
      r->has("scale_height_m") ? DensityProfile::exponential(number(*r, "scale_height_m", kScaleHeight)) : gas.profile;
  a.absorption_m1 = sigma * (fraction * gas.number_density_m3);
  r->finish();
  m.absorbers.push_back(std::move(a));
}

void resolve_aerosol(JsonReader& root, AtmosphereModel& m, const Context& ctx) {
  const std::size_t n = ctx.wavelengths_nm.size();
  m.mie_scattering_m1 = m.mie_extinction_m1 = Spectrum(n, 0.0);
  m.mie_phase = {MiePhase::Model::HenyeyGreenstein, Spectrum(n, 0.0), Spectrum(n, 0.0), Spectrum(n, 1.0), nullptr};
  auto r = root.optional_object("aerosol");
  if (!r) return;
  m.mie_density = DensityProfile::exponential(number(*r, "scale_height_m", kScaleHeight));

  {  // Scattering from turbidity, eq. (17).
    JsonReader s = r->object("scattering");
    const double T = number(s, "turbidity", kTurbidity);
    const double nu = number(s, "junge_exponent", kJunge);
    const Spectrum K = spectral(s, "K", kGoetzK, ctx);
    for (std::size_t i = 0; i < n; ++i)
      m.mie_scattering_m1[i] = mie_scattering_from_turbidity(ctx.wavelengths_nm[i], T, nu, K[i]);
    s.finish();
  }
  {  // Extinction: anomalous diffraction (eq. 18–20) or a single-scattering albedo.
    JsonReader e = r->object("extinction");
    if (auto ada = e.optional_object("anomalous_diffraction")) {
      const double radius = number(*ada, "mean_radius_m", kParticleRadius);
      const Spectrum re = spectral(*ada, "refractive_index_real", kParticleIndex, ctx);
      const Spectrum im = spectral(*ada, "refractive_index_imag", kImagIndex, ctx);
      const double N = number(*ada, "number_density_m3", kParticleDensity);
      for (std::size_t i = 0; i < n; ++i)
        m.mie_extinction_m1[i] = mie_extinction_anomalous_diffraction(ctx.wavelengths_nm[i], {re[i], im[i]}, radius, N);
      ada->finish();
    } else {
      const Spectrum ssa = spectral(e, "single_scattering_albedo", {1e-3, 1.0, ""}, ctx);
      for (std::size_t i = 0; i < n; ++i) m.mie_extinction_m1[i] = m.mie_scattering_m1[i] / ssa[i];
    }
    e.finish();
    for (std::size_t i = 0; i < n; ++i)
      if (!(m.mie_extinction_m1[i] <= kCoefficient.hi))
        r->fail("extinction", "derived Mie extinction " + std::to_string(m.mie_extinction_m1[i]) +
                                  " m^-1 must be in [0, 1] m^-1 (check number density and radius)");
    check_mie_consistency(*r, "extinction", m);
  }
  m.mie_phase = read_mie_phase(*r, ctx);
  r->finish();
}

}  // namespace

LoadedAtmosphere resolve_atmosphere(const nlohmann::json& parameters, const std::string& source,
                                    const LoadOptions& options) {
  LoadedAtmosphere out;
  out.parameters = parameters;
  JsonReader root(parameters, source);
  const int version = root.integer("zenith_atmosphere", kFormatVersion, kFormatVersion);
  (void)version;
  AtmosphereModel& m = out.model;
  m.name = root.string_or("name", source, {});
  // Free-text provenance of the values (not part of the physics or the hash).
  if (root.has("sources")) {
    const nlohmann::json& s = root.raw("sources");
    if (!s.is_array() || !std::all_of(s.begin(), s.end(), [](const nlohmann::json& x) { return x.is_string(); }))
      root.fail("sources", "must be an array of strings");
  }
  out.mode = root.string("mode", {"standard", "advanced"});
  m.wavelengths_nm = read_wavelengths(root, options.wavelengths_nm);
  Context ctx{m.wavelengths_nm, &out.warnings, &out.derivation};

  const Planet planet = read_planet(root, ctx);
  m.ground_radius_m = planet.radius_m;
  m.top_radius_m = planet.top_radius_m;
  m.ground_albedo = planet.albedo;

  if (out.mode == "standard") {
    resolve_standard(root, m, ctx);
  } else {
    const Gas gas = resolve_gas(root, m, planet, ctx);
    resolve_ozone(root, m, ctx);
    resolve_oxygen(root, m, gas, ctx);
    resolve_aerosol(root, m, ctx);
  }
  m.air_mass = read_air_mass(root, m);
  root.finish();
  try {
    m.check();
  } catch (const std::invalid_argument& e) {
    throw ConfigError(source, "", e.what());
  }
  return out;
}

LoadedAtmosphere load_atmosphere_file(const std::string& path, const LoadOptions& options) {
  return resolve_atmosphere(read_json_file(path), path, options);
}

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  for (const std::string& f : embedded_files_under("atmospheres/")) {
    const std::string base = f.substr(std::string("atmospheres/").size());
    names.push_back(base.substr(0, base.size() - std::string(".json").size()));
  }
  return names;
}

nlohmann::json preset_parameters(const std::string& name) {
  const std::string file = "atmospheres/" + name + ".json";
  try {
    return parse_json(std::string(embedded_file(file)), "preset:" + name);
  } catch (const std::out_of_range&) {
    std::string list;
    for (const auto& p : preset_names()) list += (list.empty() ? "" : ", ") + p;
    throw ConfigError("preset:" + name, "", "unknown preset; available: " + list);
  }
}

LoadedAtmosphere load_preset(const std::string& name, const LoadOptions& options) {
  return resolve_atmosphere(preset_parameters(name), "preset:" + name, options);
}

}  // namespace zenith::atmosphere
