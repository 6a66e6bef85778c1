#include "show/parameter_track.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/json_reader.h"
#include "core/strings.h"
#include "show/key_span.h"

namespace zenith::show {
namespace {

using core::cat;

/// An array index token of a JSON pointer: digits without a leading zero,
/// below 2^31; "-" is `size` (one past the end).
std::size_t array_index(const std::string& token, std::size_t size, const std::string& pointer) {
  if (token == "-") return size;
  const bool digits = !token.empty() && token.size() <= 10 &&
                      token.find_first_not_of("0123456789") == std::string::npos && (token == "0" || token[0] != '0');
  if (!digits || std::stoull(token) > 0x7fffffffULL)
    throw std::invalid_argument(cat(pointer, ": \"", token, "\" is not an index of an array of ", size, " elements"));
  return static_cast<std::size_t>(std::stoull(token));
}

}  // namespace

void write_parameter(nlohmann::json& parameters, const nlohmann::json::json_pointer& pointer, nlohmann::json value) {
  const std::string where = pointer.to_string();
  if (pointer.empty()) throw std::invalid_argument("the pointer \"\" names the whole parameter set, not one parameter");
  std::vector<std::string> tokens;
  for (nlohmann::json::json_pointer p = pointer; !p.empty(); p = p.parent_pointer())
    tokens.insert(tokens.begin(), p.back());
  nlohmann::json* node = &parameters;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::string& token = tokens[i];
    const bool last = i + 1 == tokens.size();
    if (node->is_null()) {
      if (value.is_null()) return;  // nothing to remove
      *node = nlohmann::json::object();
    }
    if (node->is_object()) {
      const auto it = node->find(token);
      if (last) {
        if (value.is_null()) {
          if (it != node->end()) node->erase(it);
        } else {
          (*node)[token] = std::move(value);
        }
        return;
      }
      if (it == node->end() && value.is_null()) return;
      node = &(*node)[token];
    } else if (node->is_array()) {
      const std::size_t index = array_index(token, node->size(), where);
      if (last) {
        if (index < node->size()) {
          if (value.is_null())
            node->erase(index);
          else
            (*node)[index] = std::move(value);
        } else if (index == node->size() && !value.is_null()) {
          node->push_back(std::move(value));
        } else if (!value.is_null()) {
          throw std::invalid_argument(
              cat(where, ": index ", token, " is past the end of an array of ", node->size(), " elements"));
        }
        return;
      }
      if (index >= node->size())
        throw std::invalid_argument(
            cat(where, ": index ", token, " is past the end of an array of ", node->size(), " elements"));
      node = &(*node)[index];
    } else {
      throw std::invalid_argument(cat(where, ": \"", token, "\" cannot be looked up in a ", node->type_name(),
                                      " (only objects and arrays have keys)"));
    }
  }
}

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
  if (step_)
    curve_.emplace(times, values);
  else
    (void)MonotoneCubic(times, std::vector<double>(times.size(), 0.0));  // checks the times
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
  write_parameter(parameters, pointer_, value_at(t_s));
}

}  // namespace zenith::show
