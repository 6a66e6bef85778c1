#include "show/recording_json.h"

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/json_reader.h"
#include "core/sha256.h"
#include "core/strings.h"
#include "core/units.h"
#include "scene/scene.h"

namespace zenith::show {
namespace {

using config::brief;
using core::cat;
using nlohmann::json;

constexpr double kMaxShowTime_s = 1e9;
constexpr double kMaxSunAngularRadius_rad = 15.0 * core::kPi / 180.0;

json vec3_json(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

/// An array of `count` numbers.
std::vector<double> numbers(JsonReader& r, const std::string& key, std::size_t count, const char* what) {
  const json& v = r.raw(key);
  if (!v.is_array() || v.size() != count)
    r.fail(key, cat("= ", brief(v), ": must be an array of ", count, " numbers ", what));
  std::vector<double> out;
  for (const json& x : v) {
    if (!x.is_number()) r.fail(key, cat("= ", brief(v), ": must be an array of ", count, " numbers ", what));
    out.push_back(x.get<double>());
  }
  return out;
}

std::uint64_t unsigned_integer(JsonReader& r, const std::string& key, std::uint64_t max) {
  const json& v = r.raw(key);
  if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<long long>() >= 0))
    r.fail(key, cat("= ", brief(v), ": must be an integer in [0, ", max, "]"));
  const std::uint64_t x = v.get<std::uint64_t>();
  if (x > max) r.fail(key, cat("= ", brief(v), ": must be an integer in [0, ", max, "]"));
  return x;
}

}  // namespace

json frame_to_json(const scene::FrameDescription& s) {
  json atmospheres = json::array();
  for (const scene::AtmosphereTableRef& ref : s.atmospheres)
    atmospheres.push_back({{"body", ref.body_name},
                           {"table_hash", core::to_hex(ref.table_hash)},
                           {"effective_from_frame", ref.effective_from_frame}});
  const glm::dquat& q = s.camera_orientation;
  json frame = {{"frame", s.frame},
                {"show_time_s", s.show_time_s},
                {"camera_position_m", vec3_json(s.camera_position_m)},
                {"camera_orientation", json::array({q.w, q.x, q.y, q.z})},
                {"exposure", s.exposure},
                {"sun_direction", vec3_json(s.sun_direction)},
                {"sun_angular_radius_rad", s.sun_angular_radius_rad},
                {"sun_irradiance_W_m2_nm", s.sun_irradiance_W_m2_nm},
                {"atmospheres", atmospheres},
                {"render_flags", s.render_flags}};
  // The operator's fade (docs/operator.md, "Fades"), only while it shows:
  // frames of the picture alone read as before fades existed.
  if (s.fade != scene::FadeState{}) frame["fade"] = {{"level", s.fade.level}, {"colour", vec3_json(s.fade.colour)}};
  // The sky by date (the night sky's own struct): only frames of a scene with a sky clock.
  if (s.sky.has_time)
    frame["sky"] = {{"utc_jd", json::array({s.sky.utc_jd1, s.sky.utc_jd2})},
                    {"star_catalogue", core::to_hex(s.sky.star_catalogue)}};
  return frame;
}

json version_to_json(const AtmosphereVersion& version) {
  return {{"body", version.body}, {"table_hash", core::to_hex(version.table_hash)}, {"parameters", version.parameters}};
}

void check_recordable(const scene::FrameDescription& s) {
  auto finite = [](const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  const glm::dquat& q = s.camera_orientation;
  if (!(std::isfinite(s.show_time_s) && s.show_time_s >= 0.0))
    throw std::invalid_argument(cat("show_time_s = ", s.show_time_s, ": must be finite and >= 0"));
  if (!finite(s.camera_position_m)) throw std::invalid_argument("camera_position_m: must be finite");
  if (!(std::abs(glm::length(q) - 1.0) <= scene::kUnitTolerance))
    throw std::invalid_argument("camera_orientation: must be a unit quaternion");
  if (!(s.exposure > 0.0 && s.exposure <= scene::kMaxExposure))
    throw std::invalid_argument(cat("exposure = ", s.exposure, ": must be in (0, 1e+06]"));
  if (!(finite(s.sun_direction) && std::abs(glm::length(s.sun_direction) - 1.0) <= scene::kUnitTolerance))
    throw std::invalid_argument("sun_direction: must be a unit vector");
  if (!(s.sun_angular_radius_rad >= 0.0 && s.sun_angular_radius_rad <= kMaxSunAngularRadius_rad))
    throw std::invalid_argument(cat("sun_angular_radius_rad = ", s.sun_angular_radius_rad, ": must be in [0, 15 deg]"));
  if (s.sun_irradiance_W_m2_nm.size() > scene::kMaxWavelengths)
    throw std::invalid_argument("sun_irradiance_W_m2_nm: too many values");
  for (double e : s.sun_irradiance_W_m2_nm)
    if (!(std::isfinite(e) && e >= 0.0)) throw std::invalid_argument("sun_irradiance_W_m2_nm: must be finite, >= 0");
  if (s.atmospheres.size() > scene::kMaxAtmospheres) throw std::invalid_argument("atmospheres: too many");
  if ((s.render_flags & ~scene::kKnownRenderFlags) != 0) throw std::invalid_argument("render_flags: unknown bits");
  if (!(s.fade.level >= 0.0 && s.fade.level <= scene::kMaxFadeLevel))
    throw std::invalid_argument(cat("fade level = ", s.fade.level, ": must be in [0, 1]"));
  for (int i = 0; i < 3; ++i)
    if (!(s.fade.colour[i] >= 0.0 && s.fade.colour[i] <= 1.0))
      throw std::invalid_argument(cat("fade colour = ", s.fade.colour[i], ": each component must be in [0, 1]"));
}

scene::FrameDescription frame_from_json(const json& frame, const scene::Scene& scene, const std::string& file,
                                        const std::string& pointer) {
  JsonReader r(frame, file, pointer);
  config::reject_unknown_keys(
      r, frame,
      {"frame", "show_time_s", "camera_position_m", "camera_orientation", "exposure", "sun_direction",
       "sun_angular_radius_rad", "sun_irradiance_W_m2_nm", "atmospheres", "render_flags", "fade", "sky"},
      "docs/shows.md");
  scene::FrameDescription s;
  s.frame = unsigned_integer(r, "frame", std::uint64_t{1} << 53);
  s.show_time_s = r.number("show_time_s", 0.0, kMaxShowTime_s, "s");
  const std::vector<double> p = numbers(r, "camera_position_m", 3, "[x, y, z] m");
  s.camera_position_m = {p[0], p[1], p[2]};
  const std::vector<double> q = numbers(r, "camera_orientation", 4, "[w, x, y, z] (a unit quaternion)");
  s.camera_orientation = glm::dquat(q[0], q[1], q[2], q[3]);
  if (!(std::abs(glm::length(s.camera_orientation) - 1.0) <= scene::kUnitTolerance))
    r.fail("camera_orientation", cat("= ", brief(r.raw("camera_orientation")),
                                     ": must be a unit quaternion (|q| - 1 within ", scene::kUnitTolerance, ")"));
  s.exposure = r.number("exposure", 0.0, scene::kMaxExposure);
  if (!(s.exposure > 0.0)) r.fail("exposure", cat("= ", brief(r.raw("exposure")), ": must be in (0, 1e+06]"));
  const std::vector<double> d = numbers(r, "sun_direction", 3, "[x, y, z] (a unit vector)");
  s.sun_direction = {d[0], d[1], d[2]};
  if (!(std::abs(glm::length(s.sun_direction) - 1.0) <= scene::kUnitTolerance))
    r.fail("sun_direction", cat("= ", brief(r.raw("sun_direction")), ": must be a unit vector"));
  s.sun_angular_radius_rad = r.number("sun_angular_radius_rad", 0.0, kMaxSunAngularRadius_rad, "rad");
  s.sun_irradiance_W_m2_nm =
      numbers(r, "sun_irradiance_W_m2_nm", scene.wavelengths_nm.size(), "(one per scene wavelength, each >= 0)");
  for (double e : s.sun_irradiance_W_m2_nm)
    if (!(e >= 0.0)) r.fail("sun_irradiance_W_m2_nm", "values must be >= 0 W m^-2 nm^-1");
  const json& atmospheres = r.raw("atmospheres");
  if (!atmospheres.is_array() || atmospheres.size() > scene::kMaxAtmospheres)
    r.fail("atmospheres", cat("= ", brief(atmospheres), ": must be an array of at most ", scene::kMaxAtmospheres,
                              " {\"body\", \"table_hash\", \"effective_from_frame\"}"));
  for (std::size_t i = 0; i < atmospheres.size(); ++i) {
    JsonReader a(atmospheres[i], file, r.key_path(cat("atmospheres/", i)));
    config::reject_unknown_keys(a, atmospheres[i], {"body", "table_hash", "effective_from_frame"}, "docs/shows.md");
    scene::AtmosphereTableRef ref;
    ref.body_name = a.string("body");
    const scene::Body* body = scene.find_body(ref.body_name);
    if (body == nullptr || !body->atmosphere)
      a.fail("body", cat("= \"", ref.body_name, "\": the scene has no body of that name with an atmosphere"));
    try {
      ref.table_hash = core::digest_from_hex(a.string("table_hash"));
    } catch (const std::invalid_argument&) {
      a.fail("table_hash", cat("= ", brief(a.raw("table_hash")), ": must be 64 hexadecimal digits"));
    }
    ref.effective_from_frame = unsigned_integer(a, "effective_from_frame", std::uint64_t{1} << 53);
    a.finish();
    s.atmospheres.push_back(std::move(ref));
  }
  s.render_flags = static_cast<std::uint32_t>(unsigned_integer(r, "render_flags", scene::kKnownRenderFlags));
  if (r.has("fade")) {
    JsonReader f(r.raw("fade"), file, r.key_path("fade"));
    config::reject_unknown_keys(f, r.raw("fade"), {"level", "colour"}, "docs/shows.md");
    s.fade.level = f.number("level", 0.0, scene::kMaxFadeLevel);
    const std::vector<double> c = numbers(f, "colour", 3, "[r, g, b], each in [0, 1]");
    for (int i = 0; i < 3; ++i)
      if (!(c[i] >= 0.0 && c[i] <= 1.0))
        f.fail("colour", cat("= ", brief(f.raw("colour")), ": each component must be in [0, 1]"));
    s.fade.colour = {c[0], c[1], c[2]};
    f.finish();
  }
  if (r.has("sky")) {
    JsonReader k(r.raw("sky"), file, r.key_path("sky"));
    config::reject_unknown_keys(k, r.raw("sky"), {"utc_jd", "star_catalogue"}, "docs/shows.md");
    const std::vector<double> jd = numbers(k, "utc_jd", 2, "[day1, day2] (a two-part UTC Julian date)");
    if (!(jd[0] + jd[1] >= 2436934.5 && jd[0] + jd[1] <= 2488069.5))
      k.fail("utc_jd",
             cat("= ", brief(k.raw("utc_jd")), ": must be a date of 1960-2100 (Julian date 2436934.5-2488069.5)"));
    s.sky.has_time = true;
    s.sky.utc_jd1 = jd[0];
    s.sky.utc_jd2 = jd[1];
    try {
      s.sky.star_catalogue = core::digest_from_hex(k.string("star_catalogue"));
    } catch (const std::invalid_argument&) {
      k.fail("star_catalogue", cat("= ", brief(k.raw("star_catalogue")), ": must be 64 hexadecimal digits"));
    }
    k.finish();
  }
  r.finish();
  return s;
}

}  // namespace zenith::show
