#include "rt/pulse_engine.hpp"

#include <algorithm>

namespace stepmod::rt {

namespace {

// The pulse thread is the only writer of every AxisFeedback field, so read-modify-write needs no
// atomic RMW: a relaxed load of our own last store, then a store with the ordering readers need.
template <typename T>
void store_max(std::atomic<T>& a, T v) noexcept {
  if (v > a.load(std::memory_order_relaxed)) a.store(v, std::memory_order_release);
}

}  // namespace

PulseEngine::PulseEngine(gpio::Backend& backend, std::span<const AxisLink> axes,
                         SpscRing<TraceRecord>* trace)
    : backend_(backend),
      axes_(axes.begin(), axes.end()),
      abort_seen_(axes.size(), 0),
      trace_(trace),
      pulse_high_(axes.size(), kNoPulse),
      in_motion_(axes.size(), 0),
      pulse_late_(axes.size(), 0),
      dir_late_(axes.size(), 0),
      truncated_epoch_(axes.size(), 0) {}

Nanos PulseEngine::next_due() noexcept {
  Nanos best = kNever;
  int best_axis = -1;
  bool starved = false;
  Nanos dry_until = kNever;
  for (unsigned axis = 0; axis < axes_.size(); ++axis) {
    const AxisLink& link = axes_[axis];
    if (link.control != nullptr &&
        link.control->abort_epoch.load(std::memory_order_acquire) > abort_seen_[axis]) {
      apply_abort(axis);
    }
    // Every call, not only when an abort arrives: the planner may still push edges of a motion
    // it has not yet learnt was aborted, and aborted edges queued behind a GPO edge reach the
    // head only after it has been executed.
    drop_stale(axis);
    if (link.control != nullptr) link.control->cut.before_next(*link.edges);  // edge_cut.hpp
    drop_beyond_limit(axis);
    // Before the peek (AxisControl::refill_at): a promise that came with a refill also makes the
    // edges pushed before it visible.
    const Nanos refill_at =
        link.control != nullptr ? link.control->refill_at.load(std::memory_order_acquire) : 0;
    const Edge* e = link.edges->peek();
    if (e == nullptr && in_motion_[axis] != 0) {
      starved = true;
      dry_until = std::min(dry_until, refill_at);
    }
    // Strictly earlier only: on a tie the lower axis goes first, a stable order for tests.
    if (e != nullptr) {
      const Nanos t = due(axis, *e);
      if (t < best) {
        best = t;
        best_axis = static_cast<int>(axis);
      }
    }
  }
  next_axis_ = best_axis;
  starved_ = starved;
  dry_until_ = dry_until;
  return best;
}

void PulseEngine::drop_stale(unsigned axis) noexcept {
  const std::uint32_t seen = abort_seen_[axis];
  if (seen == 0) return;  // no abort yet; epoch 0 is not a motion that can have been aborted
  SpscRing<Edge>& ring = *axes_[axis].edges;
  for (const Edge* e = ring.peek(); e != nullptr; e = ring.peek()) {
    if ((e->flags & edge_flag::kMotion) == 0 || e->epoch > seen) break;
    ring.pop();
  }
}

Nanos PulseEngine::due(unsigned axis, const Edge& e) const noexcept {
  // The pulse's trailing edge: a drive needs the whole high time, however late the rise was.
  if (e.level == 0 && pulse_high_[axis] == static_cast<std::uint8_t>(e.line)) {
    return e.t + pulse_late_[axis];
  }
  // The first step after a direction change: the whole set-up time after the direction write.
  if (e.dpos != 0) return e.t + dir_late_[axis];
  return e.t;
}

// Registration exactness (AxisControl::limit_steps): steps of the capped motion beyond its cap
// are dropped, and with them the rest of that motion's edges but the end of a pulse under way.
void PulseEngine::drop_beyond_limit(unsigned axis) noexcept {
  const AxisLink& link = axes_[axis];
  if (link.control == nullptr || link.feedback == nullptr) return;
  const std::uint32_t epoch = link.control->limit_epoch.load(std::memory_order_acquire);
  if (epoch == 0) return;
  const std::int64_t limit = link.control->limit_steps.load(std::memory_order_relaxed);
  SpscRing<Edge>& ring = *link.edges;
  for (const Edge* e = ring.peek(); e != nullptr; e = ring.peek()) {
    if ((e->flags & edge_flag::kMotion) == 0 || e->epoch != epoch) return;
    if (e->level == 0 && pulse_high_[axis] == static_cast<std::uint8_t>(e->line)) return;
    if (truncated_epoch_[axis] != epoch) {
      const std::int64_t steps = link.feedback->steps.load(std::memory_order_relaxed);
      const bool beyond = (e->dpos > 0 && steps >= limit) || (e->dpos < 0 && steps <= limit);
      if (!beyond) return;
      truncated_epoch_[axis] = epoch;
    }
    if ((e->flags & edge_flag::kLast) != 0) {
      in_motion_[axis] = 0;
      store_max(link.feedback->finished_epoch, epoch);
    }
    ring.pop();
  }
}

void PulseEngine::apply_abort(unsigned axis) noexcept {
  const AxisLink& link = axes_[axis];
  const std::uint32_t a = link.control->abort_epoch.load(std::memory_order_acquire);
  abort_seen_[axis] = a;
  drop_stale(axis);
  in_motion_[axis] = 0;
  // A step pulse of the aborted motion left high would be half a pulse: the drive may or may not
  // count it. End it now so the line rests at its idle level. A pulse of a newer motion (epoch >
  // a) is not ours to touch.
  const std::uint8_t line = pulse_high_[axis];
  if (line != kNoPulse &&
      (link.feedback == nullptr || link.feedback->epoch.load(std::memory_order_relaxed) <= a)) {
    write(axis, static_cast<OutputLine>(line), false, clock_());
  }
  // Acknowledge even if nothing of the epoch was queued yet (the planner had not started it):
  // the module waits for finished_epoch, and any edge of it still to come will be dropped.
  if (link.feedback != nullptr) store_max(link.feedback->finished_epoch, a);
}

void PulseEngine::late_fault(unsigned axis, const Edge& e, Nanos late) noexcept {
  // As an immediate stop of this motion that the module did not ask for: its edges (this one
  // included, still at the head of the ring) and any the planner still pushes are dropped by
  // drop_stale. The module learns of it from the feedback and stops the motion the same way.
  abort_seen_[axis] = std::max(abort_seen_[axis], e.epoch);
  drop_stale(axis);
  in_motion_[axis] = 0;
  // Edges of one axis are in time order, so a pulse's trailing edge precedes the next motion
  // edge and no pulse can be high here; should one be (a foreign order), end it rather than
  // leave the line high.
  const std::uint8_t line = pulse_high_[axis];
  if (line != kNoPulse) write(axis, static_cast<OutputLine>(line), false, clock_());
  if (AxisFeedback* fb = axes_[axis].feedback) {
    fb->fault_step.store(fb->steps.load(std::memory_order_relaxed), std::memory_order_relaxed);
    fb->fault_late_ns.store(late, std::memory_order_relaxed);
    fb->fault_epoch.store(e.epoch, std::memory_order_relaxed);
    store_max(fb->worst_fault_late_ns, late);
    fb->late_faults.store(fb->late_faults.load(std::memory_order_relaxed) + 1,
                          std::memory_order_release);
    store_max(fb->finished_epoch, e.epoch);
  }
}

void PulseEngine::write(unsigned axis, OutputLine line, bool level, Nanos t) noexcept {
  backend_.write(axis, line, level, t);
  const auto bit = static_cast<std::uint8_t>(1u << static_cast<unsigned>(line));
  if (AxisFeedback* fb = axes_[axis].feedback) {
    const std::uint8_t old = fb->output_levels.load(std::memory_order_relaxed);
    const auto now = static_cast<std::uint8_t>(level ? (old | bit) : (old & ~bit));
    if (now != old) fb->output_levels.store(now, std::memory_order_release);
  }
  if (!level && pulse_high_[axis] == static_cast<std::uint8_t>(line)) pulse_high_[axis] = kNoPulse;
  if (trace_ != nullptr) {
    TraceRecord r;
    r.t = t;
    r.axis = static_cast<std::uint8_t>(axis);
    r.line = static_cast<std::uint8_t>(line);
    r.level = level ? 1 : 0;
    r.is_input = 0;
    // Never wait for the trace writer: a lost trace record costs nothing, a late edge does.
    if (!trace_->try_push(r)) {
      trace_dropped_.store(trace_dropped_.load(std::memory_order_relaxed) + 1,
                           std::memory_order_relaxed);
    }
  }
}

void PulseEngine::execute_one(Nanos write_time) noexcept {
  if (next_axis_ < 0) return;
  const auto axis = static_cast<unsigned>(next_axis_);
  next_axis_ = -1;  // a second call without next_due() must not run a possibly later edge
  const AxisLink& link = axes_[axis];
  const Edge* p = link.edges->peek();
  if (p == nullptr) return;  // cannot happen: we are the only consumer and next_due() saw it
  const Edge e = *p;
  // The late-edge guard looks at every motion edge but the end of a pulse under way: that one
  // is always written (a drive needs the whole pulse, and due() already gave it its width).
  if ((e.flags & edge_flag::kMotion) != 0 &&
      !(e.level == 0 && pulse_high_[axis] == static_cast<std::uint8_t>(e.line))) {
    const Nanos late = write_time - due(axis, e);
    if (late > late_limit_) {
      late_fault(axis, e, late);
      return;
    }
  }
  link.edges->pop();
  if (link.control != nullptr) link.control->cut.executed(e);

  // Before write() clears pulse_high_: whether this edge ends the pulse under way.
  const bool direction_edge = e.dpos == 0 && e.line == OutputLine::kDir &&
                              pulse_high_[axis] != static_cast<std::uint8_t>(e.line) &&
                              (e.flags & edge_flag::kMotion) != 0;
  write(axis, e.line, e.level != 0, write_time);
  if (direction_edge) dir_late_[axis] = std::max<Nanos>(0, write_time - e.t);

  AxisFeedback* fb = link.feedback;
  if (e.dpos != 0) {
    // A step's leading edge.
    dir_late_[axis] = 0;
    if (e.level != 0) {
      pulse_high_[axis] = static_cast<std::uint8_t>(e.line);
      pulse_late_[axis] = std::max<Nanos>(0, write_time - e.t);
    }
    if (fb != nullptr) {
      const std::int64_t steps = fb->steps.load(std::memory_order_relaxed) + e.dpos;
      // History first: a reader that sees the new count in `steps` and then asks the history
      // for a time after this step finds it there.
      if (link.history != nullptr) link.history->record(write_time, steps);
      fb->last_step_t.store(write_time, std::memory_order_relaxed);
      fb->steps.store(steps, std::memory_order_release);
    }
  }
  if ((e.flags & edge_flag::kMotion) != 0) {
    in_motion_[axis] = (e.flags & edge_flag::kLast) != 0 ? 0 : 1;
  }
  if (fb != nullptr && (e.flags & edge_flag::kMotion) != 0) {
    fb->epoch.store(e.epoch, std::memory_order_release);
    fb->flags.store(e.flags, std::memory_order_release);
    // Last: a reader that sees the motion finished also sees its final count and flags.
    if ((e.flags & edge_flag::kLast) != 0) store_max(fb->finished_epoch, e.epoch);
  }
  stats_.record(write_time - e.t);
}

}  // namespace stepmod::rt
