#include "validate/random_atmosphere.h"

#include <cmath>
#include <string>

#include "atmosphere/reference/random.h"
#include "core/json_reader.h"
#include "core/strings.h"

namespace zenith::validate {
namespace {

using atmosphere::reference::Pcg32;
using nlohmann::json;

class Draw {
 public:
  Draw(std::uint64_t seed, std::uint64_t index) : rng_(Pcg32::for_sample(seed, 0xA7305, index)) {}
  double uniform(double lo, double hi) { return lo + rng_.uniform() * (hi - lo); }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  bool chance(double p) { return rng_.uniform() < p; }
  /// One number, or one per working wavelength (half the time each).
  json spectral(double lo, double hi, bool log) {
    auto one = [&] { return log ? log_uniform(lo, hi) : uniform(lo, hi); };
    if (chance(0.5)) return one();
    return json{{"680", one()}, {"550", one()}, {"440", one()}};
  }

 private:
  Pcg32 rng_;
};

}  // namespace

json random_atmosphere_parameters(std::uint64_t seed, std::uint64_t index) {
  Draw d(seed, index);
  json j = {{"zenith_atmosphere", 1},
            {"name", core::cat("random-", seed, "-", index)},
            {"mode", "standard"},
            {"wavelengths_nm", {680, 550, 440}},
            {"air_mass", "geometric"}};
  j["planet"] = {{"radius_m", d.log_uniform(1e4, 1e9)},
                 {"atmosphere_height_m", d.log_uniform(10.0, 1e7)},
                 {"ground_albedo", d.spectral(0.0, 1.0, false)}};
  json rayleigh = {{"scattering_m1", d.spectral(1e-9, 1e-2, true)}, {"scale_height_m", d.log_uniform(1.0, 1e6)}};
  const double phase = d.uniform(0.0, 3.0);
  rayleigh["phase"] = phase < 1.0 ? "penndorf" : phase < 2.0 ? "classic" : "depolarized";
  if (phase >= 2.0) rayleigh["depolarization"] = d.uniform(0.0, 0.5);
  j["rayleigh"] = rayleigh;
  if (d.chance(0.7)) {
    const double extinction = d.log_uniform(1e-9, 1e-2);
    json mie = {{"extinction_m1", extinction},
                {"scattering_m1", extinction * d.uniform(0.0, 1.0)},
                {"scale_height_m", d.log_uniform(1.0, 1e6)}};
    const double model = d.uniform(0.0, 3.0);
    if (model < 1.0)
      mie["phase"] = {{"model", "henyey_greenstein"}, {"g", d.spectral(-0.999, 0.999, false)}};
    else if (model < 2.0)
      mie["phase"] = {{"model", "cornette_shanks"}, {"g", d.spectral(-0.999, 0.999, false)}};
    else
      mie["phase"] = {{"model", "double_henyey_greenstein"},
                      {"g1", d.spectral(0.0, 0.999, false)},
                      {"g2", d.spectral(-0.999, 0.0, false)},
                      {"alpha", d.spectral(0.0, 1.0, false)}};
    j["mie"] = mie;
  }
  if (d.chance(0.3))
    j["absorbers"] =
        json::array({{{"name", "random absorber"},
                      {"absorption_m1", d.spectral(1e-9, 1e-3, true)},
                      {"profile", {{"type", "exponential"}, {"scale_height_m", d.log_uniform(1.0, 1e6)}}}}});
  return j;
}

}  // namespace zenith::validate
