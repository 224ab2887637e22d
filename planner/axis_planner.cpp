#include "planner/axis_planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

namespace stepmod::planner {

namespace {

Nanos to_ns(double seconds) noexcept {
  return std::llround(seconds * 1e9);
}

// While a cut request is open, the planner looks for the pulse thread's answer this often.
constexpr Nanos kCutPollNs = 20 * kNsPerUs;

}  // namespace

AxisPlanner::AxisPlanner(const PlannerAxis& axis, const PlannerOptions& options) noexcept
    : control_(axis.control),
      feedback_(axis.feedback),
      timing_(axis.timing),
      opt_(options),
      out_(axis.edges, axis.timing) {}

Nanos AxisPlanner::slip() const noexcept {
  if (feedback_ == nullptr || m_.epoch == 0) return 0;
  const std::uint64_t s = feedback_->slip.load(std::memory_order_acquire);
  // Another motion's (the pulse thread has not reached this one yet): none yet.
  if (rt::packed_epoch(s) != m_.epoch) return 0;
  return static_cast<Nanos>(rt::packed_value(s)) * kNsPerUs;
}

void AxisPlanner::publish_motion(const Motion& m, double vs) noexcept {
  if (control_ == nullptr) return;
  control_->motion_group.store(rt::pack_epoch(m.epoch, m.group), std::memory_order_release);
  control_->motion_vs.store(rt::pack_epoch(m.epoch, rt::vs_interval_ns(vs)),
                            std::memory_order_release);
}

double AxisPlanner::frontier_speed() const noexcept {
  if (!m_.active) return 0.0;
  if (m_.follow) return follow_.speed();
  if (m_.path) return path_.vector_speed_at(m_.tk);  // the path's vector speed
  return profile_.velocity_at(m_.tk);
}

std::int64_t AxisPlanner::planned_steps_at(Nanos t) const noexcept {
  return out_.steps_at(t, m_.k);
}

void AxisPlanner::apply(const Command& c, Nanos now) noexcept {
  check_abort();
  if (c.starts_motion()) {
    resolve_cut(true);
    if (prepare_start(c, now)) launch(earliest_origin(now));
    return;
  }
  now -= slip();  // from here on: the running motion's time base
  now_ = std::max(now_, now);
  resolve_cut(true);
  const std::uint32_t epoch = c.epoch;
  std::visit(
      [&](const auto& p) {
        using P = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<P, FollowUpdate>) {
          follow_update(epoch, p.spec);
        } else if constexpr (std::is_same_v<P, SpeedChange>) {
          change_speed(epoch, p);
        } else if constexpr (std::is_same_v<P, StopSpec>) {
          if (follows_path(epoch)) {
            hold_path(std::max(now + opt_.start_delay_ns, path_frontier()), p.ramp);
          } else {
            stop(epoch, p);
          }
        } else if constexpr (std::is_same_v<P, PathHold>) {
          // Alone (the Planner holds every axis of the path together).
          if (follows_path(epoch)) {
            hold_path(std::max(now + opt_.start_delay_ns, path_frontier()), p.ramp);
          }
        } else if constexpr (std::is_same_v<P, StopAfterSpec>) {
          stop_after(epoch, p);
        } else if constexpr (std::is_same_v<P, AbortSpec>) {
          if (epoch == last_motion_epoch_) abort_last_motion();
        } else if constexpr (std::is_same_v<P, GpoSpec>) {
          out_.gpo(p.level, now);
        } else if constexpr (std::is_same_v<P, PulseFormatSpec>) {
          out_.pulse_format(p.step_dir, now, m_.active);
        }
      },
      c.what);
}

void AxisPlanner::check_abort() noexcept {
  if (control_ == nullptr) return;
  const std::uint32_t a = control_->abort_epoch.load(std::memory_order_acquire);
  if (a == seen_abort_) return;
  seen_abort_ = a;
  if (last_motion_epoch_ != 0 && last_motion_epoch_ <= a) {
    resolve_cut(true);
    abort_last_motion();
  }
}

void AxisPlanner::abort_last_motion() noexcept {
  if (last_motion_aborted_ || last_motion_epoch_ == 0) return;
  last_motion_aborted_ = true;
  discard_path();
  m_.active = false;
  out_.abort(last_motion_epoch_);
}

bool AxisPlanner::prepare_start(const Command& c, Nanos now) noexcept {
  check_abort();
  now_ = std::max(now_, now - slip());
  resolve_cut(true);
  if (control_ != nullptr && c.epoch <= control_->abort_epoch.load(std::memory_order_acquire)) {
    return false;  // aborted before it started
  }
  if (c.epoch <= last_motion_epoch_) return false;  // stale or repeated
  // A new motion replaces one that is still being planned: that one ends on its newest step.
  if (m_.active) finish_at_frontier();
  const bool path = c.kind() == CommandKind::kPath || c.kind() == CommandKind::kPathResume;
  if (!path) discard_path();

  Motion m;
  m.active = true;
  m.held = true;
  m.epoch = c.epoch;
  m.group = c.group.id;
  double vs = 0.0;
  if (const auto* follow = std::get_if<FollowStart>(&c.what)) {
    // Steps and their direction come from follow_step as the target moves.
    m.dir = follow->spec.target < 0 ? Direction::kCcw : Direction::kCw;
    m.end = kEndless;
    m.follow = true;
    follow_.start(follow->spec);
    vs = follow->spec.vs;
  } else if (path) {
    prepare_path(c, m);
    vs = path_.vs();
  } else {
    ProfileSource::Start st;
    if (const auto* move = std::get_if<MoveSpec>(&c.what)) {
      st = profile_.start(*move);
    } else if (const auto* run = std::get_if<RunSpec>(&c.what)) {
      st = profile_.start(*run);
    } else {
      st = profile_.start(blend_);
    }
    m.dir = st.dir;
    m.end = st.end;
    vs = profile_.vs();
  }
  publish_motion(m, vs);  // before any of its edges is pushed
  out_.begin(c.epoch, m.dir);
  // Step/direction: the direction line must settle dir_setup_ns before the first step. CW/CCW:
  // the CCW pulse line rests low. Only a change (or an unknown level) costs an edge. (A follow
  // motion writes it with its first step: follow_step.)
  if (!m.follow && m.end > 0 && out_.direction_pending()) {
    const Nanos first = to_ns(m.path ? path_.peek().t : profile_.first_step_time(m.end));
    m.dir_edge = true;
    m.dir_shift = std::max<Nanos>(0, timing_.dir_setup_ns - first);
  }

  last_motion_epoch_ = c.epoch;
  last_motion_aborted_ = false;
  m_ = m;
  return true;
}

Nanos AxisPlanner::earliest_origin(Nanos now) const noexcept {
  return std::max(now + opt_.start_delay_ns, out_.last_t()) + m_.dir_shift;
}

void AxisPlanner::launch(Nanos origin) noexcept {
  if (!m_.active || !m_.held) return;  // aborted while it waited for its group
  m_.held = false;
  m_.origin = origin;
  m_.tk_ns = origin;
  if (m_.end <= 0) {
    finish_at_frontier();  // nothing to move: one marker edge tells the pulse thread it ended
    return;
  }
  if (!m_.dir_edge) return;
  out_.direction(origin - m_.dir_shift, m_.path ? path_.first_phase() : profile_.first_phase());
}

void AxisPlanner::finish_at_frontier() noexcept {
  if (!m_.active) return;
  if (m_.follow) {
    follow_finish();
    return;
  }
  m_.active = false;
  out_.end(m_.tk_ns);
}

void AxisPlanner::replan_to_end(std::int64_t end, const Ramp& ramp, bool exact_ramp) noexcept {
  profile_.replan_to_end(m_.k, m_.tk, end, ramp, exact_ramp);
  m_.end = end;
}

void AxisPlanner::prepare_path(const Command& c, Motion& m) noexcept {
  m.path = true;
  PathSource::Start st{Direction::kCw, 0};
  if (const auto* ps = std::get_if<PathStart>(&c.what)) {
    discard_path();  // a new path replaces a held one
    st = path_.start(ps->spec, ps->coordinate);
    path_state_ = PathState::kRunning;
    path_id_ = c.group.id;
  } else {
    const auto& r = std::get<PathResume>(c.what);
    const bool resumable = path_state_ == PathState::kHeld &&
                           (path_id_ == 0 || (book_ != nullptr && book_->held == path_id_));
    if (resumable) {
      st = path_.resume(r.vp, r.accel, r.decel);
      path_state_ = PathState::kRunning;
      path_id_ = c.group.id;
    } else {
      discard_path();  // ends at once, no step
    }
  }
  m.dir = st.dir;
  m.end = st.end;
}

void AxisPlanner::discard_path() noexcept {
  if (path_state_ == PathState::kNone) return;
  if (book_ != nullptr && path_id_ != 0) {
    if (book_->held == path_id_) book_->held = 0;
    book_->broken = path_id_;
  }
  path_state_ = PathState::kNone;
}

void AxisPlanner::hold_path(Nanos t, const Ramp& ramp) noexcept {
  if (path_state_ == PathState::kNone) return;
  path_state_ = PathState::kHeld;
  const std::int64_t left = path_.hold(static_cast<double>(t - m_.origin) * 1e-9, ramp);
  if (!m_.active || !m_.path || m_.held) return;  // its steps are all made: only the point moved
  m_.end = m_.k + left;
  if (left == 0) finish_at_frontier();
}

void AxisPlanner::change_speed(std::uint32_t epoch, const SpeedChange& c) noexcept {
  if (!m_.active || m_.held || m_.follow || m_.path || epoch != m_.epoch) return;
  if (!profile_.can_change_speed() || !(c.vp > 0.0)) return;
  profile_.change_speed(m_.k, m_.tk, c);
}

void AxisPlanner::stop(std::uint32_t epoch, const StopSpec& c) noexcept {
  if (!m_.active || epoch != m_.epoch) return;
  if (m_.follow) {
    // A follow motion keeps its own (decel) law: it ends once at rest on its target.
    follow_.finish();
    return;
  }
  if (c.trigger_t != kNoTrigger && request_cut(c)) return;
  stop_at_frontier(c.ramp);
}

void AxisPlanner::stop_at_frontier(const Ramp& ramp) noexcept {
  if (!m_.active) return;
  const std::int64_t end = profile_.stop_end(m_.k, m_.tk, ramp);
  if (end == m_.k) {
    // Nothing to ramp down: the step already planned is the last one (one step if none yet).
    if (m_.k == 0) {
      if (m_.end > 1) replan_to_end(1, ramp, true);
    } else if (m_.end > m_.k) {
      finish_at_frontier();
    }
    return;
  }
  if (end >= m_.end) return;  // the motion ends as soon anyway (e.g. already decelerating)
  replan_to_end(end, ramp, true);
}

bool AxisPlanner::request_cut(const StopSpec& c) noexcept {
  if (control_ == nullptr || m_.held || cut_.open || cut_epoch_ == m_.epoch) return false;
  // The trigger is a wall-clock time (an input edge's timestamp, a scan): on the motion's time
  // base it lies its slip earlier.
  const Nanos want = std::max(c.trigger_t - slip(), now_ + opt_.cut_margin_ns);
  const std::int64_t k = planned_steps_at(want);
  // Nothing planned after `want` (the frontier stop is as early), or no step before it yet.
  if (k < 1 || k >= m_.k || m_.k - k >= static_cast<std::int64_t>(EdgeEmitter::kHistory) - 1) {
    return false;
  }
  const Nanos t_c = out_.step_time(k);
  // A GPO edge queued after t_c would hold the replacement edges behind it in the ring.
  if (t_c < out_.nonmotion_t()) return false;
  const double t = static_cast<double>(t_c - m_.origin) * 1e-9;
  // Replanned after step k (a speed change): the profile at k is gone.
  if (t < profile_.start_time()) return false;
  if (profile_.stop_end(k, t, c.ramp) >= m_.end) return false;  // it ends as soon anyway
  if (!control_->cut.request(m_.epoch, t_c)) return false;
  cut_ = PendingCut{true, c.ramp, k, t_c};
  return true;
}

bool AxisPlanner::resolve_cut(bool now_or_never) noexcept {
  if (!cut_.open) return true;
  switch (control_->cut.poll()) {
    case rt::EdgeCut::Outcome::kAccepted:
      cut_.open = false;
      apply_cut();
      return true;
    case rt::EdgeCut::Outcome::kPending:
      if (!now_or_never) return false;
      if (!control_->cut.withdraw()) return resolve_cut(true);  // decided meanwhile
      break;
    case rt::EdgeCut::Outcome::kRefused:  // an edge after the cut had already run
    case rt::EdgeCut::Outcome::kNone:
      break;
  }
  cut_.open = false;
  stop_at_frontier(cut_.ramp);
  return true;
}

void AxisPlanner::apply_cut() noexcept {
  if (!m_.active) return;
  cut_epoch_ = m_.epoch;
  // Back to step k: the edges after it are replaced.
  const double t = static_cast<double>(cut_.t - m_.origin) * 1e-9;
  out_.cut(cut_.t, profile_.phase_at(t));
  m_.k = cut_.k;
  m_.tk = t;
  m_.tk_ns = cut_.t;
  const std::int64_t end = profile_.stop_end(cut_.k, t, cut_.ramp);
  if (end <= m_.k) {
    finish_at_frontier();
    return;
  }
  replan_to_end(end, cut_.ramp, true);
}

void AxisPlanner::stop_after(std::uint32_t epoch, const StopAfterSpec& c) noexcept {
  if (!m_.active || epoch != m_.epoch || m_.follow || m_.path) return;
  // Steps of this motion up to c.t, counting the ones already planned after it.
  // c.t is a wall-clock time (the registration input's edge): converted to the motion's time.
  const std::int64_t end = planned_steps_at(c.t - slip()) + std::max<std::int64_t>(c.steps, 0);
  if (end >= m_.end) return;  // already ends there or sooner
  if (end <= m_.k) {
    finish_at_frontier();  // the count was reached by steps already planned: end at once
    return;
  }
  // Digest 7.9 step 4: freeze the present speed, cruise, decelerate with the motion's decel.
  replan_to_end(end, profile_.decel(), false);
}

bool AxisPlanner::path_step_once(Nanos horizon) noexcept {
  Motion& m = m_;
  Nanos ns = m.origin + to_ns(path_.peek().t);
  if (ns < m.tk_ns) ns = m.tk_ns;
  if (ns > horizon) {
    // An axis that crawls near its coordinate's reversal may wait long for its next crossing:
    // planned now, that step could not be replanned by a hold any more.
    out_.end_pulse(ns);
    path_next_ns_ = ns;
    return false;
  }
  const std::int64_t k = m.k + 1;
  const PathSource::Step st = path_.take();
  if (st.dir != m.dir) {
    // The coordinate reversed (an arc's extreme): the open pulse ends, the direction line turns
    // and settles before this step.
    m.dir = st.dir;
    ns = out_.reverse(st.dir, ns, st.phase);
  }
  out_.step(ns, st.phase, k);
  m.k = k;
  m.tk = st.t;
  m.tk_ns = ns;
  if (k >= m.end) {
    out_.end(ns);
    m.active = false;
  }
  return true;
}

void AxisPlanner::step_once() noexcept {
  Motion& m = m_;
  const std::int64_t k = m.k + 1;
  auto [t, ph] = profile_.step(k, m.end);
  if (t < m.tk) t = m.tk;
  Nanos ns = m.origin + to_ns(t);
  if (ns < m.tk_ns) ns = m.tk_ns;
  out_.step(ns, ph, k);
  m.k = k;
  m.tk = t;
  m.tk_ns = ns;
  if (k >= m.end) {
    out_.end(ns);
    m.active = false;
  }
}

Nanos AxisPlanner::fill(Nanos now, Nanos s) noexcept {
  // The ring is kept filled a lookahead ahead on the motion's time base, and the time to come
  // back is a wall-clock time again.
  const Nanos next = fill_planned(now - s);
  return next >= std::numeric_limits<Nanos>::max() - s ? next : next + s;
}

Nanos AxisPlanner::fill_planned(Nanos now) noexcept {
  check_abort();
  now_ = std::max(now_, now);
  if (!resolve_cut(false)) {
    publish_refill(0);  // which edges to push is not known yet: they may come any time
    return now + kCutPollNs;
  }
  const Nanos horizon = now + opt_.lookahead_ns;
  out_.flush(horizon);
  while (m_.active && !m_.held && out_.staged_empty()) {
    if (m_.follow) {
      if (!follow_step()) break;  // at rest on the target: the next target wakes us
    } else if (m_.path) {
      if (!path_step_once(horizon)) break;  // its next step lies beyond the horizon
    } else {
      step_once();
    }
    out_.flush(horizon);
  }
  if (out_.staged_empty()) {
    if (m_.active && m_.path && !m_.held) {
      // The path's next step, left unplanned: plan it when half the lookahead is left before it.
      // A turn writes the direction line up to dir_setup_ns before that step (reverse()).
      const bool turns = path_.peek().dir != m_.dir;
      publish_refill(turns ? path_next_ns_ - timing_.dir_setup_ns : path_next_ns_);
      return std::max(now + kCutPollNs, path_next_ns_ - opt_.lookahead_ns / 2);
    }
    publish_refill(0);  // nothing planned ahead (idle, or a follow motion waiting for a target)
    return now + kIdleServiceInterval;
  }
  const Nanos head = out_.head_t();
  publish_refill(head);  // staged edges go out in time order: none before the head
  if (head > horizon) {
    // Come back when half the lookahead is left before it: refills happen in batches.
    return head - opt_.lookahead_ns / 2;
  }
  // Ring full: about half of what it holds has run by the midpoint to its newest edge.
  return now + std::max<Nanos>(10 * kNsPerUs, (out_.last_pushed_t() - now) / 2);
}

void AxisPlanner::publish_refill(Nanos t) noexcept {
  if (control_ != nullptr) control_->refill_at.store(t, std::memory_order_release);
}

void AxisPlanner::follow_update(std::uint32_t epoch, const FollowSpec& f) noexcept {
  if (!m_.active || !m_.follow || epoch != m_.epoch) return;
  follow_.update(f);
}

void AxisPlanner::follow_finish() noexcept {
  m_.active = false;
  // Every step's trailing edge is already staged: a marker edge (the direction line rewritten at
  // its present level) carries kLast so that the pulse thread reports the motion finished.
  out_.end(now_);
}

// A follow step: the servo decides it (planner/follow_servo.hpp), the emitter writes it.
bool AxisPlanner::follow_step() noexcept {
  FollowStep st;
  switch (follow_.next(m_.tk_ns, m_.k == 0, now_, opt_.start_delay_ns, timing_.step_pulse_ns, st)) {
    case FollowServo::Next::kWait:
      return false;
    case FollowServo::Next::kFinish:
      follow_finish();
      return true;
    case FollowServo::Next::kStep:
      break;
  }
  Nanos t = std::max(st.t, out_.last_t() + 1);
  if (st.from_rest || st.dir != sign(m_.dir) || m_.k == 0) {
    m_.dir = st.dir < 0 ? Direction::kCcw : Direction::kCw;
    out_.turn(m_.dir);
    if (out_.direction_pending()) {
      // Step/direction: the direction line settles dir_setup_ns before the step.
      const Nanos td = std::max(out_.last_t(), std::max(now_, t - timing_.dir_setup_ns));
      out_.direction(td, rt::Phase::kCruise);
      t = std::max(t, td + timing_.dir_setup_ns);
    }
  }
  const std::int64_t k = m_.k + 1;
  out_.pulse(t, st.phase, st.dir, st.width, k);
  m_.k = k;
  m_.tk_ns = t;
  follow_.taken(st);
  return true;
}

}  // namespace stepmod::planner
