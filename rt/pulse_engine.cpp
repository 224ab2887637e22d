#include "rt/pulse_engine.hpp"

#include <algorithm>

#include "rt/slip.hpp"

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
      truncated_epoch_(axes.size(), 0),
      heads_(axes.size(), nullptr),
      cells_(axes.size()),
      track_(axes.size()) {}

Nanos PulseEngine::next_due() noexcept {
  bool starved = false;
  Nanos dry_until = kNever;
  for (Cell& c : cells_) c.wait_after = kNever;
  for (unsigned axis = 0; axis < axes_.size(); ++axis) {
    Nanos refill_at = 0;
    bool unsettled = false;
    const Edge* e = prepare_head(axis, refill_at, unsettled);
    heads_[axis] = e;
    if (e == nullptr && (in_motion_[axis] != 0 || unsettled)) {
      starved = true;
      // refill_at is a planned time of the motion: on the wire it comes its slip later.
      dry_until = std::min(dry_until, refill_at == 0 ? 0 : refill_at + slip_of(axis));
      // The group's edges planned after it wait for it (waits_for_group). 0 names no edge: there
      // is nothing to order by (a cut being resolved; nothing planned ahead).
      if (refill_at != 0) {
        Cell& c = cells_[track_[axis].cell];
        c.wait_after = std::min(c.wait_after, refill_at);
      }
    }
  }
  Nanos best = kNever;
  int best_axis = -1;
  for (unsigned axis = 0; axis < axes_.size(); ++axis) {
    const Edge* e = heads_[axis];
    if (e == nullptr || waits_for_group(axis, *e)) continue;
    // Strictly earlier only: on a tie the lower axis goes first, a stable order for tests.
    const Nanos t = due(axis, *e);
    if (t < best) {
      best = t;
      best_axis = static_cast<int>(axis);
    }
  }
  next_axis_ = best_axis;
  starved_ = starved;
  dry_until_ = dry_until;
  return best;
}

const Edge* PulseEngine::prepare_head(unsigned axis, Nanos& refill_at, bool& unsettled) noexcept {
  const AxisLink& link = axes_[axis];
  if (link.control != nullptr &&
      link.control->abort_epoch.load(std::memory_order_acquire) > abort_seen_[axis]) {
    apply_abort(axis);
  }
  // Bounded, as everything in the pulse thread: while the planner pushes edges as fast as the
  // checks drop them, the axis has nothing ready and is polled again at once (starved, refill_at
  // 0); an edge is never written unchecked.
  const Edge* e = nullptr;
  bool examined = false;
  for (int pass = 0; pass < kHeadPasses && !examined; ++pass) {
    examined = examine_head(axis, refill_at, e);
  }
  unsettled = !examined;
  if (unsettled) {
    refill_at = 0;
    return nullptr;
  }
  if (e != nullptr && (e->flags & edge_flag::kMotion) != 0 && e->epoch != track_[axis].epoch) {
    bind(axis, *e);
  }
  return e;
}

// One pass of the head's checks; true if they all looked at the head `e` it returns. The planner
// pushes meanwhile: an edge pushed into a ring a check found empty, or behind one it popped, has
// not been looked at by every check, and would otherwise be written unchecked (a stale edge of a
// stopped motion, a step beyond a cap).
bool PulseEngine::examine_head(unsigned axis, Nanos& refill_at, const Edge*& e) noexcept {
  const AxisLink& link = axes_[axis];
  SpscRing<Edge>& ring = *link.edges;
  const std::size_t popped = ring.popped();
  const Edge* const head = ring.peek();
  // Every call, not only when an abort arrives: the planner may still push edges of a motion
  // it has not yet learnt was aborted, and aborted edges queued behind a GPO edge reach the
  // head only after it has been executed.
  drop_stale(axis);
  if (link.control != nullptr) link.control->cut.before_next(ring);  // edge_cut.hpp
  drop_beyond_limit(axis);
  // Before the peek (AxisControl::refill_at): a promise that came with a refill also makes the
  // edges pushed before it visible.
  refill_at = link.control != nullptr ? link.control->refill_at.load(std::memory_order_acquire) : 0;
  e = ring.peek();
  return ring.popped() == popped && e == head;
}

bool PulseEngine::waits_for_group(unsigned axis, const Edge& e) const noexcept {
  const std::uint8_t c = track_[axis].cell;
  if ((e.flags & edge_flag::kMotion) == 0 || c == kNoCell) return false;
  // The end of a pulse under way moves no axis: it keeps its width rather than wait.
  if (e.level == 0 && pulse_high_[axis] == static_cast<std::uint8_t>(e.line)) return false;
  return e.t > cells_[c].wait_after;
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
  if ((e.flags & edge_flag::kMotion) == 0) return e.t;  // GPO: written at its own time
  const Nanos t = e.t + slip_of(axis);
  // The pulse's trailing edge: a drive needs the whole high time, however late the rise was.
  if (e.level == 0 && pulse_high_[axis] == static_cast<std::uint8_t>(e.line)) {
    return t + pulse_late_[axis];
  }
  // The first step after a direction change: the whole set-up time after the direction write.
  if (e.dpos != 0) return t + dir_late_[axis];
  return t;
}

int PulseEngine::find_cell(unsigned axis, std::uint32_t key) const noexcept {
  const auto taken = [&](unsigned c) {
    for (unsigned b = 0; b < track_.size(); ++b) {
      if (b != axis && track_[b].cell == c) return true;
    }
    return false;
  };
  // The group's cell, if another member bound it already.
  if (key != 0) {
    for (unsigned c = 0; c < cells_.size(); ++c) {
      if (cells_[c].key == key && taken(c)) return static_cast<int>(c);
    }
  }
  if (!taken(axis)) return -static_cast<int>(axis) - 1;  // free: preferably the axis' own
  for (unsigned c = 0; c < cells_.size(); ++c) {
    if (!taken(c)) return -static_cast<int>(c) - 1;
  }
  return -static_cast<int>(axis) - 1;  // cannot happen: cells == axes, this axis holds none
}

void PulseEngine::bind(unsigned axis, const Edge& e) noexcept {
  Track& tr = track_[axis];
  std::uint32_t key = 0;
  Nanos vs_interval = 0;
  if (const AxisControl* ctl = axes_[axis].control) {
    const std::uint64_t g = ctl->motion_group.load(std::memory_order_acquire);
    const std::uint64_t v = ctl->motion_vs.load(std::memory_order_acquire);
    if (packed_epoch(g) == e.epoch) key = packed_value(g);
    if (packed_epoch(v) == e.epoch) vs_interval = packed_value(v);
  }
  // A motion that continues the previous one (planned within kChainGapNs of its slipped end)
  // keeps its slip: the gap between them is not squeezed. A start from rest starts on time.
  Nanos inherit = 0;
  if (tr.have_last && e.t - tr.last_planned < tr.last_slip + kChainGapNs) inherit = tr.last_slip;
  tr.cell = kNoCell;
  const int found = find_cell(axis, key);
  std::uint8_t c = 0;
  if (found >= 0) {
    c = static_cast<std::uint8_t>(found);
    cells_[c].slip = std::max(cells_[c].slip, inherit);  // only ever later: never squeezed
  } else {
    c = static_cast<std::uint8_t>(-found - 1);
    cells_[c] = Cell{inherit, key};
  }
  tr.cell = c;
  tr.epoch = e.epoch;
  tr.vs_interval = vs_interval;
  tr.step_seen = false;
  publish_slip(c);
}

void PulseEngine::publish_slip(std::uint8_t cell) noexcept {
  const std::uint32_t us = slip_us(cells_[cell].slip);
  for (unsigned b = 0; b < track_.size(); ++b) {
    if (track_[b].cell != cell || axes_[b].feedback == nullptr) continue;
    axes_[b].feedback->slip.store(pack_epoch(track_[b].epoch, us), std::memory_order_release);
  }
}

Nanos PulseEngine::absorb(unsigned axis, const Edge& e, Nanos write_time) noexcept {
  Track& tr = track_[axis];
  Cell& cell = cells_[tr.cell];
  // Against the slipped planned time: a step's direction set-up residual counts in here.
  const Nanos late = write_time - (e.t + cell.slip);
  if (late > kSlipFreeNs) {
    cell.slip += late - kSlipFreeNs;
    publish_slip(tr.cell);
  }
  tr.have_last = true;
  tr.last_planned = e.t;
  tr.last_slip = cell.slip;
  return std::clamp<Nanos>(write_time - (e.t + cell.slip), 0, kSlipFreeNs);
}

PulseEngine::Verdict PulseEngine::judge(unsigned axis, const Edge& e,
                                        Nanos write_time) const noexcept {
  const Track& tr = track_[axis];
  Verdict v;
  v.pause = std::max<Nanos>(0, write_time - due(axis, e));
  if (e.dpos != 0 && tr.step_seen) {
    // The gap since the previous step against the planned one: what the motor sees, whichever
    // edge (trailing, direction, this one; or another axis of the group) was late.
    v.interval = std::max<Nanos>(1, e.t - tr.step_planned);
    v.pause = std::max(v.pause, (write_time - tr.step_wire) - v.interval);
    // Above Vs (1 % tolerance: a move at Vs is planned at Vs's interval, rounded).
    const bool above_vs = tr.vs_interval == 0 || v.interval * 100 < tr.vs_interval * 99;
    if (above_vs) v.lag = v.pause / v.interval;
  }
  v.fault = (late_limit_ != 0 && v.pause > late_limit_) ||
            (tr.lag_limit != 0 && v.lag > static_cast<std::int64_t>(tr.lag_limit));
  return v;
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

void PulseEngine::fault_group(unsigned axis, const Verdict& v) noexcept {
  const std::uint8_t cell = track_[axis].cell;
  for (unsigned b = 0; b < track_.size(); ++b) {
    if (b != axis && (cell == kNoCell || track_[b].cell != cell)) continue;
    const std::uint32_t epoch = track_[b].epoch;
    const AxisFeedback* fb = axes_[b].feedback;
    // A member that has already made all its steps is not cut (its motion ended well).
    if (b != axis && fb != nullptr && fb->finished_epoch.load(std::memory_order_relaxed) >= epoch) {
      continue;
    }
    late_fault(b, epoch, v);
  }
}

void PulseEngine::late_fault(unsigned axis, std::uint32_t epoch, const Verdict& v) noexcept {
  // As an immediate stop of this motion that the module did not ask for: its edges (the faulted
  // one included, still at the head of the ring) and any the planner still pushes are dropped by
  // drop_stale. The module learns of it from the feedback and stops the motion the same way.
  abort_seen_[axis] = std::max(abort_seen_[axis], epoch);
  drop_stale(axis);
  in_motion_[axis] = 0;
  // A group member may be in the middle of a pulse: end it rather than leave the line high.
  const std::uint8_t line = pulse_high_[axis];
  if (line != kNoPulse) write(axis, static_cast<OutputLine>(line), false, clock_());
  if (AxisFeedback* fb = axes_[axis].feedback) {
    fb->fault_step.store(fb->steps.load(std::memory_order_relaxed), std::memory_order_relaxed);
    fb->fault_late_ns.store(v.pause, std::memory_order_relaxed);
    fb->fault_lag.store(v.lag, std::memory_order_relaxed);
    fb->fault_interval_ns.store(v.interval, std::memory_order_relaxed);
    fb->fault_epoch.store(epoch, std::memory_order_relaxed);
    store_max(fb->worst_fault_late_ns, v.pause);
    fb->late_faults.store(fb->late_faults.load(std::memory_order_relaxed) + 1,
                          std::memory_order_release);
    store_max(fb->finished_epoch, epoch);
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

void PulseEngine::announce() noexcept {
  if (next_axis_ < 0) return;
  const auto axis = static_cast<unsigned>(next_axis_);
  const Edge* e = heads_[axis];
  StepHistory* h = axes_[axis].history;
  if (h == nullptr || e == nullptr || e->dpos == 0 || announced_ != nullptr) return;
  h->announce();
  announced_ = h;
}

void PulseEngine::withdraw() noexcept {
  if (announced_ == nullptr) return;
  announced_->withdraw();
  announced_ = nullptr;
}

void PulseEngine::execute_one(Nanos write_time) noexcept {
  execute_head(write_time);
  withdraw();  // if the announced step was not written (cut by the guard), or recorded already
}

void PulseEngine::execute_head(Nanos write_time) noexcept {
  if (next_axis_ < 0) return;
  const auto axis = static_cast<unsigned>(next_axis_);
  next_axis_ = -1;  // a second call without next_due() must not run a possibly later edge
  const AxisLink& link = axes_[axis];
  const Edge* p = link.edges->peek();
  if (p == nullptr) return;  // cannot happen: we are the only consumer and next_due() saw it
  const Edge e = *p;
  const bool motion = (e.flags & edge_flag::kMotion) != 0;
  const bool trailing = e.level == 0 && pulse_high_[axis] == static_cast<std::uint8_t>(e.line);
  const Nanos due_t = due(axis, e);
  // The guard looks at every motion edge but the end of a pulse under way: that one is always
  // written (a drive needs the whole pulse, and due() already gave it its width).
  if (motion && !trailing) {
    const Verdict v = judge(axis, e, write_time);
    if (v.fault) {
      fault_group(axis, v);
      return;
    }
  }
  link.edges->pop();
  if (link.control != nullptr) link.control->cut.executed(e);

  const bool direction_edge = e.dpos == 0 && e.line == OutputLine::kDir && !trailing && motion;
  write(axis, e.line, e.level != 0, write_time);
  const Nanos rest = motion ? absorb(axis, e, write_time) : 0;
  if (direction_edge) dir_late_[axis] = rest;

  if (e.dpos != 0) record_step(axis, e, write_time, rest);
  if (motion) publish_motion(axis, e);
  // Against when it was due (its slipped time): the error the pulse thread itself adds.
  stats_.record(write_time - due_t);
}

// After writing a step's edge (dpos != 0) at `write_time`: its pulse, the guard's memory of the
// step and the step count (history first).
void PulseEngine::record_step(unsigned axis, const Edge& e, Nanos write_time, Nanos rest) noexcept {
  const AxisLink& link = axes_[axis];
  AxisFeedback* fb = link.feedback;
  dir_late_[axis] = 0;
  if (e.level != 0) {
    pulse_high_[axis] = static_cast<std::uint8_t>(e.line);
    pulse_late_[axis] = rest;
  }
  if ((e.flags & edge_flag::kMotion) != 0) {
    Track& tr = track_[axis];
    if (fb != nullptr) {
      fb->step_interval_ns.store(tr.step_seen ? e.t - tr.step_planned : 0,
                                 std::memory_order_relaxed);
    }
    tr.step_seen = true;
    tr.step_planned = e.t;
    tr.step_wire = write_time;
  }
  if (fb == nullptr) return;
  const std::int64_t steps = fb->steps.load(std::memory_order_relaxed) + e.dpos;
  // History first: a reader that sees the new count in `steps` and then asks the history for a
  // time after this step finds it there.
  if (link.history != nullptr) {
    link.history->record(write_time, steps);
    if (announced_ == link.history) announced_ = nullptr;  // record() ended the announcement
  }
  fb->last_step_t.store(write_time, std::memory_order_relaxed);
  fb->steps.store(steps, std::memory_order_release);
}

// After writing motion edge `e`: whether the motion goes on, and its epoch and flags published.
void PulseEngine::publish_motion(unsigned axis, const Edge& e) noexcept {
  in_motion_[axis] = (e.flags & edge_flag::kLast) != 0 ? 0 : 1;
  AxisFeedback* fb = axes_[axis].feedback;
  if (fb == nullptr) return;
  fb->epoch.store(e.epoch, std::memory_order_release);
  fb->flags.store(e.flags, std::memory_order_release);
  // Last: a reader that sees the motion finished also sees its final count and flags.
  if ((e.flags & edge_flag::kLast) != 0) store_max(fb->finished_epoch, e.epoch);
}

}  // namespace stepmod::rt
