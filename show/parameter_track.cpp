#include "show/parameter_track.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "show/key_span.h"

namespace zenith::show {

std::int64_t quantize(double value, double step) {
  const double steps = std::round(value / step);
  if (!(std::abs(steps) < 9e15)) throw std::invalid_argument("quantize: value / step is out of range");
  return static_cast<std::int64_t>(steps);
}

double quantized_value(std::int64_t level, double step) {
  char text[40];
  std::snprintf(text, sizeof text, "%.15g", static_cast<double>(level) * step);
  return std::strtod(text, nullptr);
}

ParameterTrack::ParameterTrack(nlohmann::json::json_pointer pointer, std::optional<double> step,
                               std::vector<ParameterKey> keys)
    : pointer_(std::move(pointer)), step_(step), keys_(std::move(keys)) {
  if (keys_.empty()) throw std::invalid_argument("ParameterTrack: needs at least one key");
  if (step_ && !(std::isfinite(*step_) && *step_ > 0.0))
    throw std::invalid_argument("ParameterTrack: the step must be finite and > 0");
  std::vector<double> times, values;
  for (const ParameterKey& key : keys_) {
    if (key.value.is_number() != step_.has_value())
      throw std::invalid_argument(step_ ? "ParameterTrack: a numeric track needs numbers"
                                        : "ParameterTrack: numbers need a step");
    times.push_back(key.t_s);
    if (step_) values.push_back(key.value.get<double>());
  }
  if (step_) curve_.emplace(times, values);
  else (void)MonotoneCubic(times, std::vector<double>(times.size(), 0.0));  // checks the times
}

double ParameterTrack::raw_value(double t_s) const {
  if (!curve_) throw std::logic_error("ParameterTrack::raw_value: not a numeric track");
  return (*curve_)(t_s);
}

nlohmann::json ParameterTrack::value_at(double t_s) const {
  if (step_) {
    const double step = *step_;
    return quantized_value(quantize(raw_value(t_s), step), step);
  }
  // The latest key at or before t (the first before it).
  std::size_t k = 0;
  while (k + 1 < keys_.size() && keys_[k + 1].t_s <= t_s) ++k;
  return keys_[k].value;
}

void ParameterTrack::apply(nlohmann::json& parameters, double t_s) const {
  nlohmann::json value = value_at(t_s);
  if (!value.is_null()) {
    parameters[pointer_] = std::move(value);
    return;
  }
  if (!parameters.contains(pointer_)) return;
  nlohmann::json& parent = parameters[pointer_.parent_pointer()];
  const std::string& last = pointer_.back();
  if (parent.is_object()) parent.erase(last);
  else if (parent.is_array()) parent.erase(static_cast<std::size_t>(std::stoul(last)));
}

}  // namespace zenith::show
