#include "atmosphere/model_hash.h"

#include "core/sha256.h"

#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace zenith::atmosphere {
namespace {

std::string num(double v) {
  if (v == 0.0) return "0";  // also folds -0
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.11e", v);
  return buf;
}

void line(std::ostringstream& out, const std::string& key, std::span<const double> values) {
  out << key << ":";
  for (double v : values) out << ' ' << num(v);
  out << '\n';
}

void profile(std::ostringstream& out, const std::string& key, const DensityProfile& p) {
  if (p.kind() == DensityProfile::Kind::Exponential) {
    const double h = p.scale_height_m();
    line(out, key + ".exponential.scale_height_m", std::span(&h, 1));
  } else {
    line(out, key + ".table.altitude_m", p.table().knots_x());
    line(out, key + ".table.relative_density", p.table().knots_y());
  }
}

}  // namespace

std::string canonical_description(const AtmosphereModel& m) {
  std::ostringstream out;
  out << "zenith lookup tables v" << kLookupTableFormatVersion << '\n';
  line(out, "wavelengths_nm", m.wavelengths_nm);
  line(out, "ground_radius_m", std::span(&m.ground_radius_m, 1));
  line(out, "top_radius_m", std::span(&m.top_radius_m, 1));
  line(out, "ground_albedo", m.ground_albedo.values());
  line(out, "rayleigh.scattering_m1", m.rayleigh_scattering_m1.values());
  profile(out, "rayleigh.density", m.rayleigh_density);
  out << "rayleigh.phase: " << rayleigh_phase_name(m.rayleigh_phase) << '\n';
  if (m.rayleigh_phase == RayleighPhaseModel::Depolarized)
    line(out, "rayleigh.depolarization", std::span(&m.rayleigh_depolarization, 1));
  line(out, "mie.scattering_m1", m.mie_scattering_m1.values());
  line(out, "mie.extinction_m1", m.mie_extinction_m1.values());
  if (m.has_mie()) {
    profile(out, "mie.density", m.mie_density);
    out << "mie.phase: " << int(m.mie_phase.model) << '\n';
    line(out, "mie.phase.g1", m.mie_phase.g1.values());
    line(out, "mie.phase.g2", m.mie_phase.g2.values());
    line(out, "mie.phase.alpha", m.mie_phase.alpha.values());
    if (m.mie_phase.model == MiePhase::Model::Tabulated && m.mie_phase.table)
      line(out, "mie.phase.table", m.mie_phase.table->samples());
  }
  for (const Absorber& a : m.absorbers) {
    // The absorber's name is a label; only its optics shape the tables.
    line(out, "absorber.absorption_m1", a.absorption_m1.values());
    profile(out, "absorber.density", a.profile);
  }
  out << "air_mass: " << (m.air_mass.enabled() ? "pickering" : "geometric") << '\n';
  return out.str();
}

std::string lookup_table_hash(const AtmosphereModel& model) {
  const std::string text = canonical_description(model);
  return core::sha256_hex(text.data(), text.size());
}

}  // namespace zenith::atmosphere
