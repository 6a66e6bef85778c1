#include "atmosphere/named_inputs.h"

#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace zenith::atmosphere {

LoadedAtmosphere load_atmosphere_argument(const std::string& value, const LoadOptions& options) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(value, ec) || value.find('/') != std::string::npos || value.ends_with(".json"))
    return load_atmosphere_file(value, options);
  return load_preset(value, options);
}

namespace {

// The twilight set (docs/night-sky.md, "Twilight in the tables", measured with
// bench/twilight_bench against the lit-air reference at sun 0° to −18°): the
// μs texels and the ray samples that together bring the deep-twilight zenith
// within 3 % from 0° to −18° at every wavelength. Either alone
// does not: 128 texels with 50 samples leave −3.7 % at −12° (680 nm), 64
// texels with 100 samples −3.4 %. The texels resolve J's steepening fall with
// the sun's depression (the geometric reads undershoot where ln J is concave in
// μs); the samples the band of sunlit air a few degrees above the horizon,
// hundreds of kilometres along the rays, from which all the light of the
// higher orders comes below −10°.
constexpr std::size_t kTwilightMuSFactor = 4;
constexpr int kTwilightScatteringSamples = 200;

}  // namespace

lut::TableSizes table_sizes_by_name(const std::string& name) {
  if (name == "paper") return lut::TableSizes{};
  if (name == "small") return lut::TableSizes::small();
  if (name == "twilight") {
    lut::TableSizes s;
    s.scattering_mu_s *= kTwilightMuSFactor;
    return s;
  }
  if (name == "large") return lut::TableSizes{512, 128, 128, 32, 64, 256, 64, 16};
  throw std::invalid_argument("unknown table size set '" + name + "': use paper, twilight, small or large");
}

void apply_table_set(const std::string& name, lut::PrecomputeOptions& options) {
  options.sizes = table_sizes_by_name(name);
  options.scattering_samples =
      name == "twilight" ? kTwilightScatteringSamples : lut::PrecomputeOptions{}.scattering_samples;
}

const std::vector<std::string>& table_size_names() {
  static const std::vector<std::string> names = {"paper", "twilight", "small", "large"};
  return names;
}

}  // namespace zenith::atmosphere
