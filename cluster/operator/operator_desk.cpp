#include "cluster/operator/operator_desk.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/strings.h"
#include "image/png_encoder.h"
#include "warp/viewport_config.h"

namespace zenith::cluster {

using core::cat;

/// Why a `timecode` command has nothing to act on.
constexpr const char* kNoChase =
    "the show runs on its own clock, not the house's timecode (a show file with a \"timecode\" block and "
    "--ltc-device, --ltc-file or --mtc-device make it chase; docs/shows.md, \"Chasing timecode\")";

OperatorDesk::OperatorDesk(DeskMaster& master, Setup setup, const scene::Scene& scene)
    : master_(master), setup_(std::move(setup)), sun_(scene), fade_(setup_.fps) {}

// ---------------------------------------------------------------------------- commands

std::string OperatorDesk::on_line(std::string line) {
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  if (line.empty()) return "";
  if (line.front() == '{') {
    try {
      return run(parse_operator_command_text(line), "control");
    } catch (const std::exception& e) {
      spdlog::info("master: operator (control): command refused: {}", e.what());
      return cat("error: ", e.what());
    }
  }
  if (line == "quit" || line == "stop") {
    master_.stop("stopped by the operator");
    return "stopping";
  }
  if (!setup_.clock) {
    if (line == "status")
      return cat("default show at frame ", master_.barrier_frame(), " (no show file: only status and quit)");
    return "no show is playing: only 'status' and 'quit' are available";
  }
  try {
    std::string reply = apply_to_show(line);
    spdlog::info("master: operator: {} → {}", line, reply);
    return reply;
  } catch (const std::invalid_argument& e) {
    return cat("error: ", e.what());
  }
}

std::string OperatorDesk::run(const OperatorCommand& command, const std::string& source) {
  namespace oc = operator_command;
  try {
    std::string reply;
    if (std::holds_alternative<oc::Quit>(command)) {
      master_.stop("stopped by the operator");
      reply = "stopping";
    } else if (const auto* exposure = std::get_if<oc::Exposure>(&command)) {
      exposure_ = exposure->exposure;
      reply = exposure->exposure ? cat("exposure ", *exposure->exposure, " from the next frame on")
                                 : std::string("the show's own exposure from the next frame on");
    } else if (const auto* set = std::get_if<oc::Set>(&command)) {
      reply = master_.set_atmosphere(*set);
    } else if (const auto* sun = std::get_if<oc::Sun>(&command)) {
      reply = apply_sun(*sun);
    } else if (const auto* clear = std::get_if<oc::Clear>(&command)) {
      reply = apply_clear(*clear);
    } else if (const auto* on = std::get_if<oc::Preview>(&command)) {
      reply = apply_preview(*on);
    } else if (const auto* fade = std::get_if<oc::Fade>(&command)) {
      reply = apply_fade(*fade);
    } else if (const auto* blackout = std::get_if<oc::Blackout>(&command)) {
      reply = apply_blackout(*blackout);
    } else if (!setup_.clock) {
      if (!std::holds_alternative<oc::Status>(command))
        throw std::invalid_argument(cat(describe(command),
                                        ": no show is playing (the default show has no clock: start "
                                        "the master with --show FILE for play, pause, seek, rate and loop)"));
      reply = cat("default show at frame ", master_.barrier_frame());
    } else {
      if (const auto* seek = std::get_if<oc::Seek>(&command); seek && seek->seconds > setup_.clock->duration_s())
        throw std::invalid_argument(cat("command: /seconds = ", seek->seconds, ": must be in [0, ",
                                        setup_.clock->duration_s(), "] s (the show's duration)"));
      // The clock's own words: "seek 12.5", "loop on".
      reply = apply_to_show(describe(command));
    }
    spdlog::info("master: operator ({}): {} → {}", source, core::escaped(describe(command)), core::escaped(reply));
    return reply;
  } catch (const std::exception& e) {
    spdlog::info("master: operator ({}): {} refused: {}", source, core::escaped(describe(command)),
                 core::escaped(e.what()));
    throw;
  }
}

std::string OperatorDesk::apply_to_show(const std::string& line) {
  if (setup_.chase) return apply_to_chase(line);
  if (line.rfind("timecode ", 0) == 0) throw std::invalid_argument(cat("'", line, "': ", kNoChase));
  return setup_.clock->apply_command(line);
}

std::string OperatorDesk::apply_to_chase(const std::string& line) {
  show::TimecodeChase& chase = *setup_.chase;
  const show::TimecodeRate rate = setup_.show->timecode()->rate;
  const std::string start = show::format_timecode(show::timecode_at_seconds(chase.settings().offset_s, rate), rate);
  if (line == "play") {
    chase.resume();
    return cat("chasing the house's timecode from ", start, " (", show::to_string(rate), " fps)");
  }
  if (line == "status") {
    const FrameState* latest = master_.latest_frame();
    return cat("chasing timecode, show time 0 at ", start, ": show time ",
               fmt::format("{:.3f}", latest != nullptr ? latest->show_time_s : 0.0), " s");
  }
  if (line.rfind("timecode offset ", 0) == 0) {
    const show::Timecode at = show::parse_timecode(line.substr(16), rate);  // throws std::invalid_argument
    chase.set_offset_s(show::timecode_seconds(at, rate));
    return cat("show time 0 at ", show::format_timecode(at, rate), " from the next frame on");
  }
  throw std::invalid_argument(cat("'", line,
                                  "': the show follows the house's timecode (pause, seek, rate and loop are its); "
                                  "'play' resumes a stopped chase, 'timecode offset hh:mm:ss:ff' moves the show's "
                                  "start, 'status' says where it is"));
}

/// An operator's `sun` (docs/operator.md, "Sun"): the show's sun replaced from the next frame on.
std::string OperatorDesk::apply_sun(const operator_command::Sun& sun) {
  if (setup_.feed) throw std::invalid_argument(cat(describe(sun), ": the frames come from an offline render's feed"));
  const scene::SkyAngles angles = sun_.set(sun, master_.latest_frame());
  return fmt::format("sun at elevation {}°, azimuth {}° from the next frame on, until cleared", angles.elevation_deg,
                     angles.azimuth_deg);
}

/// An operator's `preview`: the nodes send thumbnails with their RenderDone
/// (every preview_interval_frames() frames) while it is on, never while off.
std::string OperatorDesk::apply_preview(const operator_command::Preview& on) {
  if (!preview_)
    throw std::invalid_argument(
        "preview: the dome preview is served at /api/preview: start the master with --operator-port");
  preview_on_ = on.on;
  if (!on.on) {
    preview_->clear();
    return "dome preview off: the nodes send no thumbnails";
  }
  const std::uint64_t every = preview_interval_frames();
  return cat("dome preview on: every node sends a thumbnail of each output every ",
             every == 1 ? std::string("frame") : cat(every, " frames"), " (",
             preview_->layout() == DomePreview::Layout::dome ? "placed in the dome master" : "in a grid", ", ",
             preview_->width_px(), "x", preview_->height_px(), " px at /api/preview)");
}

/// An operator's `clear`: the show's (or scene's) own sun, exposure or atmosphere again.
std::string OperatorDesk::apply_clear(const operator_command::Clear& clear) {
  if (clear.what == operator_command::Clear::What::atmosphere) return master_.clear_atmosphere(clear.body);
  if (clear.what == operator_command::Clear::What::exposure) {
    exposure_.reset();
    return "the show's own exposure from the next frame on";
  }
  sun_.clear();
  return setup_.show ? "the show's sun track from the next frame on" : "the default show's sun from the next frame on";
}

std::uint64_t OperatorDesk::next_frame() const {
  const FrameState* latest = master_.latest_frame();
  return latest ? latest->frame + 1 : master_.barrier_frame();
}

/// An operator's `fade` (docs/operator.md, "Fades"): from the next frame on, on every node.
std::string OperatorDesk::apply_fade(const operator_command::Fade& fade) {
  if (setup_.feed) throw std::invalid_argument(cat(describe(fade), ": the frames come from an offline render's feed"));
  const std::uint64_t frame = next_frame();
  std::optional<glm::dvec3> colour;
  if (fade.colour) colour = glm::dvec3((*fade.colour)[0], (*fade.colour)[1], (*fade.colour)[2]);
  fade_.start(frame, fade.level, colour, fade.seconds);
  const glm::dvec3& c = fade_.target_colour();
  const std::string toward = fade.level == 0.0 ? std::string("the picture")
                                               : fmt::format("level {} of [{}, {}, {}]", fade.level, c.x, c.y, c.z);
  if (fade_.frames() == 0) return fmt::format("fade to {} at frame {}", toward, frame);
  return fmt::format("fade to {} over {} frames ({} s at {} Hz), frames {} to {}", toward, fade_.frames(), fade.seconds,
                     setup_.fps, frame, frame + fade_.frames() - 1);
}

/// An operator's `blackout`: black (or the picture again) at the next frame on every node.
std::string OperatorDesk::apply_blackout(const operator_command::Blackout& blackout) {
  if (setup_.feed)
    throw std::invalid_argument(cat(describe(blackout), ": the frames come from an offline render's feed"));
  const std::uint64_t frame = next_frame();
  if (blackout.on) {
    fade_.start(frame, 1.0, glm::dvec3(0.0), 0.0);
    return fmt::format("blackout from frame {} on every node", frame);
  }
  fade_.start(frame, 0.0, std::nullopt, 0.0);
  return fmt::format("blackout off: the picture from frame {} on", frame);
}

void OperatorDesk::hold_fade(const scene::FadeState& fade, std::uint64_t first_frame) {
  fade_.start(first_frame, fade.level, fade.colour, 0.0);
}

// ---------------------------------------------------------------------------- the frames

void OperatorDesk::shape(FrameState& next) const {
  if (exposure_) next.exposure = *exposure_;
  sun_.apply(next);
  fade_.apply(next.fade, next.frame);
}

void OperatorDesk::add_thumbnail(const std::string& node, const Thumbnail& thumbnail) {
  if (!preview_on_) return;  // sent before the preview was turned off
  preview_->add(node, thumbnail);
}

std::uint64_t OperatorDesk::preview_interval_frames() const {
  constexpr double kPreviewsPerSecond = 2.0;
  return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::lround(setup_.fps / kPreviewsPerSecond)));
}

// ---------------------------------------------------------------------------- status

nlohmann::json OperatorDesk::status() const {
  const FrameState* latest = master_.latest_frame();
  nlohmann::json status =
      master_.status(DeskStatus{exposure_, latest ? std::optional(sun_.angles_of(*latest)) : std::nullopt,
                                sun_.angles(), preview_ ? &*preview_ : nullptr, preview_on_});
  // The latest frame's fade and the operator's (docs/operator.md, "Status").
  const scene::FadeState shown = latest ? latest->fade : scene::FadeState{};
  const std::uint64_t frame = latest ? latest->frame : 0;
  status["fade"] = {{"level", shown.level},
                    {"colour", {shown.colour.x, shown.colour.y, shown.colour.z}},
                    {"operator", fade_.active(frame)},
                    {"target_level", fade_.target_level()},
                    {"frames_left", fade_.frames_left(frame)}};
  return status;
}

std::optional<std::string> OperatorDesk::preview_png() const {
  if (!preview_on_ || preview_->empty()) return std::nullopt;
  const DomePreview::Picture picture = preview_->compose();
  const std::vector<std::uint8_t> png = image::encode_png_rgb8(picture.width_px, picture.height_px, picture.rgb);
  return std::string(png.begin(), png.end());
}

// ---------------------------------------------------------------------------- where commands come from

void OperatorDesk::start_console(boost::asio::io_context& io, const OperatorConsoleOptions& console) {
  const auto command = [this](const OperatorCommand& c, const std::string& source) { return run(c, source); };
  if (console.http_port) {
    preview_.emplace(setup_.config, warp::load_viewport_config(setup_.config.viewports));
    http_.emplace(io,
                  OperatorHttpServer::Options{console.http_host, *console.http_port, console.token, console.http_names},
                  OperatorHttpServer::Handlers{[this] { return status(); }, command, [this] { return preview_png(); }});
    http_->start();
    spdlog::info("master: operator console at {} ({}; docs/operator.md)", http_->url(),
                 console.token ? "operator token required" : "loopback only, no token");
  }
  if (console.osc_port) {
    osc_.emplace(io, OscReceiver::Options{console.osc_host, *console.osc_port, console.osc_allow}, command);
    osc_->start();
    spdlog::info(
        "master: OSC on udp {}:{} (/zenith/play, /zenith/pause, /zenith/seek, /zenith/rate, /zenith/exposure, "
        "/zenith/sun/elevation, /zenith/sun/azimuth, /zenith/fade, /zenith/blackout, "
        "/zenith/atmosphere/BODY/PARAMETER; "
        "docs/operator.md)",
        console.osc_host, osc_->port());
  }
}

void OperatorDesk::start_inputs(boost::asio::io_context& io, bool console, std::optional<std::uint16_t> control_port) {
  input_.emplace(io, [this](std::string line) { return on_line(std::move(line)); });
  if (console) {
    input_->read_console();
    spdlog::info("master: console commands: play, pause, toggle, seek SECONDS, rate FACTOR, loop on|off, status, quit");
  }
  if (control_port) {
    input_->listen_for_control(*control_port);
    spdlog::info("master: control socket on 127.0.0.1:{} (zenith show control --port {} COMMAND)", *control_port,
                 *control_port);
  }
}

void OperatorDesk::close() {
  if (input_) input_->close();
  if (http_) http_->close();
  if (osc_) osc_->close();
}

}  // namespace zenith::cluster
