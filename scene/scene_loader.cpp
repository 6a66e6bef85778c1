#include "scene/scene_loader.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <string_view>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vector_relational.hpp>

#include "atmosphere/photometry.h"
#include "atmosphere/spectrum.h"
#include "core/json_reader.h"
#include "core/strings.h"
#include "core/units.h"
#include "scene/albedo_map.h"
#include "scene/local_horizon.h"
#include "scene/sun_disc.h"

namespace zenith::scene {
namespace {

using config::brief;
using core::cat;

using glm::dvec3;
using nlohmann::json;
namespace fs = std::filesystem;

constexpr int kFormatVersion = 1;
using core::kDeg;
using core::kPi;

/// Allowed ranges, in one place (docs/scenes.md lists them).
struct Range {
  double lo, hi;
  const char* unit;
};
// The working wavelengths are limited to the tabulated solar spectrum (Kurucz,
// 360–830 nm) — the scene's irradiance comes from it — which also covers the
// ozone cross sections; atmospheres alone accept [200, 2500] nm.
constexpr Range kWavelength{360.0, 830.0, "nm"};
constexpr int kMaxWavelengths = 64;
constexpr Range kRadius{1.0, 1e9, "m"};
constexpr double kMaxCoordinate_m = 1e14;  // ~670 AU
constexpr double kMaxAtmosphereRadiusMismatch_m = 1.0;
constexpr int kMaxAtmospheres = 8;
constexpr Range kAlbedo{0.0, 1.0, ""};
constexpr Range kLatitude{-90.0, 90.0, "deg"};
constexpr Range kLongitude{-360.0, 360.0, "deg"};
constexpr Range kAzimuth{-360.0, 360.0, "deg"};
constexpr Range kElevation{-90.0, 90.0, "deg"};
constexpr Range kSiteLongitude{-180.0, 360.0, "deg"};
constexpr Range kSiteAltitude{-500.0, 10000.0, "m"};
constexpr Range kRoll{-360.0, 360.0, "deg"};
constexpr Range kRotation{-360.0, 360.0, "deg"};
constexpr Range kAltitude{0.1, 40.0 * kAstronomicalUnit_m, "m"};
constexpr double kMinCameraClearance_m = 0.1;
constexpr Range kSunDistance{0.02, 1000.0, "AU"};
constexpr double kMaxSunAngularDiameter_deg = 30.0;
constexpr Range kIrradianceScale{0.0, 1e6, ""};
constexpr Range kIrradiance{0.0, 1e4, "W m^-2 nm^-1"};
constexpr double kDefaultExposure = 10.0;
constexpr int kMaxMapWidth_px = 16384, kMaxMapHeight_px = 8192;
/// Two directions closer than this (radians) count as parallel.
constexpr double kParallel_rad = 1e-6;

void allow_keys(const JsonReader& r, const json& object, std::initializer_list<std::string_view> allowed) {
  config::reject_unknown_keys(r, object, allowed, "docs/scenes.md");
}

/// The object under `key`, with its keys checked.
JsonReader open_object(JsonReader& parent, const std::string& key, std::initializer_list<std::string_view> allowed) {
  const json& v = parent.raw(key);
  if (!v.is_object()) parent.fail(key, cat("must be an object, got ", brief(v)));
  JsonReader r(v, parent.file(), parent.key_path(key));
  allow_keys(r, v, allowed);
  return r;
}

/// Exactly one of `keys` is present; returns its index.
std::size_t exactly_one(const JsonReader& r, std::initializer_list<const char*> keys) {
  std::size_t found = keys.size(), count = 0, i = 0;
  for (const char* k : keys) {
    if (r.has(k)) {
      found = i;
      ++count;
    }
    ++i;
  }
  if (count != 1) {
    std::ostringstream s;
    s << "give exactly one of ";
    i = 0;
    for (const char* k : keys) s << (i++ ? ", " : "") << '"' << k << '"';
    s << (count == 0 ? " (none given)" : " (several given)");
    r.fail("", s.str());
  }
  return found;
}

double number(JsonReader& r, const std::string& key, const Range& range) {
  return r.number(key, range.lo, range.hi, range.unit);
}

double number_or(JsonReader& r, const std::string& key, double fallback, const Range& range) {
  return r.number_or(key, fallback, range.lo, range.hi, range.unit);
}

/// A finite number in (0, hi].
double positive(JsonReader& r, const std::string& key, double hi, const std::string& unit) {
  const json& v = r.raw(key);
  const double x = v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
  if (!(std::isfinite(x) && x > 0.0 && x <= hi)) {
    std::ostringstream s;
    s << "= " << brief(v) << ": must be " << (v.is_number() ? "" : "a number ") << "in (0, " << hi << "]"
      << (unit.empty() ? "" : " ") << unit;
    r.fail(key, s.str());
  }
  return x;
}

/// An array of 3 finite numbers with |component| ≤ max_abs.
dvec3 vec3(JsonReader& r, const std::string& key, double max_abs, const std::string& unit) {
  const json& v = r.raw(key);
  auto fail = [&] {
    std::ostringstream s;
    s << "= " << brief(v) << ": must be an array of 3 numbers [x, y, z], each in [" << -max_abs << ", " << max_abs
      << "]" << (unit.empty() ? "" : " ") << unit;
    r.fail(key, s.str());
  };
  if (!v.is_array() || v.size() != 3) fail();
  dvec3 out;
  for (int i = 0; i < 3; ++i) {
    const json& x = v[std::size_t(i)];
    if (!x.is_number() || !std::isfinite(x.get<double>()) || std::abs(x.get<double>()) > max_abs) fail();
    out[i] = x.get<double>();
  }
  return out;
}

/// A non-zero vector, returned normalized (scaled first so tiny vectors do not underflow).
dvec3 direction(JsonReader& r, const std::string& key) {
  const dvec3 v = vec3(r, key, kMaxCoordinate_m, "");
  const double scale = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(scale > 0.0)) r.fail(key, cat("= ", brief(r.raw(key)), ": must be a non-zero vector (a direction)"));
  return glm::normalize(v / scale);
}

dvec3 position(JsonReader& r, const std::string& key) { return vec3(r, key, kMaxCoordinate_m, "m"); }

double angle_between(const dvec3& a, const dvec3& b) {
  // atan2 of |a × b| and a · b: accurate near 0 and π, unlike acos.
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

/// The rotation taking the frame's axes (x, y, z) to the given orthonormal
/// right-handed world vectors.
glm::dquat rotation_from_axes(const dvec3& x, const dvec3& y, const dvec3& z) {
  return glm::normalize(glm::quat_cast(glm::dmat3(x, y, z)));
}

/// Where the scene file is, for relative paths.
struct Context {
  std::string file;
  fs::path base_dir;
  std::vector<double> wavelengths_nm;
};

// ------------------------------------------------------------------ wavelengths

std::vector<double> read_wavelengths(JsonReader& root) {
  if (!root.has("wavelengths_nm")) return atmosphere::kDefaultWavelengths_nm;
  const json& v = root.raw("wavelengths_nm");
  if (!v.is_array() || v.empty() || v.size() > std::size_t(kMaxWavelengths))
    root.fail("wavelengths_nm", cat("= ", brief(v), ": must be an array of 1 to ", kMaxWavelengths, " wavelengths in [",
                                    kWavelength.lo, ", ", kWavelength.hi, "] nm"));
  std::vector<double> wl;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const json& x = v[i];
    const std::string key = cat("wavelengths_nm/", i);
    if (!x.is_number() || !(x.get<double>() >= kWavelength.lo && x.get<double>() <= kWavelength.hi))
      root.fail(key,
                cat("= ", brief(x), ": ", JsonReader::range_text(kWavelength.lo, kWavelength.hi, kWavelength.unit)));
    wl.push_back(x.get<double>());
  }
  // Strictly monotonic, either way (the default 680, 550, 440 decreases): a
  // wavelength list is an ordered set of bands for colour mapping and output.
  bool increasing = true, decreasing = true;
  for (std::size_t i = 1; i < wl.size(); ++i) {
    increasing = increasing && wl[i] > wl[i - 1];
    decreasing = decreasing && wl[i] < wl[i - 1];
  }
  if (!increasing && !decreasing)
    root.fail("wavelengths_nm", cat("= ", brief(v), ": must be strictly increasing or strictly decreasing"));
  return wl;
}

// ------------------------------------------------------------------ bodies

AlbedoSource read_albedo(JsonReader& body, const Context& ctx) {
  AlbedoSource a;
  if (!body.has("albedo")) return a;  // the default grey of scene.h
  const json& v = body.raw("albedo");
  if (v.is_number()) {
    a.colour_linear_rgb = dvec3(number(body, "albedo", kAlbedo));
    return a;
  }
  if (v.is_array()) {
    const dvec3 c = vec3(body, "albedo", 1.0, "");
    if (glm::any(glm::lessThan(c, dvec3(0.0))))
      body.fail("albedo", cat("= ", brief(v), ": must be a linear [r, g, b] reflectance, each in [0, 1]"));
    a.colour_linear_rgb = c;
    return a;
  }
  if (!v.is_object())
    body.fail("albedo", cat("= ", brief(v),
                            ": must be a reflectance in [0, 1], a linear [r, g, b], {\"image\": path} or "
                            "{\"procedural\": generator, ...}"));
  JsonReader r = open_object(body, "albedo", {"image", "procedural", "seed", "width_px", "height_px"});
  if (exactly_one(r, {"image", "procedural"}) == 0) {
    allow_keys(r, v, {"image"});
    a.kind = AlbedoSource::Kind::image;
    a.image_path = r.existing_file("image", ctx.base_dir);
  } else {
    a.kind = AlbedoSource::Kind::procedural;
    a.procedural = r.string("procedural", albedo_generators());
    if (r.has("seed")) {
      const json& s = r.raw("seed");
      if (!s.is_number_unsigned() || s.get<unsigned long long>() > 0xffffffffull)
        r.fail("seed", cat("= ", brief(s), ": must be an integer in [0, 4294967295]"));
      a.seed = std::uint32_t(s.get<unsigned long long>());
    }
    if (r.has("width_px")) a.width_px = r.integer("width_px", 2, kMaxMapWidth_px);
    if (r.has("height_px")) a.height_px = r.integer("height_px", 2, kMaxMapHeight_px);
  }
  r.finish();
  return a;
}

/// Re-raises an error from an inline atmosphere under the scene's file, with
/// the key prefixed by the pointer of the inline object.
[[noreturn]] void rethrow_inline(const ConfigError& e, const std::string& file, const std::string& prefix) {
  const std::string what = e.what();
  const std::string head = cat(e.file(), ": ", e.key().empty() ? std::string("(top level)") : e.key());
  std::string rest = what.starts_with(head) ? what.substr(head.size()) : cat(": ", what);
  if (rest.starts_with(": "))
    rest = rest.substr(2);
  else if (rest.starts_with(" "))
    rest = rest.substr(1);
  throw ConfigError(file, prefix + e.key(), rest);
}

std::optional<BodyAtmosphere> read_atmosphere(JsonReader& body, const Context& ctx) {
  if (!body.has("atmosphere")) return std::nullopt;
  const atmosphere::LoadOptions options{ctx.wavelengths_nm};
  const std::vector<std::string> presets = atmosphere::preset_names();
  BodyAtmosphere out;
  const json& v = body.raw("atmosphere");
  if (v.is_string()) {
    const std::string name = body.string("atmosphere", presets);
    out.source = cat("preset:", name);
    out.loaded = atmosphere::load_preset(name, options);
    return out;
  }
  if (!v.is_object())
    body.fail("atmosphere", cat("= ", brief(v),
                                ": must be a preset name, {\"preset\": name}, {\"file\": path} or "
                                "{\"parameters\": {...}}"));
  JsonReader r = open_object(body, "atmosphere", {"preset", "file", "parameters"});
  switch (exactly_one(r, {"preset", "file", "parameters"})) {
    case 0: {
      const std::string name = r.string("preset", presets);
      out.source = cat("preset:", name);
      out.loaded = atmosphere::load_preset(name, options);
      break;
    }
    case 1: {
      const fs::path path = r.existing_file("file", ctx.base_dir);
      out.source = path.string();
      try {
        out.loaded = atmosphere::load_atmosphere_file(path.string(), options);
      } catch (const ConfigError& e) {
        r.fail("file", cat("invalid atmosphere file: ", e.what()));
      }
      break;
    }
    default: {
      const json& parameters = r.raw("parameters");
      if (!parameters.is_object()) r.fail("parameters", cat("must be an object, got ", brief(parameters)));
      const std::string prefix = r.key_path("parameters");
      out.source = "inline";
      try {
        out.loaded = atmosphere::resolve_atmosphere(parameters, cat(ctx.file, "#", prefix), options);
      } catch (const ConfigError& e) {
        rethrow_inline(e, ctx.file, prefix);
      }
      break;
    }
  }
  r.finish();
  return out;
}

glm::dquat read_orientation(JsonReader& body) {
  if (!body.has("orientation")) return {1.0, 0.0, 0.0, 0.0};
  JsonReader r = open_object(body, "orientation", {"axis", "angle_deg", "north_pole", "prime_meridian"});
  glm::dquat q;
  if (r.has("axis") || r.has("angle_deg")) {
    if (r.has("north_pole") || r.has("prime_meridian"))
      r.fail("", "give either {\"axis\", \"angle_deg\"} or {\"north_pole\", \"prime_meridian\"}, not both");
    // A rotation by angle_deg about axis (right-handed), body frame → world.
    const dvec3 axis = direction(r, "axis");
    q = glm::angleAxis(number(r, "angle_deg", kRotation) * kDeg, axis);
  } else if (r.has("north_pole") || r.has("prime_meridian")) {
    // The body's +z (north pole) and the direction of latitude 0, longitude 0
    // (+x) in the world; the latter is made perpendicular to the pole.
    const dvec3 z = direction(r, "north_pole");
    const dvec3 meridian = direction(r, "prime_meridian");
    if (angle_between(z, meridian) < kParallel_rad || angle_between(z, meridian) > kPi - kParallel_rad)
      r.fail("prime_meridian", cat("= ", brief(r.raw("prime_meridian")), ": must not be parallel to north_pole"));
    const dvec3 x = glm::normalize(meridian - glm::dot(meridian, z) * z);
    q = rotation_from_axes(x, glm::cross(z, x), z);
  } else {
    r.fail(
        "",
        "give {\"axis\": [x, y, z], \"angle_deg\": a} or {\"north_pole\": [x, y, z], \"prime_meridian\": [x, y, z]}");
  }
  r.finish();
  return q;
}

Body read_body(const json& v, std::size_t index, const Context& ctx) {
  JsonReader r(v, ctx.file, cat("/bodies/", index));
  allow_keys(r, v, {"name", "radius_m", "position_m", "orientation", "albedo", "atmosphere"});
  Body b;
  b.name = r.string("name");
  if (b.name.empty()) r.fail("name", "= \"\": must not be empty");
  b.atmosphere = read_atmosphere(r, ctx);
  if (r.has("radius_m")) {
    b.radius_m = number(r, "radius_m", kRadius);
    if (b.atmosphere) {
      const double ground = b.atmosphere->loaded.model.ground_radius_m;
      if (std::abs(b.radius_m - ground) > kMaxAtmosphereRadiusMismatch_m)
        r.fail("radius_m", cat("= ", brief(r.raw("radius_m")), ": differs from the ground radius of its atmosphere (",
                               b.atmosphere->source, ": ", ground, " m) by ", std::abs(b.radius_m - ground),
                               " m; must agree within 1 m (or leave radius_m out)"));
    }
  } else if (b.atmosphere) {
    b.radius_m = b.atmosphere->loaded.model.ground_radius_m;
  } else {
    r.fail("radius_m", "missing required key (it may be left out only when the body has an atmosphere)");
  }
  b.position_m = r.has("position_m") ? position(r, "position_m") : dvec3(0.0);
  b.orientation = read_orientation(r);
  b.albedo = read_albedo(r, ctx);
  r.finish();
  return b;
}

std::vector<Body> read_bodies(JsonReader& root, const Context& ctx) {
  const json& list = root.raw("bodies");
  if (!list.is_array() || list.empty() || list.size() > kMaxBodies)
    root.fail("bodies", cat("= ", brief(list), ": must be an array of 1 to ", kMaxBodies, " body objects"));
  std::vector<Body> bodies;
  for (std::size_t i = 0; i < list.size(); ++i) {
    Body b = read_body(list[i], i, ctx);
    for (std::size_t j = 0; j < bodies.size(); ++j)
      if (bodies[j].name == b.name)
        throw ConfigError(ctx.file, cat("/bodies/", i, "/name"),
                          cat("= \"", b.name, "\": duplicate body name (also /bodies/", j, "/name)"));
    bodies.push_back(std::move(b));
  }
  int atmospheres = 0;
  for (const Body& b : bodies) atmospheres += b.atmosphere ? 1 : 0;
  if (atmospheres > kMaxAtmospheres)
    root.fail("bodies", cat(atmospheres, " bodies have an atmosphere; at most ", kMaxAtmospheres, " may"));
  // Solid spheres must not intersect (atmospheres may overlap other bodies).
  for (std::size_t i = 0; i < bodies.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const double distance = glm::length(bodies[i].position_m - bodies[j].position_m);
      const double sum = bodies[i].radius_m + bodies[j].radius_m;
      if (distance <= sum)
        throw ConfigError(
            ctx.file, cat("/bodies/", i),
            cat("body \"", bodies[i].name, "\" intersects body \"", bodies[j].name, "\" (/bodies/", j,
                "): their centres are ", distance, " m apart, not more than the sum of their radii ", sum, " m"));
    }
  return bodies;
}

// ------------------------------------------------------------------ camera and the local horizon

/// Camera frame (+x right, +y up, −z forward) → world, from a forward and an up
/// that are not parallel (up is made perpendicular to forward).
glm::dquat camera_rotation(const dvec3& forward, const dvec3& up) {
  const dvec3 right = glm::normalize(glm::cross(forward, up));
  const dvec3 true_up = glm::cross(right, forward);
  return rotation_from_axes(right, true_up, -forward);
}

void allow_camera_keys(const JsonReader& r, const json& camera) {
  allow_keys(r, camera, {"position_m", "surface", "look_at", "look", "forward", "up", "exposure"});
}

/// Reads a camera object (its keys already checked by allow_camera_keys).
CameraPlacement read_camera(JsonReader& r, const std::vector<Body>& bodies, const Context& ctx) {
  CameraPlacement out;
  Camera& cam = out.camera;

  // Position, and the body the camera stands on or is above.
  std::size_t reference = 0;
  std::string position_key;
  if (exactly_one(r, {"position_m", "surface"}) == 0) {
    position_key = "position_m";
    cam.position_m = position(r, "position_m");
    reference = nearest_body(bodies, cam.position_m);
  } else {
    position_key = "surface";
    JsonReader s = open_object(r, "surface", {"body", "latitude_deg", "longitude_deg", "altitude_m"});
    std::vector<std::string> names;
    for (const Body& b : bodies) names.push_back(b.name);
    const std::string name = s.string("body", names);
    reference = std::size_t(std::find(names.begin(), names.end(), name) - names.begin());
    const Body& b = bodies[reference];
    const double lat = number(s, "latitude_deg", kLatitude) * kDeg;
    const double lon = number(s, "longitude_deg", kLongitude) * kDeg;
    const double altitude = number(s, "altitude_m", kAltitude);
    // p = c + q · (R + h) (cos φ cos λ, cos φ sin λ, sin φ)
    cam.position_m =
        b.position_m + b.orientation * direction_from_latitude_longitude(lat, lon) * (b.radius_m + altitude);
    out.surface = CameraPlacement::Surface{lat, lon, altitude};
    s.finish();
  }
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const double altitude = glm::length(cam.position_m - bodies[i].position_m) - bodies[i].radius_m;
    if (i == reference && position_key == "surface") continue;  // altitude_m is range-checked
    if (altitude < kMinCameraClearance_m)
      throw ConfigError(
          ctx.file, r.key_path(position_key),
          cat("the camera is ",
              altitude < 0.0
                  ? cat("inside body \"", bodies[i].name, "\" (/bodies/", i, "), ", -altitude, " m below its surface")
                  : cat("only ", altitude, " m above body \"", bodies[i].name, "\" (/bodies/", i, ")"),
              "; it must be at least ", kMinCameraClearance_m, " m above every body's surface"));
  }
  out.reference_body = reference;
  const LocalHorizon h = local_horizon_at(cam.position_m, bodies[reference]);

  // Orientation.
  if (exactly_one(r, {"look_at", "look", "forward"}) == 1) {
    if (r.has("up"))
      r.fail("up", "is not used with \"look\" (its up is the zenith tilted by the elevation; use roll_deg)");
    JsonReader l = open_object(r, "look", {"azimuth_deg", "elevation_deg", "roll_deg"});
    const double azimuth = number(l, "azimuth_deg", kAzimuth) * kDeg;
    const double elevation = number(l, "elevation_deg", kElevation) * kDeg;
    const double roll = number_or(l, "roll_deg", 0.0, kRoll) * kDeg;
    l.finish();
    const dvec3 forward = h.direction(azimuth, elevation);
    // Up: the zenith tilted back by the elevation (the horizon stays level);
    // then rolled about forward, positive tilting up toward the right.
    const dvec3 up = h.direction(azimuth, elevation + 0.5 * kPi);
    const dvec3 right = glm::cross(forward, up);
    cam.orientation = camera_rotation(forward, std::cos(roll) * up + std::sin(roll) * right);
  } else {
    dvec3 forward;
    if (r.has("look_at")) {
      const dvec3 target = position(r, "look_at");
      const dvec3 d = target - cam.position_m;
      if (!(glm::length(d) > 1e-9 * std::max(1.0, glm::length(cam.position_m))))
        r.fail("look_at", cat("= ", brief(r.raw("look_at")), ": must differ from the camera position"));
      forward = glm::normalize(d);
    } else {
      forward = direction(r, "forward");
    }
    dvec3 up;
    if (r.has("up")) {
      up = direction(r, "up");
      const double a = angle_between(forward, up);
      if (a < kParallel_rad || a > kPi - kParallel_rad)
        r.fail("up", cat("= ", brief(r.raw("up")), ": must not be parallel to the viewing direction"));
    } else {
      // Default up: the local zenith; looking (nearly) straight up or down, the
      // reference body's north pole; failing that, the horizon's north.
      const dvec3 pole = bodies[reference].orientation * dvec3(0, 0, 1);
      up = h.up;
      if (angle_between(forward, up) < 1e-3 || angle_between(forward, up) > kPi - 1e-3) up = pole;
      if (angle_between(forward, up) < 1e-3 || angle_between(forward, up) > kPi - 1e-3) up = h.north;
    }
    cam.orientation = camera_rotation(forward, up);
  }
  cam.exposure = r.has("exposure") ? positive(r, "exposure", kMaxExposure, "") : kDefaultExposure;
  r.finish();
  return out;
}

// ------------------------------------------------------------------ sun

std::vector<double> read_irradiance(JsonReader& r, double distance_au, const Context& ctx) {
  const std::vector<double>& wl = ctx.wavelengths_nm;
  std::vector<double> kurucz(wl.size());
  // The Kurucz spectrum is at 1 AU; irradiance falls as the inverse square of the distance.
  for (std::size_t i = 0; i < wl.size(); ++i)
    kurucz[i] = atmosphere::solar_irradiance_W_m2_nm(wl[i]) / (distance_au * distance_au);
  if (!r.has("irradiance")) return kurucz;
  const json& v = r.raw("irradiance");
  if (v.is_string()) {
    r.string("irradiance", {"kurucz"});
    return kurucz;
  }
  if (v.is_number()) {
    const double scale = number(r, "irradiance", kIrradianceScale);
    for (double& e : kurucz) e *= scale;
    return kurucz;
  }
  if (!v.is_object() || v.empty())
    r.fail("irradiance", cat("= ", brief(v),
                             ": must be \"kurucz\", a scale factor on it in [0, 1e+06], or an object "
                             "{\"<wavelength nm>\": W m^-2 nm^-1, ...}"));
  // Samples at wavelengths, interpolated linearly; not scaled by the distance.
  std::vector<std::pair<double, double>> samples;
  for (const auto& [text, x] : v.items()) {
    const double nm = config::wavelength_key(r, "irradiance", text);
    if (!x.is_number() || !(x.get<double>() >= kIrradiance.lo && x.get<double>() <= kIrradiance.hi))
      r.fail(cat("irradiance/", text),
             cat("= ", brief(x), ": ", JsonReader::range_text(kIrradiance.lo, kIrradiance.hi, kIrradiance.unit)));
    for (const auto& s : samples)
      if (s.first == nm) r.fail("irradiance", cat("wavelength ", nm, " nm listed twice"));
    samples.emplace_back(nm, x.get<double>());
  }
  const atmosphere::SpectralTable table(samples);
  std::vector<double> out(wl.size());
  for (std::size_t i = 0; i < wl.size(); ++i) {
    if (!table.is_constant() && !table.covers(wl[i]))
      r.fail("irradiance", cat("is sampled from ", table.samples().front().first, " to ", table.samples().back().first,
                               " nm; it must cover every working wavelength (", wl[i], " nm is outside)"));
    out[i] = table(wl[i]);
  }
  return out;
}

void allow_sun_keys(const JsonReader& r, const json& sun) {
  allow_keys(r, sun, {"direction", "position_m", "sky", "angular_diameter_deg", "distance_au", "irradiance"});
}

/// The object under `key` of `parent` (not yet checked for unknown keys).
JsonReader open_unchecked(JsonReader& parent, const std::string& key) {
  const json& v = parent.raw(key);
  if (!v.is_object()) parent.fail(key, cat("must be an object, got ", brief(v)));
  return JsonReader(v, parent.file(), parent.key_path(key));
}

/// Reads a sun object (its keys already checked by allow_sun_keys); "sky" is in
/// the local horizon of `camera`. With `ephemeris` (the scene's "time" and
/// "site") the direction and distance are the ephemeris', and none may be given.
Sun read_sun(JsonReader& r, const std::vector<Body>& bodies, const CameraPlacement& placement, const Context& ctx,
             const std::optional<EphemerisSun>& ephemeris = std::nullopt) {
  const Camera& camera = placement.camera;
  const LocalHorizon horizon = local_horizon_at(camera.position_m, bodies.at(placement.reference_body));
  Sun sun;
  double distance_au = 1.0;
  if (ephemeris) {
    for (const char* key : {"direction", "position_m", "sky", "distance_au"})
      if (r.has(key))
        r.fail(key, "is not used: the scene's \"time\" and \"site\" place the sun (remove them to set it by hand)");
  }
  switch (ephemeris ? 3 : exactly_one(r, {"direction", "position_m", "sky"})) {
    case 3:
      sun.direction = ephemeris->direction;
      distance_au = ephemeris->distance_au;
      break;
    case 0:
      sun.direction = direction(r, "direction");
      distance_au = number_or(r, "distance_au", 1.0, kSunDistance);
      break;
    case 1: {
      // A point in the world: the direction and the distance are the camera's.
      if (r.has("distance_au"))
        r.fail("distance_au", "is not used with \"position_m\" (the distance is |position_m - camera position|)");
      const dvec3 d = position(r, "position_m") - camera.position_m;
      distance_au = glm::length(d) / kAstronomicalUnit_m;
      if (!(distance_au >= kSunDistance.lo && distance_au <= kSunDistance.hi))
        r.fail("position_m",
               cat("= ", brief(r.raw("position_m")), ": is ", distance_au, " AU from the camera; the sun's distance ",
                   JsonReader::range_text(kSunDistance.lo, kSunDistance.hi, kSunDistance.unit)));
      sun.direction = glm::normalize(d);
      break;
    }
    default: {
      JsonReader s = open_object(r, "sky", {"elevation_deg", "azimuth_deg"});
      sun.direction = glm::normalize(
          horizon.direction(number(s, "azimuth_deg", kAzimuth) * kDeg, number(s, "elevation_deg", kElevation) * kDeg));
      s.finish();
      distance_au = number_or(r, "distance_au", 1.0, kSunDistance);
      break;
    }
  }
  // Angular diameter: given, or the Sun's at this distance, 2 asin(R_sun / d).
  const double diameter_deg = r.has("angular_diameter_deg")
                                  ? positive(r, "angular_diameter_deg", kMaxSunAngularDiameter_deg, "deg")
                                  : 2.0 * std::asin(kSolarRadius_m / (distance_au * kAstronomicalUnit_m)) / kDeg;
  sun.angular_radius_rad = 0.5 * diameter_deg * kDeg;
  sun.irradiance_W_m2_nm = read_irradiance(r, distance_au, ctx);
  r.finish();
  return sun;
}

/// "time" and "site" (docs/scenes.md, "Time and place"): both or neither, for a
/// camera on or above the Earth.
std::optional<SkyClock> read_sky_clock(JsonReader& root, const std::vector<Body>& bodies,
                                       const CameraPlacement& camera) {
  if (!root.has("time") && !root.has("site")) return std::nullopt;
  if (!root.has("site"))
    root.fail("site", "missing: \"time\" needs a \"site\" {latitude_deg, longitude_deg, altitude_m}");
  if (!root.has("time"))
    root.fail("time", "missing: \"site\" needs a \"time\" (ISO 8601 UTC, e.g. \"2026-12-21T16:30:00Z\")");
  SkyClock clock;
  clock.body = camera.reference_body;
  std::string body = bodies.at(clock.body).name;
  std::transform(body.begin(), body.end(), body.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (body != "earth")
    root.fail("site", cat("places the sun by the Earth's ephemeris, but the camera's body is \"",
                          bodies.at(clock.body).name, "\": give the sun by \"sky\" for other planets"));
  const std::string text = root.string("time");
  try {
    clock.time = astro::parse_utc_time(text);
    (void)astro::AstroTime::from_utc(clock.time);  // a calendar date ERFA accepts
  } catch (const std::invalid_argument& e) {
    root.fail("time", e.what());
  }
  JsonReader site = open_object(root, "site", {"latitude_deg", "longitude_deg", "altitude_m"});
  clock.site.latitude_deg = number(site, "latitude_deg", kLatitude);
  clock.site.longitude_deg = number(site, "longitude_deg", kSiteLongitude);
  clock.site.altitude_m = number_or(site, "altitude_m", 0.0, kSiteAltitude);
  site.finish();
  return clock;
}

/// "scintillation": true (the defaults of astro::ScintillationOptions), false
/// (steady stars) or {"c_y", "pupil_mm", "integration_s", "turbulence_height_m"}.
std::optional<astro::ScintillationOptions> read_scintillation(JsonReader& night) {
  const json& v = night.raw("scintillation");
  if (v.is_boolean())
    return v.get<bool>() ? std::optional<astro::ScintillationOptions>(astro::ScintillationOptions{}) : std::nullopt;
  if (!v.is_object())
    night.fail("scintillation", cat("must be true, false or an object {\"c_y\", \"pupil_mm\", \"integration_s\", "
                                    "\"turbulence_height_m\"}, got ",
                                    brief(v)));
  JsonReader s = open_object(night, "scintillation", {"c_y", "pupil_mm", "integration_s", "turbulence_height_m"});
  astro::ScintillationOptions o;
  o.c_y = s.number_or("c_y", o.c_y, 0.0, 5.0);
  o.pupil_mm = s.number_or("pupil_mm", o.pupil_mm, 1.0, 1000.0, "mm");
  o.integration_s = s.number_or("integration_s", o.integration_s, 0.001, 10.0, "s");
  o.turbulence_height_m = s.number_or("turbulence_height_m", o.turbulence_height_m, 100.0, 30000.0, "m");
  s.finish();
  return o;
}

/// "night_sky": {"zenith_v_mag_arcsec2", "scintillation"} and "light_pollution": {"zenith_mcd_m2" | "bortle",
/// "colour_temperature_K"} (docs/scenes.md, "Night sky"), seen through the atmosphere of
/// the camera's body.
std::optional<NightSky> read_night_sky(JsonReader& root, const std::vector<Body>& bodies,
                                       const CameraPlacement& camera) {
  if (!root.has("night_sky") && !root.has("light_pollution")) return std::nullopt;
  NightSky night;
  night.body = camera.reference_body;
  const Body& body = bodies.at(night.body);
  const char* key = root.has("night_sky") ? "night_sky" : "light_pollution";
  if (!body.atmosphere)
    root.fail(key, cat("is seen through the atmosphere of the camera's body, but \"", body.name, "\" has none"));
  if (root.has("night_sky")) {
    JsonReader n = open_object(root, "night_sky", {"zenith_v_mag_arcsec2", "scintillation"});
    night.floor.zenith_v_mag_arcsec2 = n.number_or("zenith_v_mag_arcsec2", 22.0, 19.0, 23.0, "mag/arcsec^2");
    if (n.has("scintillation")) night.scintillation = read_scintillation(n);
    n.finish();
  }
  if (root.has("light_pollution")) {
    JsonReader l = open_object(root, "light_pollution", {"zenith_mcd_m2", "bortle", "colour_temperature_K"});
    night.light_pollution.colour_temperature_K = l.number_or("colour_temperature_K", 3000.0, 1500.0, 10000.0, "K");
    if (l.has("zenith_mcd_m2") == l.has("bortle"))
      l.fail("", "give exactly one of \"zenith_mcd_m2\" (artificial zenith luminance) and \"bortle\" (class 1-9)");
    if (l.has("zenith_mcd_m2")) {
      night.light_pollution.zenith_mcd_m2 = l.number("zenith_mcd_m2", 0.0, 1e5, "mcd/m^2");
    } else {
      const auto& model = body.atmosphere->loaded.model;
      const double natural = astro::NightSkyFloor(model, night.floor).zenith_luminance_cd_m2();
      night.light_pollution.zenith_mcd_m2 = astro::bortle_artificial_mcd_m2(l.integer("bortle", 1, 9), model, natural,
                                                                            night.light_pollution.colour_temperature_K);
    }
    l.finish();
  }
  return night;
}

}  // namespace

Scene parse_scene(const json& j, const std::string& source, const fs::path& base_dir) {
  JsonReader root(j, source);
  allow_keys(root, j,
             {"zenith_scene", "name", "description", "wavelengths_nm", "bodies", "sun", "camera", "time", "site",
              "night_sky", "light_pollution"});
  const json& version = root.raw("zenith_scene");
  if (!version.is_number_integer() || version.get<long long>() != kFormatVersion)
    root.fail("zenith_scene", cat("= ", brief(version), ": unsupported scene format version; this build reads version ",
                                  kFormatVersion));
  Scene scene;
  scene.source = source;
  scene.name = root.string("name");
  if (scene.name.empty()) root.fail("name", "= \"\": must not be empty");
  if (root.has("description")) root.string("description");  // free text, for people
  scene.wavelengths_nm = read_wavelengths(root);
  const Context ctx{source, base_dir, scene.wavelengths_nm};
  scene.bodies = read_bodies(root, ctx);
  JsonReader camera_reader = open_unchecked(root, "camera");
  allow_camera_keys(camera_reader, root.raw("camera"));
  const CameraPlacement camera = read_camera(camera_reader, scene.bodies, ctx);
  scene.camera = camera.camera;
  scene.sky_clock = read_sky_clock(root, scene.bodies, camera);
  scene.night_sky = read_night_sky(root, scene.bodies, camera);
  std::optional<EphemerisSun> ephemeris;
  if (scene.sky_clock)
    ephemeris = ephemeris_sun(scene, *scene.sky_clock, astro::AstroTime::from_utc(scene.sky_clock->time),
                              camera.camera.position_m);
  JsonReader sun_reader = open_unchecked(root, "sun");
  allow_sun_keys(sun_reader, root.raw("sun"));
  scene.sun = read_sun(sun_reader, scene.bodies, camera, ctx, ephemeris);
  root.finish();
  try {
    check_scene(scene);  // the invariants, once more, on the resolved values
  } catch (const std::invalid_argument& e) {
    throw ConfigError(source, "", e.what());
  }
  return scene;
}

std::size_t nearest_body(const std::vector<Body>& bodies, const dvec3& point_m) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < bodies.size(); ++i)
    if (glm::length(point_m - bodies[i].position_m) - bodies[i].radius_m <
        glm::length(point_m - bodies[best].position_m) - bodies[best].radius_m)
      best = i;
  return best;
}

CameraPlacement parse_camera(const json& camera, const Scene& scene, const std::string& source,
                             const std::string& pointer) {
  JsonReader r(camera, source, pointer);
  allow_camera_keys(r, camera);
  if (scene.bodies.empty()) r.fail("", "the scene has no bodies to place a camera by");
  const Context ctx{source, {}, scene.wavelengths_nm};
  return read_camera(r, scene.bodies, ctx);
}

Sun parse_sun(const json& sun, const Scene& scene, const CameraPlacement& camera, const std::string& source,
              const std::string& pointer) {
  JsonReader r(sun, source, pointer);
  allow_sun_keys(r, sun);
  const Context ctx{source, {}, scene.wavelengths_nm};
  return read_sun(r, scene.bodies, camera, ctx);
}

Scene load_scene(const fs::path& path) { return parse_scene(read_json_file(path), path.string(), path.parent_path()); }

}  // namespace zenith::scene
