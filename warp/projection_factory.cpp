#include "warp/projection_factory.h"

#include <algorithm>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "core/json_reader.h"
#include "warp/cube_face_projection.h"
#include "warp/cylindrical_projection.h"
#include "warp/equirectangular_projection.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"

namespace zenith::warp {
namespace {

using nlohmann::json;

/// The keys each type accepts ("type" included).
std::vector<std::string_view> keys_of(const std::string& type) {
  if (type == "planar")
    return {"type", "fov_deg", "left_deg", "right_deg", "down_deg", "up_deg", "yaw_deg", "pitch_deg", "roll_deg"};
  if (type == "fisheye")
    return {"type", "fov_deg", "tilt_deg", "rotation_deg", "centre_x_px", "centre_y_px", "radius_px"};
  if (type == "cylindrical")
    return {"type", "horizontal_fov_deg", "down_deg", "up_deg", "yaw_deg", "pitch_deg", "roll_deg"};
  if (type == "equirectangular")
    return {"type", "longitude_min_deg", "longitude_max_deg", "latitude_min_deg", "latitude_max_deg"};
  return {"type", "face"};  // cube
}

/// Rejects any key the type does not accept, listing those it does.
void allow_keys(const JsonReader& r, const json& spec, const std::string& type) {
  const std::vector<std::string_view> allowed = keys_of(type);
  for (const auto& [key, value] : spec.items()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::ostringstream s;
    s << "unknown key (check the spelling); allowed for type \"" << type << "\": ";
    for (std::size_t i = 0; i < allowed.size(); ++i) s << (i ? ", " : "") << allowed[i];
    s << " (see docs/projections.md)";
    r.fail(key, s.str());
  }
}

/// The number under `key` (any value: the projection checks the range), or
/// nothing when the key is absent.
std::optional<double> optional_number(JsonReader& r, const std::string& key, const char* unit) {
  if (!r.has(key)) return std::nullopt;
  const json& v = r.raw(key);
  if (!v.is_number()) r.fail(key, "= " + v.dump() + ": must be a number (" + unit + ")");
  return v.get<double>();
}

double number_or(JsonReader& r, const std::string& key, double fallback, const char* unit) {
  return optional_number(r, key, unit).value_or(fallback);
}

double required_number(JsonReader& r, const std::string& key, const char* unit) {
  if (!r.has(key)) r.fail(key, "missing required key");
  return *optional_number(r, key, unit);
}

/// Runs `make`, turning the projection's std::invalid_argument into a
/// ConfigError. Its message reads "<Class>: <name> = <value>: <range>" (or
/// "projection width_px = ..." for sizes); <name> is the JSON key, or renamed
/// by `renames` where the key differs (planar "fov_deg"). When the spec holds
/// that key the error points at it; otherwise at the spec itself.
template <typename Make>
std::unique_ptr<Projection> build(const JsonReader& r, const json& spec, Make&& make,
                                  std::initializer_list<std::pair<std::string_view, std::string_view>> renames = {}) {
  try {
    return std::forward<Make>(make)();
  } catch (const std::invalid_argument& e) {
    std::string message = e.what();
    if (message.starts_with("projection ")) {
      message.erase(0, std::string_view("projection ").size());
    } else if (const std::size_t colon = message.find(": "); colon != std::string::npos) {
      message.erase(0, colon + 2);  // "PlanarProjection: "
    }
    const std::size_t space = message.find(' ');
    std::string name = message.substr(0, space);
    for (const auto& [from, to] : renames)
      if (name == from) name = std::string(to);
    const std::string rest = space == std::string::npos ? std::string() : message.substr(space + 1);
    if (spec.contains(name) && rest.starts_with("= ")) {
      r.fail(name, rest);
    }
    if (name == "width_px" || name == "height_px") r.fail("", "image " + message);
    r.fail("", message);
  }
}

std::unique_ptr<Projection> make_planar(JsonReader& r, const json& spec, int width_px, int height_px) {
  const bool edges = r.has("left_deg") || r.has("right_deg") || r.has("down_deg") || r.has("up_deg");
  if (r.has("fov_deg") == edges)
    r.fail("", edges ? "give either fov_deg or left_deg, right_deg, down_deg and up_deg, not both"
                     : "give either fov_deg (symmetric) or left_deg, right_deg, down_deg and up_deg (asymmetric)");
  const double yaw = number_or(r, "yaw_deg", 0.0, "degrees");
  const double pitch = number_or(r, "pitch_deg", 0.0, "degrees");
  const double roll = number_or(r, "roll_deg", 0.0, "degrees");
  if (!edges) {
    const double fov = required_number(r, "fov_deg", "degrees");
    return build(r, spec,
                 [&] {
                   PlanarFrustum f = PlanarProjection::symmetric(width_px, height_px, fov).frustum();
                   f.yaw_deg = yaw;
                   f.pitch_deg = pitch;
                   f.roll_deg = roll;
                   return std::make_unique<PlanarProjection>(width_px, height_px, f);
                 },
                 {{"horizontal_fov_deg", "fov_deg"}});
  }
  PlanarFrustum f{};
  f.left_deg = required_number(r, "left_deg", "degrees");
  f.right_deg = required_number(r, "right_deg", "degrees");
  f.down_deg = required_number(r, "down_deg", "degrees");
  f.up_deg = required_number(r, "up_deg", "degrees");
  f.yaw_deg = yaw;
  f.pitch_deg = pitch;
  f.roll_deg = roll;
  return build(r, spec, [&] { return std::make_unique<PlanarProjection>(width_px, height_px, f); });
}

std::unique_ptr<Projection> make_fisheye(JsonReader& r, const json& spec, int width_px, int height_px) {
  FisheyeParameters p;
  p.fov_deg = number_or(r, "fov_deg", p.fov_deg, "degrees");
  p.tilt_deg = number_or(r, "tilt_deg", p.tilt_deg, "degrees");
  p.rotation_deg = number_or(r, "rotation_deg", p.rotation_deg, "degrees");
  p.centre_x_px = optional_number(r, "centre_x_px", "px");
  p.centre_y_px = optional_number(r, "centre_y_px", "px");
  p.radius_px = optional_number(r, "radius_px", "px");
  return build(r, spec, [&] { return std::make_unique<FisheyeProjection>(width_px, height_px, p); });
}

std::unique_ptr<Projection> make_cylindrical(JsonReader& r, const json& spec, int width_px, int height_px) {
  CylindricalParameters p;
  p.horizontal_fov_deg = number_or(r, "horizontal_fov_deg", p.horizontal_fov_deg, "degrees");
  p.down_deg = number_or(r, "down_deg", p.down_deg, "degrees");
  p.up_deg = number_or(r, "up_deg", p.up_deg, "degrees");
  p.yaw_deg = number_or(r, "yaw_deg", p.yaw_deg, "degrees");
  p.pitch_deg = number_or(r, "pitch_deg", p.pitch_deg, "degrees");
  p.roll_deg = number_or(r, "roll_deg", p.roll_deg, "degrees");
  return build(r, spec, [&] { return std::make_unique<CylindricalProjection>(width_px, height_px, p); });
}

std::unique_ptr<Projection> make_equirectangular(JsonReader& r, const json& spec, int width_px, int height_px) {
  EquirectangularParameters p;
  p.longitude_min_deg = number_or(r, "longitude_min_deg", p.longitude_min_deg, "degrees");
  p.longitude_max_deg = number_or(r, "longitude_max_deg", p.longitude_max_deg, "degrees");
  p.latitude_min_deg = number_or(r, "latitude_min_deg", p.latitude_min_deg, "degrees");
  p.latitude_max_deg = number_or(r, "latitude_max_deg", p.latitude_max_deg, "degrees");
  return build(r, spec, [&] { return std::make_unique<EquirectangularProjection>(width_px, height_px, p); });
}

std::unique_ptr<Projection> make_cube(JsonReader& r, const json& spec, int width_px, int height_px) {
  const std::string name = r.string("face", {"+x", "-x", "+y", "-y", "+z", "-z"});
  if (width_px != height_px) {
    std::ostringstream s;
    s << "a cube face is square: the image is " << width_px << "×" << height_px << " px";
    r.fail("", s.str());
  }
  const CubeFace face = *cube_face_from_name(name);
  return build(r, spec, [&] { return std::make_unique<CubeFaceProjection>(width_px, face); });
}

}  // namespace

std::unique_ptr<Projection> make_projection(const nlohmann::json& spec, int width_px, int height_px,
                                            const std::string& source, const std::string& pointer) {
  JsonReader r(spec, source, pointer);  // throws unless spec is an object
  const std::string type = r.string("type", {"planar", "fisheye", "cylindrical", "equirectangular", "cube"});
  allow_keys(r, spec, type);
  std::unique_ptr<Projection> projection;
  if (type == "planar")
    projection = make_planar(r, spec, width_px, height_px);
  else if (type == "fisheye")
    projection = make_fisheye(r, spec, width_px, height_px);
  else if (type == "cylindrical")
    projection = make_cylindrical(r, spec, width_px, height_px);
  else if (type == "equirectangular")
    projection = make_equirectangular(r, spec, width_px, height_px);
  else
    projection = make_cube(r, spec, width_px, height_px);
  r.finish();  // every allowed key was read above; kept as the safety net
  return projection;
}

}  // namespace zenith::warp
