// AxisPlanner: filling the ring. Whatever the motion kind, the one fill loop
// (planner/step_loop.hpp) asks its step source for the next step (planner/step_source.hpp) and the
// edge emitter writes it (planner/edge_emitter.hpp); the ring is kept filled a lookahead ahead.
#include <algorithm>
#include <limits>

#include "planner/axis_planner.hpp"
#include "planner/step_loop.hpp"

namespace stepmod::planner {

namespace {
// While a cut request is open, the planner looks for the pulse thread's answer this often.
constexpr Nanos kCutPollNs = 20 * kNsPerUs;
}  // namespace

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
  SourceStep st;
  Answer a = Answer::kStep;
  if (m_.active && !m_.held) {
    StepLoop loop(m_.at, m_.active, out_, now_, horizon, st);
    a = source_->plan(loop);
  }
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
