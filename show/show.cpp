#include "show/show.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "atmosphere/model_hash.h"
#include "core/json_reader.h"
#include "core/sha256.h"
#include "core/strings.h"
#include "scene/frame_scene.h"
#include "show/show_impl.h"

namespace zenith::show {

using core::cat;

scene::TableHash table_hash_of(const atmosphere::LoadedAtmosphere& loaded) {
  return core::digest_from_hex(atmosphere::lookup_table_hash(loaded.model));
}

nlohmann::json AtmosphereTracks::parameters_at(double t_s) const {
  nlohmann::json parameters = base;
  for (const ParameterTrack& track : tracks) track.apply(parameters, t_s);
  return parameters;
}

scene::TableHash Show::Impl::remember(AtmosphereVersion version) const {
  const scene::TableHash hash = version.table_hash;
  std::lock_guard lock(mutex);
  versions.try_emplace(hash, std::move(version));
  return hash;
}

scene::TableHash Show::Impl::tracked_hash(const AtmosphereTracks& body, double t_s) const {
  nlohmann::json parameters = body.parameters_at(t_s);
  const std::string key = cat(body.body, '\n', parameters.dump());
  {
    std::lock_guard lock(mutex);
    if (const auto known = hash_by_parameters.find(key); known != hash_by_parameters.end()) return known->second;
  }
  // New: resolve outside the lock (it takes milliseconds); two threads may
  // resolve the same set at once, and both get the same answer.
  AtmosphereVersion version;
  version.body = body.body;
  try {
    version.loaded = atmosphere::resolve_atmosphere(parameters, cat(source.string(), "#/atmospheres/", body.entry),
                                                    atmosphere::LoadOptions{scene.wavelengths_nm});
  } catch (const ConfigError& e) {
    std::string values;
    for (const ParameterTrack& track : body.tracks)
      values += cat(values.empty() ? "" : ", ", track.pointer().to_string(), " = ", track.value_at(t_s).dump());
    throw ConfigError(source.string(), cat("/atmospheres/", body.entry),
                      cat("at show time ", t_s, " s (", values, ") the atmosphere of \"", body.body,
                          "\" does not resolve: ", e.what()));
  }
  version.parameters = std::move(parameters);
  version.table_hash = table_hash_of(version.loaded);
  const scene::TableHash hash = remember(std::move(version));
  std::lock_guard lock(mutex);
  hash_by_parameters.emplace(key, hash);
  return hash;
}

scene::FrameDescription Show::Impl::keyframed_state(double t_s, std::uint64_t frame, std::uint32_t render_flags) const {
  scene::FrameDescription s;
  s.frame = frame;
  s.show_time_s = t_s;
  s.camera_position_m = camera ? camera->position_m(t_s) : scene.camera.position_m;
  s.camera_orientation = camera ? camera->orientation(t_s) : scene.camera.orientation;
  s.exposure = log_exposure ? std::exp((*log_exposure)(t_s)) : scene.camera.exposure;
  const scene::Sun sun_now = sun ? sun->at(t_s) : scene.sun;
  s.sun_direction = sun_now.direction;
  s.sun_angular_radius_rad = sun_now.angular_radius_rad;
  s.sun_irradiance_W_m2_nm = sun_now.irradiance_W_m2_nm;
  if (time) {
    // The sky clock moved: the ephemeris' sun in the camera's horizon at t (the
    // irradiance is the scene's: the Earth–Sun distance changes by 1e-5 in a night).
    const scene::EphemerisSun e = scene::ephemeris_sun(scene, *scene.sky_clock, time->at(t_s), s.camera_position_m);
    s.sun_direction = e.direction;
    s.sun_angular_radius_rad = e.angular_radius_rad;
    s.sky = scene::sky_frame(time->at(t_s), star_catalogue);
  } else if (scene.sky_clock) {
    s.sky = scene::sky_frame(astro::AstroTime::from_utc(scene.sky_clock->time), star_catalogue);
  }
  for (const scene::Body& body : scene.bodies) {
    if (!body.atmosphere) continue;
    scene::AtmosphereTableRef ref;
    ref.body_name = body.name;
    const auto tracked = std::find_if(atmosphere_tracks.begin(), atmosphere_tracks.end(),
                                      [&](const AtmosphereTracks& a) { return a.body == body.name; });
    ref.table_hash = tracked != atmosphere_tracks.end() ? tracked_hash(*tracked, t_s) : fixed_atmospheres.at(body.name);
    ref.effective_from_frame = 0;
    s.atmospheres.push_back(std::move(ref));
  }
  s.render_flags = render_flags;
  return s;
}

scene::FrameDescription Show::Impl::recorded_state(double t_s, std::uint64_t frame) const {
  // Frames were recorded at a constant rate: frame i belongs to [i, i + 1) / fps
  // of the recording's timeline (1e-9 s of slack for times computed as i / fps).
  const double position = std::floor(t_s * frame_rate_hz + 1e-9 * frame_rate_hz);
  const std::size_t index = std::min(frames.size() - 1, static_cast<std::size_t>(std::max(0.0, position)));
  scene::FrameDescription s = frames[index];
  s.frame = frame;
  for (scene::AtmosphereTableRef& ref : s.atmospheres)
    ref.effective_from_frame = std::min(ref.effective_from_frame, frame);
  return s;
}

// ---------------------------------------------------------------------------- Show

Show::Show(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Show::~Show() = default;
Show::Show(Show&&) noexcept = default;
Show& Show::operator=(Show&&) noexcept = default;

Show::Kind Show::kind() const { return impl_->kind; }
const std::string& Show::name() const { return impl_->name; }
const std::filesystem::path& Show::source() const { return impl_->source; }
const scene::Scene& Show::scene() const { return impl_->scene; }
const std::filesystem::path& Show::scene_path() const { return impl_->scene_path; }
const std::optional<std::filesystem::path>& Show::cluster_path() const { return impl_->cluster_path; }
double Show::duration_s() const { return impl_->duration_s; }
bool Show::loop() const { return impl_->loop; }
const std::optional<Show::HouseTimecode>& Show::timecode() const { return impl_->timecode; }
double Show::frame_rate_hz() const { return impl_->frame_rate_hz; }

std::uint64_t Show::frame_count(double fps) const {
  if (impl_->kind == Kind::recording) return impl_->frames.size();
  if (!(std::isfinite(fps) && fps > 0.0))
    throw std::invalid_argument(cat("Show::frame_count: fps = ", fps, " must be > 0"));
  return static_cast<std::uint64_t>(std::floor(impl_->duration_s * fps + 1e-9)) + 1;
}

double Show::frame_time_s(std::uint64_t index, double fps) const {
  if (impl_->kind == Kind::recording) {
    if (index >= impl_->frames.size())
      throw std::out_of_range(cat("Show::frame_time_s: frame ", index, " of a recording of ", impl_->frames.size()));
    return static_cast<double>(index) / impl_->frame_rate_hz;
  }
  if (!(std::isfinite(fps) && fps > 0.0))
    throw std::invalid_argument(cat("Show::frame_time_s: fps = ", fps, " must be > 0"));
  return static_cast<double>(index) / fps;
}

std::optional<astro::AstroTime> Show::sky_time_at(double show_time_s) const {
  if (!impl_->scene.sky_clock || std::isnan(show_time_s)) return std::nullopt;
  const double t = std::clamp(show_time_s, 0.0, impl_->duration_s);
  if (impl_->time) return impl_->time->at(t);
  return astro::AstroTime::from_utc(impl_->scene.sky_clock->time);
}

scene::FrameDescription Show::state_at(double show_time_s, std::uint64_t frame, std::uint32_t render_flags) const {
  if (std::isnan(show_time_s)) throw std::invalid_argument("Show::state_at: show time is NaN");
  const double t = std::clamp(show_time_s, 0.0, impl_->duration_s);
  return impl_->kind == Kind::recording ? impl_->recorded_state(t, frame)
                                        : impl_->keyframed_state(t, frame, render_flags);
}

std::vector<AtmosphereVersion> Show::atmosphere_versions(double fps) const {
  std::vector<scene::TableHash> order;
  auto note = [&order](const scene::TableHash& hash) {
    if (std::find(order.begin(), order.end(), hash) == order.end()) order.push_back(hash);
  };
  if (impl_->kind == Kind::recording) {
    for (const scene::FrameDescription& f : impl_->frames)
      for (const scene::AtmosphereTableRef& ref : f.atmospheres) note(ref.table_hash);
    for (const scene::TableHash& hash : impl_->recorded_versions) note(hash);
  } else {
    const std::uint64_t frames = frame_count(fps);
    for (std::uint64_t i = 0; i < frames; ++i)
      for (const scene::AtmosphereTableRef& ref : state_at(frame_time_s(i, fps), i, 0).atmospheres)
        note(ref.table_hash);
  }
  std::vector<AtmosphereVersion> out;
  std::lock_guard lock(impl_->mutex);
  for (const scene::TableHash& hash : order) out.push_back(impl_->versions.at(hash));
  return out;
}

const AtmosphereVersion* Show::find_version(const scene::TableHash& table_hash) const {
  std::lock_guard lock(impl_->mutex);
  const auto found = impl_->versions.find(table_hash);
  return found == impl_->versions.end() ? nullptr : &found->second;
}

// ---------------------------------------------------------------------------- apply_state

void apply_state(const scene::FrameDescription& state, const std::map<scene::TableHash, AtmosphereVersion>& versions,
                 scene::Scene& scene) {
  // Everything checked first (nothing changes when something is wrong), then
  // the per-frame parts (scene::apply_frame, as a cluster node applies them),
  // then each body's atmosphere version.
  scene::check_frame(state, scene);
  for (const scene::AtmosphereTableRef& ref : state.atmospheres) {
    const auto body = std::find_if(scene.bodies.begin(), scene.bodies.end(),
                                   [&](const scene::Body& b) { return b.name == ref.body_name; });
    if (body == scene.bodies.end() || !body->atmosphere)
      throw std::invalid_argument(cat("apply_state: the scene has no body \"", ref.body_name,
                                      "\" with an atmosphere (table ", core::to_hex(ref.table_hash), ")"));
    const auto version = versions.find(ref.table_hash);
    if (version == versions.end())
      throw std::invalid_argument(cat("apply_state: no atmosphere version with table hash ",
                                      core::to_hex(ref.table_hash), " for body \"", ref.body_name, "\""));
    if (version->second.body != ref.body_name)
      throw std::invalid_argument(cat("apply_state: table hash ", core::to_hex(ref.table_hash), " belongs to body \"",
                                      version->second.body, "\", not \"", ref.body_name, "\""));
  }
  scene::apply_frame(state, scene);
  for (const scene::AtmosphereTableRef& ref : state.atmospheres) {
    scene::Body& body = *std::find_if(scene.bodies.begin(), scene.bodies.end(),
                                      [&](const scene::Body& b) { return b.name == ref.body_name; });
    const AtmosphereVersion& version = versions.at(ref.table_hash);
    body.atmosphere->loaded = version.loaded;
    body.atmosphere->source = cat("show version ", core::to_hex(ref.table_hash).substr(0, 12));
  }
}

}  // namespace zenith::show
