#include "cluster/master/takeover.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cluster/link/atmosphere_definition.h"
#include "core/strings.h"

namespace zenith::cluster {

using core::cat;

namespace {

/// Whether two vectors agree to within `tolerance` in every component.
template <typename V>
bool close(const V& a, const V& b, double tolerance) {
  for (int i = 0; i < V::length(); ++i)
    if (std::abs(a[i] - b[i]) > tolerance) return false;
  return true;
}

}  // namespace

Continuation continuation_of(const TakeoverState& state, const FrameState& expected, double fps) {
  if (!state.last_frame) throw std::logic_error("continuation_of: no frame to continue from");
  const FrameState& last = *state.last_frame;
  Continuation c;
  c.next_frame = state.next_frame();
  c.last_show_time_s = last.show_time_s;
  if (state.show_time_step_s) {
    // Rates are typed values (1, 2, 0.5, -1): the step's rounding error is not one.
    double rate = *state.show_time_step_s * fps;
    if (const double typed = std::round(rate * 1e6) / 1e6; std::abs(rate - typed) < 1e-9) rate = typed;
    if (*state.show_time_step_s == 0.0)
      c.paused = true;
    else if (std::abs(rate) <= show::PlaybackClock::kMaxRate)
      c.rate = rate;
  }
  if (last.exposure != expected.exposure) c.exposure = last.exposure;
  const double tolerance = 1e-9;
  if (!close(last.camera_position_m, expected.camera_position_m,
             1e-6 * std::max(1.0, glm::length(last.camera_position_m))))
    c.mismatches.push_back("camera position");
  if (!close(glm::dvec4(last.camera_orientation.w, last.camera_orientation.x, last.camera_orientation.y,
                        last.camera_orientation.z),
             glm::dvec4(expected.camera_orientation.w, expected.camera_orientation.x, expected.camera_orientation.y,
                        expected.camera_orientation.z),
             tolerance))
    c.mismatches.push_back("camera orientation");
  if (!close(last.sun_direction, expected.sun_direction, tolerance)) c.mismatches.push_back("sun direction");
  if (last.sun_irradiance_W_m2_nm.size() != expected.sun_irradiance_W_m2_nm.size())
    c.mismatches.push_back("sun irradiance wavelengths");
  if (last.render_flags != expected.render_flags) c.mismatches.push_back("render flags");
  return c;
}

void continue_clock(const Continuation& c, show::PlaybackClock& clock) {
  clock.seek(c.last_show_time_s);
  if (c.paused)
    clock.pause();
  else
    clock.set_rate(c.rate);
  (void)clock.next_frame_time_s();  // the last frame's time: the next one is a step on
}

void adopt_takeover_tables(const TakeoverState& state, const scene::Scene& scene, TableVersions& tables,
                           bool default_show) {
  for (const TakeoverState::Version& v : state.versions) {
    tables.add_version(v.definition.body_name, resolve_definition(v.definition, scene), v.definition.table_hash);
    tables.add_set(v.set);
  }
  if (!default_show || !state.last_frame) return;
  for (const AtmosphereTableRef& ref : state.last_frame->atmospheres) {
    if (!tables.has_set(ref.table_hash))
      throw std::runtime_error(cat("frame ", state.last_frame->frame, " uses table set ", short_hex(ref.table_hash),
                                   " of '", ref.body_name, "', which the standby did not receive"));
    tables.add_current(ref.body_name, ref.table_hash, ref.effective_from_frame);
  }
}

Continuation continue_show(const TakeoverState& t, const FrameState& expected, double fps) {
  const Continuation c = continuation_of(t, expected, fps);
  const FrameState& last = *t.last_frame;
  for (const std::string& what : c.mismatches)
    spdlog::warn(
        "master: taking over: the {} of frame {} differs from this standby's show (are its scene, show "
        "and --sun-step-deg the active master's?): the picture jumps at the takeover",
        what, last.frame);
  spdlog::info(
      "master: taking over the show at frame {} (the active master's last was frame {}, show time {:.3f} s, "
      "{}) with the {} table version{} it distributed",
      c.next_frame, last.frame, last.show_time_s, t.frame_in_flight() ? "in flight, not seen presented" : "presented",
      t.versions.size(), t.versions.size() == 1 ? "" : "s");
  return c;
}

}  // namespace zenith::cluster
