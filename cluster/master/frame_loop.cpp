#include "cluster/master/frame_loop.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include <boost/asio/post.hpp>

#include "cluster/protocol/datagram.h"
#include "core/strings.h"
#include "core/timing.h"
#include "scene/frame_scene.h"

namespace zenith::cluster {

using core::cat;
using core::ms_since;
using std::chrono::milliseconds;

FrameLoop::FrameLoop(boost::asio::io_context& io, Parts parts)
    : p_(std::move(parts)), barrier_timer_(io), frame_timer_(io), resend_timer_(io), pacer_(p_.play.fps) {}

void FrameLoop::retry_after(Clock::duration delay) {
  frame_timer_.expires_after(delay);
  frame_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) start_frame();
  });
}

void FrameLoop::on_node_left(std::uint32_t session) {
  if (p_.barrier.remove(session) && p_.barrier.complete()) complete_frame();
}

void FrameLoop::stop() {
  barrier_timer_.cancel();
  frame_timer_.cancel();
  resend_timer_.cancel();
  if (p_.options.paced && p_.progress.presented > 0)
    spdlog::info(
        "master: pacing at {} Hz: {} frames presented, {} more than a period after they were due (the warm-up "
        "frame 0 not counted), the schedule moved {} time{}",
        p_.play.fps, p_.progress.presented, late_frames_, pacer_.slips(), pacer_.slips() == 1 ? "" : "s");
}

void FrameLoop::maybe_start() {
  if (p_.progress.started || p_.progress.stopping) return;
  if (!p_.tables.may_start() && !p_.options.takeover) return;
  if (!waiting_since_) waiting_since_ = Clock::now();
  const std::size_t ready = p_.sessions.ready_count();
  const bool waited = ms_since(*waiting_since_) >= p_.options.wait_for_nodes_ms;
  if (ready == p_.options.config.nodes.size() || (waited && ready > 0)) {
    p_.progress.started = true;
    spdlog::info("master: starting the show with {} of {} node{}{}", ready, p_.options.config.nodes.size(),
                 p_.options.config.nodes.size() == 1 ? "" : "s",
                 p_.options.frames ? cat(", ", p_.options.frames, " frames") : std::string(", until stopped"));
    start_frame();
  } else if (waited && !waiting_logged_) {
    waiting_logged_ = true;
    spdlog::warn("master: no node is ready after {} ms; still waiting", p_.options.wait_for_nodes_ms);
  }
}

/// The next frame of the feed, the show or the default show; false when there is none yet (or no more).
bool FrameLoop::next_frame(FrameState& next) {
  if (p_.options.feed) {
    switch (p_.options.feed->pop(next)) {
      case FrameFeed::Next::finished: p_.stop("every frame of the feed was presented"); return false;
      case FrameFeed::Next::wait: retry_after(milliseconds(2)); return false;
      case FrameFeed::Next::frame: return true;
    }
  }
  const std::uint64_t frame = p_.barrier.frame();
  if (p_.play.timecode) {
    // The frame's moment: its due time on the schedule, else (under the barrier) now.
    const Clock::time_point moment = schedule_started_ ? pacer_.due(p_.progress.presented) : Clock::now();
    next = p_.play.show->state_at(chased_show_time(moment), frame, p_.play.render_flags);
    p_.desk.shape(next);
    return true;
  }
  next = p_.play.show ? p_.play.show->state_at(p_.play.clock->next_frame_time_s(), frame, p_.play.render_flags)
                      : scene::default_show_frame(p_.play.scene, frame, p_.options.sun_step_deg,
                                                  p_.tables.tables().current(), p_.play.render_flags);
  if (!p_.play.show) next.show_time_s = static_cast<double>(frame) / p_.play.fps;  // the live session's clock
  p_.desk.shape(next);
  return true;
}

double FrameLoop::chased_show_time(Clock::time_point moment) {
  show::TimecodeChase& chase = p_.play.timecode->chase;
  p_.play.timecode->take_frames();
  const show::ChasePosition before = p_.play.chased;
  const auto seconds = [](Clock::time_point t) { return std::chrono::duration<double>(t.time_since_epoch()).count(); };
  const show::ChasePosition& now = p_.play.chased = chase.position(seconds(moment), seconds(Clock::now()));
  const std::string label = now.last ? show::format_timecode(*now.last, now.rate) : std::string("none");
  if (now.state != before.state)
    spdlog::info("master: timecode {} (last frame {}, show time {:.3f} s{})", show::to_string(now.state), label,
                 now.show_time_s,
                 now.state == show::ChaseState::locked ? fmt::format(", drift {:+.0f} ppm", now.drift_ppm) : "");
  if (now.locates != before.locates)
    spdlog::info("master: timecode located to {}: show time {:.3f} s", label, now.show_time_s);
  if (now.before_start && !before.before_start)
    spdlog::warn("master: timecode {} is before the show's start: the show holds at its start", label);
  return now.show_time_s;
}

std::optional<FrameState> FrameLoop::frame_for(const std::vector<std::uint32_t>& participants,
                                               const std::vector<std::uint32_t>& holders) {
  if (participants.empty()) {
    if (!waiting_logged_) spdlog::warn("master: no node is ready for frame {}; waiting", p_.barrier.frame());
    waiting_logged_ = true;
    retry_after(milliseconds(20));
    return std::nullopt;
  }
  waiting_logged_ = false;
  p_.tables.maybe_start_switch();
  if (!held_frame_) {
    FrameState next;
    if (!next_frame(next)) return std::nullopt;
    held_frame_ = std::move(next);
    held_since_ = Clock::now();
    held_logged_ = false;
  }
  if (!p_.tables.participants_hold(*held_frame_, holders, !held_logged_)) {
    held_logged_ = true;
    retry_after(milliseconds(20));
    return std::nullopt;
  }
  if (held_logged_) {
    spdlog::info("master: frame {} goes on after waiting {:.1f} s for its tables", held_frame_->frame,
                 ms_since(held_since_) / 1000.0);
    // Paced: the frames after the wait keep the frame rate instead of
    // catching up on the time spent waiting.
    pacer_.hold(Clock::now() - held_since_);
  }
  FrameState state = std::move(*held_frame_);
  held_frame_.reset();
  if (p_.play.show && !p_.options.feed) p_.tables.apply_overrides(state);
  return state;
}

void FrameLoop::start_frame() {
  if (p_.progress.stopping) return;
  if (schedule_started_) return schedule_tick();
  const std::vector<std::uint32_t> participants = p_.barrier.participants_among(p_.sessions.ready_ids());
  std::optional<FrameState> next = frame_for(participants, participants);
  if (!next) return;
  FrameState& state = p_.progress.in_flight;
  state = std::move(*next);
  const std::uint64_t frame = p_.options.feed ? state.frame : p_.barrier.frame();
  auto encoded = std::make_shared<const std::vector<std::uint8_t>>(encode(state));
  if (p_.desk.wants_preview(frame)) {  // before the FrameState it names
    auto request =
        std::make_shared<const std::vector<std::uint8_t>>(encode(PreviewRequest{frame, kMaxThumbnailEdgePx}));
    for (const std::uint32_t id : participants) p_.sessions.find(id)->connection->send_encoded(request);
  }
  for (const std::uint32_t id : participants) p_.sessions.find(id)->connection->send_encoded(encoded);
  p_.sessions.send_to_standbys(encoded);
  p_.barrier.begin(frame, participants);
  frame_started_ = Clock::now();
  spdlog::debug("master: frame {} sent to {} node{}", frame, participants.size(), participants.size() == 1 ? "" : "s");
  barrier_timer_.expires_after(milliseconds(p_.options.config.barrier_timeout_ms));
  barrier_timer_.async_wait([this, frame](const boost::system::error_code& ec) {
    if (!ec && p_.barrier.in_flight() && p_.barrier.frame() == frame) on_barrier_timeout();
  });
}

void FrameLoop::on_render_done(const NodeSession& s, const RenderDone& done) {
  note_presents(s, done);
  if (schedule_started_ && done.frame > 0) {  // scheduled: a report, nothing waits for it
    p_.statistics.rendered(s.name, done.render_ms, false);
    if (const std::uint64_t missed = p_.statistics.missed(s.name, done.missed_frames); missed > 0)
      spdlog::warn(
          "master: node '{}' missed {} scheduled frame{} (they reached it too late, or not at all); {} so "
          "far",
          s.name, missed, missed == 1 ? "" : "s", p_.statistics.of(s.name).missed_frames);
    return;
  }
  switch (p_.barrier.on_render_done(s.id, done.frame)) {
    case FrameBarrier::Report::counted:
      p_.statistics.rendered(s.name, done.render_ms, p_.barrier.complete() && p_.barrier.participant_count() > 1);
      if (p_.barrier.complete()) complete_frame();
      return;
    case FrameBarrier::Report::rejoins:
      p_.statistics.rendered(s.name, done.render_ms, false);
      p_.statistics.rejoined(s.name);
      spdlog::info("master: node '{}' finished frame {} late; it rejoins the barrier at frame {}", s.name, done.frame,
                   p_.barrier.next_boundary());
      return;
    case FrameBarrier::Report::ignored_lagging: return;
    case FrameBarrier::Report::ignored:
      spdlog::debug("master: ignoring RenderDone {} from node '{}' (frame {} in flight)", done.frame, s.name,
                    p_.barrier.frame());
      return;
  }
}

/// The node's late presents (a missed vblank), in the status and the log: a
/// line at the first, then at most one a second per node with the total.
void FrameLoop::note_presents(const NodeSession& s, const RenderDone& done) {
  const std::uint64_t late = p_.statistics.presented(s.name, done.presents, done.late_presents, done.present_ms);
  if (late == 0) return;
  const auto now = Clock::now();
  const auto logged = late_logged_.find(s.name);
  if (logged != late_logged_.end() && now - logged->second < std::chrono::seconds(1)) return;
  late_logged_[s.name] = now;
  const NodeStatistics::Counts c = p_.statistics.of(s.name);
  spdlog::warn(
      "master: node '{}' presented late (a missed vblank): {} of its {} presents so far (last {:.1f} ms "
      "from Present to swap)",
      s.name, c.late_presents, c.presents, done.present_ms);
}

void FrameLoop::on_barrier_timeout() {
  for (const std::uint32_t id : p_.barrier.drop_unfinished())
    if (const NodeSession* s = p_.sessions.find(id)) {
      p_.statistics.dropped(s->name);
      spdlog::warn(
          "master: node '{}' missed the barrier of frame {} (no RenderDone within {} ms): dropped from the "
          "barrier; the show goes on without it",
          s->name, p_.barrier.frame(), p_.options.config.barrier_timeout_ms);
    }
  complete_frame();
}

void FrameLoop::complete_frame() {
  barrier_timer_.cancel();
  // Stopping (the operator quit, a signal): the frames released before are
  // presented by every node — their Presents went out before the Goodbye —
  // and the frame in flight is not released, neither presented nor recorded,
  // so that the recording holds exactly the frames the nodes showed.
  if (p_.progress.stopping) return;
  const FrameBarrier::Release release = p_.barrier.release();
  const std::uint64_t frame = release.frame;
  auto encoded = std::make_shared<const std::vector<std::uint8_t>>(encode(Present{frame}));
  for (const std::uint32_t id : release.present_to)
    if (NodeSession* s = p_.sessions.find(id)) s->connection->send_encoded(encoded);
  p_.sessions.send_to_standbys(encoded);
  spdlog::info("master: present frame {} on {} node{} ({:.1f} ms)", frame, release.present_to.size(),
               release.present_to.size() == 1 ? "" : "s", ms_since(frame_started_));
  if (p_.play.recorder) {
    for (const AtmosphereTableRef& r : p_.progress.in_flight.atmospheres)
      p_.play.recorder->add_version(p_.tables.tables().version(r.table_hash));
    p_.play.recorder->record(p_.progress.in_flight);
  }
  if (p_.options.feed) p_.options.feed->presented(frame);
  if (p_.options.paced && p_.progress.presented == 0 && scheduled()) {
    // Frame 0 warmed the nodes up; frame 1 is due a full lookahead from now,
    // so that it too reaches every node that far ahead of its moment.
    const int lookahead = p_.options.config.lookahead_frames;
    pacer_.start(Clock::now() + (lookahead - 1) * pacer_.period());
    schedule_started_ = true;
    spdlog::info(
        "master: warm-up frame {} presented after {:.1f} ms; scheduled frames at {} Hz from now, each sent {} "
        "frame{} ({:.1f} ms) ahead of its moment",
        frame, ms_since(frame_started_), p_.play.fps, lookahead, lookahead == 1 ? "" : "s",
        lookahead * std::chrono::duration<double, std::milli>(pacer_.period()).count());
  } else if (p_.options.paced && p_.progress.presented == 0) {
    // Frame 0 warmed the nodes up (its programs, buffers, uploads and first
    // swap, however long they took): the schedule starts at its Present.
    pacer_.start(Clock::now());
    spdlog::info("master: warm-up frame {} presented after {:.1f} ms; the {} Hz schedule starts now", frame,
                 ms_since(frame_started_), p_.play.fps);
  } else if (p_.options.paced && pacer_.late(p_.progress.presented, Clock::now())) {
    ++late_frames_;  // later than a period after it was due: the projectors showed the last frame twice
  }
  const std::uint64_t presented = ++p_.progress.presented;
  if (p_.options.frames != 0 && presented >= p_.options.frames)
    return p_.stop(cat("show finished after ", presented, " frames"));
  if (p_.play.clock && p_.play.clock->finished() && !p_.options.feed)
    return p_.stop(cat("show '", p_.play.show->name(), "' finished after ", presented, " frames"));
  if (!p_.options.paced) {
    boost::asio::post(frame_timer_.get_executor(), [this] { start_frame(); });
    return;
  }
  if (schedule_started_) return after_tick(false);  // frame 1 goes out a lookahead before its moment
  // Pace: frame N starts no earlier than show start + N / rate (frame_pacer.h).
  const std::uint64_t slips = pacer_.slips();
  const Clock::duration wait = pacer_.wait_before(presented, Clock::now());
  const bool slipped = pacer_.slips() != slips;
  if (slipped && (slips == 0 || presented >= last_slip_logged_ + static_cast<std::uint64_t>(p_.play.fps))) {
    last_slip_logged_ = presented;  // the first slip, then at most one line a second
    spdlog::info(
        "master: frame {} is more than a period behind the {} Hz schedule (the slowest node, or the tables): "
        "the schedule moves on instead of bursting frames ({} time{} so far)",
        presented, p_.play.fps, pacer_.slips(), pacer_.slips() == 1 ? "" : "s");
  }
  retry_after(wait);
}

// ---- scheduled frames -----------------------------------------------------------

namespace {
std::uint64_t ns_of(FrameLoop::Clock::time_point t) {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count());
}
}  // namespace

void FrameLoop::schedule_tick() {
  const std::vector<std::uint32_t> nodes = p_.sessions.ready_ids();
  // A frame waits for its tables on the nodes that can be reached, not on
  // one cut off: that node skips the frames whose tables it lacks until they
  // arrive, as a late joiner does, and the dome goes on.
  std::vector<std::uint32_t> reachable;
  for (const std::uint32_t id : nodes)
    if (const NodeSession* s = p_.sessions.find(id); s && !s->link_quiet) reachable.push_back(id);
  std::optional<FrameState> next = frame_for(nodes, reachable);
  if (!next) return;
  const FrameState state = std::move(*next);
  const std::uint64_t frame = p_.barrier.frame();
  const std::uint64_t n = p_.progress.presented;  // frames since the start: frame 0 was the warm-up
  const auto period_ns = static_cast<std::uint64_t>(std::chrono::nanoseconds(pacer_.period()).count());
  const FrameSchedule when{frame, ns_of(pacer_.due(n)), period_ns};

  resend_ahead(nodes);
  const auto now = Clock::now();
  if (p_.desk.wants_preview(frame)) {  // before the frame it names
    auto request =
        std::make_shared<const std::vector<std::uint8_t>>(encode(PreviewRequest{frame, kMaxThumbnailEdgePx}));
    for (const std::uint32_t id : nodes) p_.sessions.find(id)->connection->send_encoded(request);
  }
  send_scheduled(state, when, nodes);
  ahead_.push_back({when, state});
  resend_between_ticks();

  // A standby follows every frame as under the barrier (its takeover goes on from the last one sent).
  p_.sessions.send_to_standbys(std::make_shared<const std::vector<std::uint8_t>>(encode(state)));
  p_.sessions.send_to_standbys(std::make_shared<const std::vector<std::uint8_t>>(encode(Present{frame})));
  if (p_.play.recorder) {
    for (const AtmosphereTableRef& r : state.atmospheres)
      p_.play.recorder->add_version(p_.tables.tables().version(r.table_hash));
    p_.play.recorder->record(state);
  }
  p_.progress.in_flight = state;
  p_.barrier.start_at(frame + 1);
  const std::uint64_t sent = ++p_.progress.presented;
  spdlog::debug("master: frame {} scheduled on {} node{} for {:.1f} ms from now", frame, nodes.size(),
                nodes.size() == 1 ? "" : "s",
                static_cast<double>(static_cast<std::int64_t>(when.present_at_ns - ns_of(now))) / 1e6);
  const bool last =
      (p_.options.frames != 0 && sent >= p_.options.frames) || (p_.play.clock && p_.play.clock->finished());
  after_tick(last);
}

void FrameLoop::resend_ahead(const std::vector<std::uint32_t>& nodes) {
  // A lost datagram costs nothing while one of its copies arrives.
  const auto now = Clock::now();
  while (!ahead_.empty() && ahead_.front().when.present_at_ns <= ns_of(now)) ahead_.pop_front();
  for (const Scheduled& a : ahead_)
    for (const std::uint32_t id : nodes)
      if (const NodeSession* s = p_.sessions.find(id); s && p_.datagrams.reaches(*s, now))
        p_.datagrams.send(*s, std::make_shared<const std::vector<std::uint8_t>>(
                                  seal_datagram(*s->datagram_key, s->id, std::vector<Message>{a.when, a.state})));
}

void FrameLoop::send_scheduled(const FrameState& state, const FrameSchedule& when,
                               const std::vector<std::uint32_t>& nodes) {
  const auto now = Clock::now();
  std::shared_ptr<const std::vector<std::uint8_t>> tcp_schedule, tcp_state;
  for (const std::uint32_t id : nodes) {
    NodeSession* s = p_.sessions.find(id);
    if (s == nullptr) continue;
    if (p_.datagrams.reaches(*s, now)) {
      p_.datagrams.send(*s, std::make_shared<const std::vector<std::uint8_t>>(
                                seal_datagram(*s->datagram_key, s->id, std::vector<Message>{when, state})));
      continue;
    }
    // Not heard on UDP (a firewall, a node just welcomed): TCP, once.
    if (!tcp_state) {
      tcp_schedule = std::make_shared<const std::vector<std::uint8_t>>(encode(when));
      tcp_state = std::make_shared<const std::vector<std::uint8_t>>(encode(state));
    }
    s->connection->send_encoded(tcp_schedule);
    s->connection->send_encoded(tcp_state);
  }
}

void FrameLoop::after_tick(bool last_frame) {
  const std::uint64_t sent = p_.progress.presented;
  if (last_frame) {
    const std::string reason = p_.options.frames != 0 && sent >= p_.options.frames
                                   ? cat("show finished after ", sent, " frames")
                                   : cat("show '", p_.play.show->name(), "' finished after ", sent, " frames");
    return tail_tick(sent, reason);
  }
  // The tick of frame n: lookahead periods before its moment.
  const Clock::duration lookahead = p_.options.config.lookahead_frames * pacer_.period();
  const std::uint64_t slips = pacer_.slips();
  const Clock::duration wait = pacer_.wait_before(sent, Clock::now() + lookahead);
  if (pacer_.slips() != slips && (slips == 0 || sent >= last_slip_logged_ + static_cast<std::uint64_t>(p_.play.fps))) {
    last_slip_logged_ = sent;
    spdlog::info(
        "master: frame {} could not be sent {} frame{} ahead of its moment (the master was held up): the schedule "
        "moves on ({} time{} so far)",
        sent, p_.options.config.lookahead_frames, p_.options.config.lookahead_frames == 1 ? "" : "s", pacer_.slips(),
        pacer_.slips() == 1 ? "" : "s");
  }
  retry_after(wait);
}

void FrameLoop::tail_tick(std::uint64_t k, const std::string& reason) {
  const std::uint64_t sent = p_.progress.presented;
  const Clock::time_point last_moment = pacer_.due(sent - 1);
  const Clock::time_point tick = pacer_.due(k) - p_.options.config.lookahead_frames * pacer_.period();
  if (tick >= last_moment) {
    // Stop once the nodes have presented the last frame: its moment and a period more.
    frame_timer_.expires_at(last_moment + pacer_.period());
    frame_timer_.async_wait([this, reason](const boost::system::error_code& ec) {
      if (!ec) p_.stop(reason);
    });
    return;
  }
  frame_timer_.expires_at(tick);
  frame_timer_.async_wait([this, k, reason](const boost::system::error_code& ec) {
    if (ec) return;
    resend_ahead(p_.sessions.ready_ids());
    resend_between_ticks();
    tail_tick(k + 1, reason);
  });
}

void FrameLoop::resend_between_ticks() {
  resend_timer_.expires_after(pacer_.period() / 2);
  resend_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) resend_ahead(p_.sessions.ready_ids());
  });
}

}  // namespace zenith::cluster
