// AxisPlanner: the one fill loop. Whatever the motion kind, its step source answers the next step
// (planner/step_source.hpp) and the edge emitter writes it (planner/edge_emitter.hpp); the ring
// is kept filled a lookahead ahead.
#include <algorithm>
#include <limits>

#include "planner/axis_planner.hpp"

namespace stepmod::planner {

namespace {
// While a cut request is open, the planner looks for the pulse thread's answer this often.
constexpr Nanos kCutPollNs = 20 * kNsPerUs;
}  // namespace

Nanos AxisPlanner::fill(Nanos now) noexcept {
  // The ring is kept filled a lookahead ahead on the motion's time base, and the time to come
  // back is a wall-clock time again.
  const Nanos s = slip();
  const Nanos next = fill_planned(now - s);
  return next >= std::numeric_limits<Nanos>::max() - s ? next : next + s;
}

Answer AxisPlanner::plan_steps(Nanos horizon, SourceStep& st) noexcept {
  Answer a = Answer::kStep;
  while (m_.active && !m_.held && out_.staged_empty()) {
    StepProgress& p = m_.at;
    a = source_->next(p, StepWindow{now_, horizon, out_.last_t()}, st);
    if (a == Answer::kLater) {
      out_.rest(st.t);  // left unplanned, so that a hold can still replan it
      return a;
    }
    if (a == Answer::kWait) return a;
    if (a == Answer::kEnd) {
      finish_at_frontier();
    } else {
      const Nanos t = out_.step(st, p.k + 1);
      ++p.k;
      p.tk = st.ts;
      p.tk_ns = t;
      if (p.k >= p.end) {
        out_.end(t);
        m_.active = false;
      }
    }
    out_.flush(horizon);
  }
  return a;
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
  SourceStep st;
  const Answer a = plan_steps(horizon, st);
  if (out_.staged_empty()) {
    if (m_.active && !m_.held && a == Answer::kLater) {
      // The next step, left unplanned: plan it when half the lookahead is left before it.
      publish_refill(out_.first_edge_of(st));
      return std::max(now + kCutPollNs, st.t - opt_.lookahead_ns / 2);
    }
    publish_refill(0);  // nothing planned ahead (idle, or a follower waiting for a target)
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

void AxisPlanner::finish_at_frontier() noexcept {
  if (!m_.active) return;
  m_.active = false;
  out_.end(source_->end_time(m_.at, now_));
}

void AxisPlanner::publish_refill(Nanos t) noexcept {
  if (control_ != nullptr) control_->refill_at.store(t, std::memory_order_release);
}

}  // namespace stepmod::planner
