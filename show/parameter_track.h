#pragma once
// A track over one atmosphere parameter (docs/shows.md, "Atmosphere tracks").
//
// The parameter is a JSON pointer into the body's atmosphere parameter set
// (atmosphere::LoadedAtmosphere::parameters). Two kinds:
//  * numeric — every key a number, and a `step`: the monotone cubic through
//    the keys, rounded to the nearest multiple of the step. Every distinct
//    parameter set needs its own lookup tables (minutes of precompute each),
//    so the step bounds how many sets a show needs: a turbidity from 3 to 2
//    with step 0.25 makes 5 sets, however long the show;
//  * held — any other JSON values (booleans, strings, objects, null): the
//    value of the latest key at or before t, a step function. null removes
//    the key (e.g. "/ozone": null turns ozone absorption off).
// Before its first key a track holds the first key's value.
#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "show/monotone_cubic.h"

namespace zenith::show {

struct ParameterKey {
  double t_s = 0.0;
  nlohmann::json value;
};

/// The multiple of `step` nearest to `value`, as a whole number of steps.
std::int64_t quantize(double value, double step);
/// level · step, rounded to 15 significant digits so that 3 × 0.1 reads 0.3.
double quantized_value(std::int64_t level, double step);

/// Writes `value` into `parameters` at `pointer` (into an atmosphere's
/// parameter set: tracks, the operator's `set`), creating objects on the way;
/// null removes the key (nothing happens when it is absent). "-" or the size
/// of an array appends to it. Throws std::invalid_argument, naming the
/// pointer, for the root pointer, a step through a value that is neither an
/// object nor an array, and an array index that is not a number in range.
void write_parameter(nlohmann::json& parameters, const nlohmann::json::json_pointer& pointer, nlohmann::json value);

class ParameterTrack {
 public:
  /// Keys strictly increasing in t_s, at least one. A step (finite, > 0)
  /// makes a numeric track and then every value must be a number; without
  /// one no value may be a number. Throws std::invalid_argument otherwise.
  ParameterTrack(nlohmann::json::json_pointer pointer, std::optional<double> step, std::vector<ParameterKey> keys);

  const nlohmann::json::json_pointer& pointer() const { return pointer_; }
  const std::vector<ParameterKey>& keys() const { return keys_; }

  /// Numeric tracks: the interpolated value before quantization.
  double raw_value(double t_s) const;
  /// The value the parameter takes at t (quantized; null = removed).
  nlohmann::json value_at(double t_s) const;
  /// Writes value_at(t) into `parameters` at the pointer (removing the key for null).
  void apply(nlohmann::json& parameters, double t_s) const;

 private:
  nlohmann::json::json_pointer pointer_;
  std::optional<double> step_;
  std::vector<ParameterKey> keys_;
  std::optional<MonotoneCubic> curve_;
};

}  // namespace zenith::show
