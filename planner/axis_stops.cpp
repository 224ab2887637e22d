// AxisPlanner: controlled stops. A profile motion (ProfileSource) is replanned from a step: from
// its newest planned step (stop_at_frontier), from a registration count (stop_after), or from the
// step at a trigger time, for which the pulse thread must first agree to drop the queued edges
// after it (the cut handshake, rt/edge_cut.hpp). A path's stop is its hold (axis_path.cpp).
#include <algorithm>

#include "planner/axis_planner.hpp"

namespace stepmod::planner {

void AxisPlanner::replan_to_end(std::int64_t end, const Ramp& ramp, bool exact_ramp) noexcept {
  profile_.replan_to_end(m_.at.k, m_.at.tk, end, ramp, exact_ramp);
  m_.at.end = end;
}

void AxisPlanner::stop(std::uint32_t epoch, const StopSpec& c) noexcept {
  if (!m_.active || epoch != m_.epoch) return;
  // A follow motion keeps its own (decel) law: it ends once at rest on its target.
  if (source_->stop_by_own_law()) return;
  if (c.trigger_t != kNoTrigger && request_cut(c)) return;
  stop_at_frontier(c.ramp);
}

void AxisPlanner::stop_at_frontier(const Ramp& ramp) noexcept {
  if (!m_.active) return;
  const std::int64_t end = profile_.stop_end(m_.at.k, m_.at.tk, ramp);
  if (end == m_.at.k) {
    // Nothing to ramp down: the step already planned is the last one (one step if none yet).
    if (m_.at.k == 0) {
      if (m_.at.end > 1) replan_to_end(1, ramp, true);
    } else if (m_.at.end > m_.at.k) {
      finish_at_frontier();
    }
    return;
  }
  if (end >= m_.at.end) return;  // the motion ends as soon anyway (e.g. already decelerating)
  replan_to_end(end, ramp, true);
}

bool AxisPlanner::request_cut(const StopSpec& c) noexcept {
  if (control_ == nullptr || m_.held || cut_.open || cut_epoch_ == m_.epoch) return false;
  // The trigger is a wall-clock time (an input edge's timestamp, a scan): on the motion's time
  // base it lies its slip earlier.
  const Nanos want = std::max(c.trigger_t - slip(), now_ + opt_.cut_margin_ns);
  const std::int64_t k = planned_steps_at(want);
  // Nothing planned after `want` (the frontier stop is as early), or no step before it yet.
  if (k < 1 || k >= m_.at.k ||
      m_.at.k - k >= static_cast<std::int64_t>(EdgeEmitter::kHistory) - 1) {
    return false;
  }
  const Nanos t_c = out_.step_time(k);
  // A GPO edge queued after t_c would hold the replacement edges behind it in the ring.
  if (t_c < out_.nonmotion_t()) return false;
  const double t = static_cast<double>(t_c - m_.at.origin) * 1e-9;
  // Replanned after step k (a speed change): the profile at k is gone.
  if (t < profile_.start_time()) return false;
  if (profile_.stop_end(k, t, c.ramp) >= m_.at.end) return false;  // it ends as soon anyway
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
  const double t = static_cast<double>(cut_.t - m_.at.origin) * 1e-9;
  out_.cut(cut_.t, profile_.phase_at(t));
  m_.at.k = cut_.k;
  m_.at.tk = t;
  m_.at.tk_ns = cut_.t;
  const std::int64_t end = profile_.stop_end(cut_.k, t, cut_.ramp);
  if (end <= m_.at.k) {
    finish_at_frontier();
    return;
  }
  replan_to_end(end, cut_.ramp, true);
}

void AxisPlanner::stop_after(std::uint32_t epoch, const StopAfterSpec& c) noexcept {
  if (!m_.active || epoch != m_.epoch || source_ != &profile_) return;
  // Steps of this motion up to c.t, counting the ones already planned after it: as the pulse
  // thread's history counted them, or else c.t, a wall-clock time (the registration input's
  // edge), converted to the motion's time. That conversion takes the slip of now, one step
  // short when the motion slipped a step's time between c.t and now (a loaded machine).
  const std::int64_t at_t = c.done_at_t >= 0 ? c.done_at_t : planned_steps_at(c.t - slip());
  const std::int64_t end = at_t + std::max<std::int64_t>(c.steps, 0);
  if (end >= m_.at.end) return;  // already ends there or sooner
  if (end <= m_.at.k) {
    finish_at_frontier();  // the count was reached by steps already planned: end at once
    return;
  }
  // Registration (3601 manual ch. 4, 3602 ch. 2), after the trigger: freeze the present speed,
  // cruise, decelerate with the motion's decel.
  replan_to_end(end, profile_.decel(), false);
}

}  // namespace stepmod::planner
