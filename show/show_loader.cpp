// load_show: reads and checks a show file (docs/shows.md) into a Show.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include <spdlog/spdlog.h>
#include <glm/geometric.hpp>

#include "astro/sky_data_identity.h"
#include "astro/star_catalogue.h"
#include "core/json_reader.h"
#include "core/sha256.h"
#include "core/strings.h"
#include "core/units.h"
#include "scene/scene.h"
#include "scene/scene_loader.h"
#include "show/recording_json.h"
#include "show/show.h"
#include "show/show_impl.h"

namespace zenith::show {
namespace {

using config::brief;
using core::cat;
using nlohmann::json;
using scene::kMaxExposure;
namespace fs = std::filesystem;

constexpr double kMaxKeyTime_s = 86400.0;  // a day
/// Keys of a track, whatever the limits say (ShowLimits::max_keys_per_track is checked first).
constexpr std::size_t kMaxKeys = ShowLimits::kMaxKeysPerTrackCeiling;
constexpr double kMaxFps = 240.0;
constexpr double kDefaultFps = 30.0;
constexpr double kMaxRecordingFps = 1000.0;
constexpr double kMinCameraClearance_m = 0.1;  // as scenes
/// Samples per segment when checking that a free camera path clears every body.
constexpr int kClearanceSamples = 64;
using core::kDeg;

void allow(const JsonReader& r, const json& object, std::initializer_list<std::string_view> keys) {
  config::reject_unknown_keys(r, object, keys, "docs/shows.md");
}

bool boolean_or(JsonReader& r, const std::string& key, bool fallback) {
  if (!r.has(key)) return fallback;
  const json& v = r.raw(key);
  if (!v.is_boolean()) r.fail(key, cat("= ", brief(v), ": must be true or false"));
  return v.get<bool>();
}

/// Every track's key count against `max_keys`, before a key is read: a show
/// of 10^7 keys once took 3.5 GB before the key limit could refuse it.
void check_key_counts(const json& show, const std::string& file, std::size_t max_keys) {
  const auto check = [&](const json& keys, const std::string& pointer) {
    if (keys.is_array() && keys.size() > max_keys)
      throw ConfigError(file, pointer,
                        cat("= an array of ", keys.size(), " keys: a track holds at most ", max_keys,
                            " (--max-keys; docs/shows.md, \"Limits\")"));
  };
  if (!show.is_object()) return;
  for (const char* track : {"camera", "sun", "exposure"})
    if (show.contains(track)) check(show[track], cat("/", track));
  const auto atmospheres = show.find("atmospheres");
  if (atmospheres == show.end() || !atmospheres->is_array()) return;
  for (std::size_t i = 0; i < atmospheres->size(); ++i) {
    const json& body = (*atmospheres)[i];
    const auto tracks = body.is_object() ? body.find("tracks") : body.end();
    if (!body.is_object() || tracks == body.end() || !tracks->is_array()) continue;
    for (std::size_t k = 0; k < tracks->size(); ++k)
      if ((*tracks)[k].is_object() && (*tracks)[k].contains("keys"))
        check((*tracks)[k]["keys"], cat("/atmospheres/", i, "/tracks/", k, "/keys"));
  }
}

/// A track: a non-empty array of key objects.
const json& track_array(JsonReader& r, const std::string& key, const char* form) {
  const json& keys = r.raw(key);
  if (!keys.is_array() || keys.empty() || keys.size() > kMaxKeys)
    r.fail(key, cat("= ", brief(keys), ": must be an array of 1 to ", kMaxKeys, " keys ", form));
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (!keys[i].is_object()) r.fail(cat(key, "/", i), cat("= ", brief(keys[i]), ": must be a key object ", form));
  return keys;
}

/// The "t_s" of a key: in [0, 1 day], after the previous key's.
double key_time(JsonReader& key, double previous_s) {
  const double t = key.number("t_s", 0.0, kMaxKeyTime_s, "s");
  if (!(t > previous_s))
    key.fail("t_s", cat("= ", brief(key.raw("t_s")),
                        ": keys must be strictly increasing in t_s (the previous key is at ", previous_s, " s)"));
  return t;
}

/// The key object without "t_s": the camera or sun object it carries.
json without_time(const json& key) {
  json object = key;
  object.erase("t_s");
  return object;
}

/// The keys of the camera or sun track (`track`: "camera", "sun"), in order:
/// the time of each (key_time: after the previous key's), then the rest of it
/// by `read_key(object, pointer, t_s, earlier)`, `earlier` the keys before it.
template <class Key, class ReadKey>
std::vector<Key> read_object_keys(JsonReader& root, const json& keys, const std::string& track, ReadKey&& read_key) {
  std::vector<Key> out;
  double previous = -1.0;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string pointer = cat("/", track, "/", i);
    JsonReader key(keys[i], root.file(), pointer);
    previous = key_time(key, previous);
    out.push_back(read_key(key, keys[i], pointer, previous, out));
  }
  return out;
}

// ------------------------------------------------------------------ camera

void check_clearance(const CameraTrack& track, const scene::Scene& scene, const std::string& file) {
  const std::vector<double>& t = track.key_times_s();
  for (std::size_t k = 0; k + 1 < t.size(); ++k)
    for (int j = 1; j < kClearanceSamples; ++j) {
      const double time = t[k] + (t[k + 1] - t[k]) * j / kClearanceSamples;
      const glm::dvec3 p = track.position_m(time);
      for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
        const double altitude = glm::length(p - scene.bodies[b].position_m) - scene.bodies[b].radius_m;
        if (altitude < kMinCameraClearance_m)
          throw ConfigError(file, cat("/camera/", k + 1),
                            cat("between this key and the previous one the camera path comes within ", altitude,
                                " m of the surface of body \"", scene.bodies[b].name, "\" (at t = ", time,
                                " s); it must stay at least ", kMinCameraClearance_m,
                                " m above every body (add keys, or give every key as \"surface\" on one body so the "
                                "path follows the ground)"));
      }
    }
}

CameraTrack read_camera_track(JsonReader& root, const scene::Scene& scene) {
  const json& keys = track_array(root, "camera", "{\"t_s\", camera object as in a scene}");
  std::vector<CameraKey> out = read_object_keys<CameraKey>(
      root, keys, "camera",
      [&](JsonReader& key, const json& object, const std::string& pointer, double t_s, const std::vector<CameraKey>&) {
        if (object.contains("exposure"))
          key.fail("exposure", "the exposure has its own track, /exposure (docs/shows.md)");
        CameraKey k;
        k.t_s = t_s;
        k.placement = scene::parse_camera(without_time(object), scene, root.file(), pointer);
        return k;
      });
  // Surface paths: consecutive keys less than kMaxSurfaceKeyAngle_deg apart.
  bool surface = true;
  for (const CameraKey& k : out)
    surface = surface && k.placement.surface && k.placement.reference_body == out.front().placement.reference_body;
  for (std::size_t i = 1; surface && i < out.size(); ++i) {
    const auto& a = *out[i - 1].placement.surface;
    const auto& b = *out[i].placement.surface;
    const double angle = angle_between_rad(scene::direction_from_latitude_longitude(a.latitude_rad, a.longitude_rad),
                                           scene::direction_from_latitude_longitude(b.latitude_rad, b.longitude_rad));
    if (angle > kMaxSurfaceKeyAngle_deg * kDeg)
      throw ConfigError(root.file(), cat("/camera/", i, "/surface"),
                        cat("is ", angle / kDeg,
                            " deg around the body from the previous key; consecutive surface keys "
                            "must be at most ",
                            kMaxSurfaceKeyAngle_deg, " deg apart (add keys in between)"));
  }
  CameraTrack track(out, scene.bodies);
  check_clearance(track, scene, root.file());
  return track;
}

/// Where the camera is at t, for sun keys given in its local sky.
scene::CameraPlacement camera_at(const std::optional<CameraTrack>& camera, const scene::Scene& scene, double t_s) {
  scene::CameraPlacement placement;
  placement.camera = scene.camera;
  if (camera) {
    placement.camera.position_m = camera->position_m(t_s);
    placement.camera.orientation = camera->orientation(t_s);
  }
  placement.reference_body = camera && camera->surface_body()
                                 ? *camera->surface_body()
                                 : scene::nearest_body(scene.bodies, placement.camera.position_m);
  return placement;
}

// ------------------------------------------------------------------ sun and exposure

SunTrack read_sun_track(JsonReader& root, const scene::Scene& scene, const std::optional<CameraTrack>& camera) {
  const json& keys = track_array(root, "sun", "{\"t_s\", sun object as in a scene}");
  return SunTrack(read_object_keys<SunKey>(
      root, keys, "sun",
      [&](JsonReader&, const json& object, const std::string& pointer, double t_s, const std::vector<SunKey>& earlier) {
        SunKey k;
        k.t_s = t_s;
        k.sun = scene::parse_sun(without_time(object), scene, camera_at(camera, scene, t_s), root.file(), pointer);
        if (!earlier.empty()) {
          const double angle = angle_between_rad(earlier.back().sun.direction, k.sun.direction);
          if (angle >= kMaxSunKeyAngle_deg * kDeg)
            throw ConfigError(root.file(), pointer,
                              cat("the sun is ", angle / kDeg,
                                  " deg from the previous key's; consecutive sun keys "
                                  "must be less than ",
                                  kMaxSunKeyAngle_deg, " deg apart (add keys in between)"));
        }
        return k;
      }));
}

MonotoneCubic read_exposure_track(JsonReader& root) {
  const json& keys = track_array(root, "exposure", "{\"t_s\", \"exposure\"}");
  std::vector<double> times, log_exposure;
  double previous = -1.0;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    JsonReader key(keys[i], root.file(), cat("/exposure/", i));
    allow(key, keys[i], {"t_s", "exposure"});
    times.push_back(previous = key_time(key, previous));
    const double exposure = key.number("exposure", 0.0, kMaxExposure);
    if (!(exposure > 0.0)) key.fail("exposure", cat("= ", brief(key.raw("exposure")), ": must be in (0, 1e+06]"));
    log_exposure.push_back(std::log(exposure));
    key.finish();
  }
  return MonotoneCubic(times, log_exposure);
}

// ------------------------------------------------------------------ atmospheres

bool overlaps(const json::json_pointer& a, const json::json_pointer& b) {
  const std::string x = a.to_string(), y = b.to_string();
  return x == y || x.starts_with(y + "/") || y.starts_with(x + "/");
}

ParameterTrack read_parameter_track(const json& track, const std::string& pointer, const std::string& file,
                                    const json& base, const std::string& body,
                                    const std::vector<ParameterTrack>& earlier) {
  JsonReader r(track, file, pointer);
  allow(r, track, {"parameter", "step", "keys"});
  const std::string text = r.string("parameter");
  json::json_pointer parameter;
  try {
    if (!text.starts_with("/")) throw std::invalid_argument("must start with /");
    parameter = json::json_pointer(text);
  } catch (const std::exception&) {
    r.fail("parameter", cat("= \"", text,
                            "\": must be a JSON pointer into the atmosphere's parameters, such as "
                            "\"/aerosol/scattering/turbidity\""));
  }
  if (!base.contains(parameter)) {
    std::string top;
    for (const auto& [key, value] : base.items()) top += cat(top.empty() ? "" : ", ", key);
    r.fail("parameter", cat("= \"", text, "\": not present in the parameters of the atmosphere of \"", body,
                            "\" as the scene resolves it (its top-level keys: ", top, ")"));
  }
  for (std::size_t j = 0; j < earlier.size(); ++j)
    if (overlaps(parameter, earlier[j].pointer()))
      r.fail("parameter", cat("= \"", text, "\": overlaps the parameter of track ", j, " (\"",
                              earlier[j].pointer().to_string(), "\"); each part of the parameters may have one track"));

  const json& keys = track_array(r, "keys", "{\"t_s\", \"value\"}");
  const bool numeric = keys[0].contains("value") && keys[0]["value"].is_number();
  std::optional<double> step;
  if (numeric) {
    const json& s = r.raw("step");
    if (!s.is_number() || !(s.get<double>() > 0.0) || !std::isfinite(s.get<double>()))
      r.fail("step", cat("= ", brief(s), ": must be a number > 0 (the values are rounded to multiples of it)"));
    step = s.get<double>();
  } else if (r.has("step")) {
    r.fail("step",
           "applies to numeric tracks only (this track's values are not numbers: they are held from key to key)");
  }
  std::vector<ParameterKey> out;
  double previous = -1.0;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    JsonReader key(keys[i], file, r.key_path(cat("keys/", i)));
    allow(key, keys[i], {"t_s", "value"});
    ParameterKey k;
    k.t_s = previous = key_time(key, previous);
    k.value = key.raw("value");
    if (k.value.is_number() != numeric)
      key.fail("value", cat("= ", brief(k.value),
                            numeric ? ": must be a number, as key 0's value is (a numeric track)"
                                    : ": must not be a number, as key 0's value is not (a held "
                                      "track; give numbers in a track with a step)"));
    if (numeric && !(std::abs(k.value.get<double>() / *step) < 9e15))
      key.fail("value", cat("= ", brief(k.value), ": is too large for the step ", *step));
    key.finish();
    out.push_back(std::move(k));
  }
  r.finish();
  return ParameterTrack(parameter, step, std::move(out));
}

std::vector<AtmosphereTracks> read_atmosphere_tracks(JsonReader& root, const scene::Scene& scene) {
  const json& list = root.raw("atmospheres");
  if (!list.is_array() || list.empty())
    root.fail("atmospheres", cat("= ", brief(list), ": must be an array of {\"body\", \"tracks\"}"));
  std::vector<std::string> with_atmosphere;
  for (const scene::Body& b : scene.bodies)
    if (b.atmosphere) with_atmosphere.push_back(b.name);
  std::vector<AtmosphereTracks> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    JsonReader r(list[i], root.file(), cat("/atmospheres/", i));
    allow(r, list[i], {"body", "tracks"});
    AtmosphereTracks body;
    body.entry = i;
    body.body = r.string("body");
    if (std::find(with_atmosphere.begin(), with_atmosphere.end(), body.body) == with_atmosphere.end()) {
      std::string names;
      for (const std::string& n : with_atmosphere) names += cat(names.empty() ? "" : ", ", '"', n, '"');
      r.fail("body",
             cat("= \"", body.body, "\": the scene has no body of that name with an atmosphere (those with one: ",
                 names.empty() ? std::string("none") : names, ")"));
    }
    for (const AtmosphereTracks& other : out)
      if (other.body == body.body)
        r.fail("body", cat("= \"", body.body, "\": already has tracks at /atmospheres/", other.entry,
                           "; give all of a body's tracks in one entry"));
    body.base = scene.find_body(body.body)->atmosphere->loaded.parameters;
    const json& tracks = r.raw("tracks");
    if (!tracks.is_array() || tracks.empty())
      r.fail("tracks", cat("= ", brief(tracks), ": must be an array of {\"parameter\", \"step\", \"keys\"}"));
    for (std::size_t j = 0; j < tracks.size(); ++j)
      body.tracks.push_back(read_parameter_track(tracks[j], r.key_path(cat("tracks/", j)), root.file(), body.base,
                                                 body.body, body.tracks));
    r.finish();
    out.push_back(std::move(body));
  }
  return out;
}

// ------------------------------------------------------------------ timecode

/// "timecode": {"rate": "25", "start": "01:00:00:00", "freewheel_s": 2, "after_dropout": "hold"}
/// (docs/shows.md, "Chasing timecode").
Show::HouseTimecode read_timecode(JsonReader& root) {
  JsonReader r = root.object("timecode");
  allow(r, root.raw("timecode"), {"rate", "start", "freewheel_s", "after_dropout"});
  Show::HouseTimecode tc;
  const std::string rate = r.string("rate", {"24", "25", "29.97df", "30"});
  tc.rate = *parse_timecode_rate(rate);
  const std::string start = r.string("start");
  try {
    tc.chase.offset_s = timecode_seconds(parse_timecode(start, tc.rate), tc.rate);
  } catch (const std::invalid_argument& e) {
    r.fail("start", e.what());
  }
  tc.chase.freewheel_s = r.number_or("freewheel_s", tc.chase.freewheel_s, 0.0, 3600.0, "s");
  tc.chase.after_dropout = r.string_or("after_dropout", "hold", {"hold", "stop"}) == "stop"
                               ? ChaseSettings::AfterDropout::stop
                               : ChaseSettings::AfterDropout::hold;
  r.finish();
  return tc;
}

// ------------------------------------------------------------------ recordings

void read_recording(JsonReader& root, Show::Impl& show) {
  JsonReader r = root.object("recording");
  allow(r, root.raw("recording"), {"fps", "versions", "frames"});
  show.frame_rate_hz = r.number("fps", 0.0, kMaxRecordingFps, "Hz");
  if (!(show.frame_rate_hz > 0.0))
    r.fail("fps", cat("= ", brief(r.raw("fps")), ": must be in (0, ", kMaxRecordingFps, "] Hz"));

  const json& versions = r.raw("versions");
  if (!versions.is_array())
    r.fail("versions", cat("= ", brief(versions), ": must be an array of {\"body\", \"table_hash\", \"parameters\"}"));
  for (std::size_t i = 0; i < versions.size(); ++i) {
    JsonReader v(versions[i], root.file(), r.key_path(cat("versions/", i)));
    allow(v, versions[i], {"body", "table_hash", "parameters"});
    AtmosphereVersion version;
    version.body = v.string("body");
    const scene::Body* body = show.scene.find_body(version.body);
    if (body == nullptr || !body->atmosphere)
      v.fail("body", cat("= \"", version.body, "\": the scene has no body of that name with an atmosphere"));
    scene::TableHash listed{};
    try {
      listed = core::digest_from_hex(v.string("table_hash"));
    } catch (const std::invalid_argument&) {
      v.fail("table_hash", cat("= ", brief(v.raw("table_hash")), ": must be 64 hexadecimal digits"));
    }
    version.parameters = v.raw("parameters");
    if (!version.parameters.is_object())
      v.fail("parameters", cat("must be an object, got ", brief(version.parameters)));
    try {
      version.loaded =
          atmosphere::resolve_atmosphere(version.parameters, cat(root.file(), "#", v.key_path("parameters")),
                                         atmosphere::LoadOptions{show.scene.wavelengths_nm});
    } catch (const ConfigError& e) {
      v.fail("parameters", cat("do not resolve: ", e.what()));
    }
    version.table_hash = table_hash_of(version.loaded);
    if (version.table_hash != listed)
      v.fail("table_hash", cat("= \"", core::to_hex(listed), "\": does not match the parameters, whose tables hash to ",
                               core::to_hex(version.table_hash),
                               " (edited parameters, or recorded by a build with another table format)"));
    if (std::find(show.recorded_versions.begin(), show.recorded_versions.end(), listed) != show.recorded_versions.end())
      v.fail("table_hash", "is listed twice");
    show.recorded_versions.push_back(listed);
    show.versions.insert_or_assign(listed, std::move(version));
  }

  const json& frames = r.raw("frames");
  if (!frames.is_array() || frames.empty())
    r.fail("frames", cat("= ", brief(frames), ": must be a non-empty array of frame states"));
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::string pointer = r.key_path(cat("frames/", i));
    if (!frames[i].is_object())
      throw ConfigError(root.file(), pointer, cat("must be an object, got ", brief(frames[i])));
    scene::FrameDescription frame = frame_from_json(frames[i], show.scene, root.file(), pointer);
    for (std::size_t a = 0; a < frame.atmospheres.size(); ++a) {
      const auto version = show.versions.find(frame.atmospheres[a].table_hash);
      const std::string key = cat(pointer, "/atmospheres/", a, "/table_hash");
      const bool listed = std::find(show.recorded_versions.begin(), show.recorded_versions.end(),
                                    frame.atmospheres[a].table_hash) != show.recorded_versions.end();
      if (!listed)
        throw ConfigError(root.file(), key,
                          cat("= \"", core::to_hex(frame.atmospheres[a].table_hash),
                              "\": not among the recording's /recording/versions"));
      if (version->second.body != frame.atmospheres[a].body_name)
        throw ConfigError(root.file(), key,
                          cat("is the version of body \"", version->second.body, "\", not of \"",
                              frame.atmospheres[a].body_name, "\""));
    }
    show.frames.push_back(std::move(frame));
  }
  // A recording's timeline is the session's: frame i at i / fps, whatever its
  // show time (the operator may have paused, sought or reversed the show).
  show.duration_s = static_cast<double>(show.frames.size() - 1) / show.frame_rate_hz;
  r.finish();
}

/// "time": {"start": ISO UTC (default: the scene's "time"), "time_rate": sky seconds per
/// show second, "end_s": the show time it runs to} (docs/shows.md, "Time track").
TimeTrack read_time_track(JsonReader& root, const scene::Scene& scene) {
  if (!scene.sky_clock)
    root.fail("time", "moves the scene's sky clock, but the scene gives no \"time\" and \"site\" (docs/scenes.md)");
  if (root.has("sun")) root.fail("time", "and a \"sun\" track both move the sun: give one");
  const json& v = root.raw("time");
  if (!v.is_object()) root.fail("time", cat("must be an object {\"start\", \"time_rate\", \"end_s\"}, got ", brief(v)));
  JsonReader r(v, root.file(), root.key_path("time"));
  allow(r, v, {"start", "time_rate", "end_s"});
  TimeTrack track;
  astro::UtcTime start = scene.sky_clock->time;
  if (r.has("start")) {
    try {
      start = astro::parse_utc_time(r.string("start"));
    } catch (const std::invalid_argument& e) {
      r.fail("start", e.what());
    }
  }
  try {
    track.start = astro::AstroTime::from_utc(start);
  } catch (const std::invalid_argument& e) {
    r.fail("start", e.what());
  }
  track.time_rate = r.number_or("time_rate", 1.0, -86400.0, 86400.0, "sky s per show s");
  track.end_s = r.number_or("end_s", 0.0, 0.0, 86400.0, "s");
  r.finish();
  return track;
}

}  // namespace

Show load_show(const fs::path& path, const ShowLimits& limits) {
  const std::string file = path.string();
  const json j = read_json_file(path);
  JsonReader root(j, file);
  allow(root, j,
        {"zenith_show", "name", "description", "scene", "cluster", "fps", "loop", "camera", "sun", "time", "exposure",
         "atmospheres", "recording", "timecode"});
  const json& version = root.raw("zenith_show");
  if (!version.is_number_integer() || version.get<long long>() != kShowFormatVersion)
    root.fail("zenith_show", cat("= ", brief(version), ": unsupported show format version; this build reads version ",
                                 kShowFormatVersion));
  check_key_counts(j, file, std::min(limits.max_keys_per_track, kMaxKeys));

  auto impl = std::make_unique<Show::Impl>();
  Show::Impl& show = *impl;
  show.source = path;
  show.name = root.string("name");
  if (show.name.empty()) root.fail("name", "= \"\": must not be empty");
  if (root.has("description")) root.string("description");  // free text, for people
  const fs::path base_dir = path.parent_path();
  show.scene_path = root.existing_file("scene", base_dir);
  try {
    show.scene = scene::load_scene(show.scene_path);
  } catch (const ConfigError& e) {
    root.fail("scene", cat("invalid scene file: ", e.what()));
  }
  if (root.has("cluster")) show.cluster_path = root.existing_file("cluster", base_dir);
  show.loop = boolean_or(root, "loop", false);
  if (root.has("timecode")) show.timecode = read_timecode(root);

  for (const scene::Body& body : show.scene.bodies)
    if (body.atmosphere) {
      AtmosphereVersion v{body.name, body.atmosphere->loaded.parameters, table_hash_of(body.atmosphere->loaded),
                          body.atmosphere->loaded};
      show.fixed_atmospheres[body.name] = v.table_hash;
      show.versions.try_emplace(v.table_hash, std::move(v));
    }

  if (root.has("recording")) {
    show.kind = Show::Kind::recording;
    for (const char* key : {"fps", "camera", "sun", "time", "exposure", "atmospheres"})
      if (root.has(key))
        root.fail(key, "is not used in a recording (its frames hold every state; its rate is /recording/fps)");
    read_recording(root, show);
    root.finish();
    return Show(std::move(impl));
  }

  show.kind = Show::Kind::keyframed;
  if (root.has("fps")) {
    show.frame_rate_hz = root.number("fps", 0.0, kMaxFps, "Hz");
    if (!(show.frame_rate_hz > 0.0)) root.fail("fps", cat("= ", brief(root.raw("fps")), ": must be in (0, 240] Hz"));
  } else {
    show.frame_rate_hz = kDefaultFps;
  }
  std::vector<double> last_key_times{0.0};
  if (root.has("camera")) {
    show.camera = read_camera_track(root, show.scene);
    last_key_times.push_back(show.camera->key_times_s().back());
  }
  if (root.has("sun")) {
    show.sun = read_sun_track(root, show.scene, show.camera);
    last_key_times.push_back(show.sun->key_times_s().back());
  }
  if (show.scene.sky_clock) {
    // The catalogue's and the Moon's map's identity, never their data, go to the
    // nodes (each reads its own copy: astro/sky_data_identity.h).
    try {
      show.star_catalogue = core::digest_from_hex(astro::sky_data_identity(
          astro::load_star_catalogue().identity_sha256, astro::moon_map_identity(astro::kStellariumMoonMap)));
    } catch (const std::exception& e) {
      spdlog::warn("show '{}': no star catalogue to name to the nodes ({}); they draw what they have", show.name,
                   e.what());
    }
  }
  if (root.has("time")) {
    show.time = read_time_track(root, show.scene);
    last_key_times.push_back(show.time->end_s);
  }
  if (root.has("exposure")) {
    show.log_exposure = read_exposure_track(root);
    last_key_times.push_back(show.log_exposure->times().back());
  }
  if (root.has("atmospheres")) {
    show.atmosphere_tracks = read_atmosphere_tracks(root, show.scene);
    for (const AtmosphereTracks& body : show.atmosphere_tracks) {
      show.fixed_atmospheres.erase(body.body);
      for (const ParameterTrack& track : body.tracks) last_key_times.push_back(track.keys().back().t_s);
    }
  }
  root.finish();
  show.duration_s = *std::max_element(last_key_times.begin(), last_key_times.end());

  // Resolve every parameter set the show uses at its own rate and at every key,
  // so that a set that does not resolve is reported now, not mid-show.
  // Each new set is counted as it appears: the limit stops a tiny step after
  // max_table_sets resolutions, not after thousands.
  const auto check_sets = [&](const AtmosphereTracks& body, double t_s) {
    if (show.versions.size() <= limits.max_table_sets) return;
    throw ConfigError(file, cat("/atmospheres/", body.entry),
                      cat("the tracks of \"", body.body, "\" step through more than ", limits.max_table_sets,
                          " lookup-table sets (reached at t = ", t_s, " s); each is a precompute and about ",
                          "a table set's memory on the master and every node: use a coarser \"step\" or fewer keys, "
                          "or raise the limit (--max-table-sets)"));
  };
  for (const AtmosphereTracks& body : show.atmosphere_tracks) {
    for (const ParameterTrack& track : body.tracks)
      for (const ParameterKey& key : track.keys()) {
        show.tracked_hash(body, key.t_s);
        check_sets(body, key.t_s);
      }
    const auto frames = static_cast<std::uint64_t>(std::floor(show.duration_s * show.frame_rate_hz + 1e-9)) + 1;
    for (std::uint64_t i = 0; i < frames; ++i) {
      const double t_s = static_cast<double>(i) / show.frame_rate_hz;
      show.tracked_hash(body, t_s);
      check_sets(body, t_s);
    }
  }
  return Show(std::move(impl));
}

}  // namespace zenith::show
