#include "planner/edge_emitter.hpp"

#include <algorithm>
#include <utility>

namespace stepmod::planner {

EdgeEmitter::EdgeEmitter(SpscRing<rt::Edge>* ring, AxisTiming timing) noexcept
    : ring_(ring), timing_(timing) {}

void EdgeEmitter::stage_sorted(const rt::Edge& e) noexcept {
  // Behind every staged edge at or before e.t, ahead of later ones (a GPO change must not wait
  // for a step planned a second ahead).
  stage(e);
  std::size_t i = staged_count_ - 1;
  while (i > 0) {
    rt::Edge& prev = staged_[(staged_head_ + i - 1) & (kStaged - 1)];
    rt::Edge& cur = staged_[(staged_head_ + i) & (kStaged - 1)];
    if (prev.t <= cur.t) break;
    std::swap(prev, cur);
    --i;
  }
}

void EdgeEmitter::flush(Nanos horizon) noexcept {
  while (staged_count_ != 0) {
    const rt::Edge& e = staged_[staged_head_];
    if (e.t > horizon) break;
    if (!ring_->try_push(e)) break;
    last_pushed_t_ = e.t;
    staged_head_ = (staged_head_ + 1) & (kStaged - 1);
    --staged_count_;
  }
}

std::int64_t EdgeEmitter::steps_at(Nanos t, std::int64_t planned) const noexcept {
  std::int64_t hi = planned;
  if (hi == 0) return 0;
  if (step_time(hi) <= t) return hi;
  std::int64_t lo = std::max<std::int64_t>(1, hi - static_cast<std::int64_t>(kHistory) + 1);
  // Older than the history: the best we know is that it was before step lo.
  if (step_time(lo) > t) return lo - 1;
  // Invariant: time(lo) <= t < time(hi).
  while (hi - lo > 1) {
    const std::int64_t mid = lo + (hi - lo) / 2;
    if (step_time(mid) <= t) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

void EdgeEmitter::begin(std::uint32_t epoch, Direction dir, const FirstStep& first) noexcept {
  if (want_step_dir_ != step_dir_) step_dir_ = want_step_dir_;
  epoch_ = epoch;
  first_pending_ = true;
  pulse_open_ = false;
  motion_floor_t_ = last_t_;
  base_flags_ = 0;
  turn(dir);
  // Step/direction: the direction line must settle dir_setup_ns before the first step. CW/CCW:
  // the CCW pulse line rests low. Only a change (or an unknown level) costs an edge.
  lead_edge_ = first.known && direction_pending();
  lead_ = lead_edge_ ? std::max<Nanos>(0, timing_.dir_setup_ns - seconds_to_ns(first.t)) : 0;
  lead_phase_ = first.phase;
}

void EdgeEmitter::launch(Nanos origin) noexcept {
  if (lead_edge_) direction(origin - lead_, lead_phase_);
}

Nanos EdgeEmitter::set_up_direction(const SourceStep& s) noexcept {
  if (s.dir != dir_) {
    // The motion turns between two steps (a path coordinate's reversal, the follower reversing):
    // the open pulse ends first.
    rest(s.t);
    turn(s.dir);
  }
  if (!direction_pending()) return s.t;  // CW/CCW format: the other line, no set-up
  const Nanos td = std::max({last_t_, s.not_before, s.t - timing_.dir_setup_ns});
  direction(td, s.phase);
  return std::max(s.t, td + timing_.dir_setup_ns);
}

void EdgeEmitter::turn(Direction dir) noexcept {
  const bool ccw = dir == Direction::kCcw;
  dir_ = dir;
  line_ = (step_dir_ || !ccw) ? OutputLine::kStep : OutputLine::kDir;
  base_flags_ = static_cast<std::uint8_t>(rt::edge_flag::kMotion | (ccw ? rt::edge_flag::kCcw : 0) |
                                          (base_flags_ & rt::edge_flag::kReplacement));
}

void EdgeEmitter::rest(Nanos t_next) noexcept {
  if (!pulse_open_) return;
  const Nanos w = std::max<Nanos>(1, std::min(timing_.step_pulse_ns, (t_next - step_t_) / 2));
  stage(make_edge(step_t_ + w, line_, 0, 0, step_flags_));
  pulse_open_ = false;
}

void EdgeEmitter::direction(Nanos t, rt::Phase phase) noexcept {
  const std::uint8_t level = dir_target();
  stage(make_edge(t, OutputLine::kDir, level, 0,
                  take_first(base_flags_ | static_cast<std::uint8_t>(phase))));
  dir_level_ = level;
}

void EdgeEmitter::whole_pulse(Nanos t, rt::Phase phase, Nanos width, std::int64_t k) noexcept {
  const auto flags = static_cast<std::uint8_t>(base_flags_ | static_cast<std::uint8_t>(phase));
  stage(make_edge(t, line_, 1, static_cast<std::int8_t>(sign(dir_)), take_first(flags)));
  stage(make_edge(t + width, line_, 0, 0, flags));
  history_[static_cast<std::size_t>(k) & (kHistory - 1)] = t;
  pulse_open_ = false;
  step_t_ = t;
  step_flags_ = flags;
}

void EdgeEmitter::end(Nanos t) noexcept {
  if (pulse_open_) {
    pulse_open_ = false;
    stage(make_edge(step_t_ + timing_.step_pulse_ns, line_, 0, 0,
                    step_flags_ | rt::edge_flag::kLast));
    return;
  }
  // No pulse to end: rewrite the direction line at its present level, carrying kLast (and kFirst
  // if nothing of the motion was written) so the pulse thread still reports the motion finished.
  const int level = dir_level_ >= 0 ? dir_level_ : 0;
  dir_level_ = level;
  stage(make_edge(std::max(t, last_t_), OutputLine::kDir, static_cast<std::uint8_t>(level), 0,
                  take_first(base_flags_ | rt::edge_flag::kLast)));
}

void EdgeEmitter::abort(std::uint32_t epoch) noexcept {
  // The pulse thread drops this motion's edges; drop the ones it would never see as well.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < staged_count_; ++i) {
    const rt::Edge e = staged_[(staged_head_ + i) & (kStaged - 1)];
    if ((e.flags & rt::edge_flag::kMotion) != 0 && e.epoch <= epoch) continue;
    staged_[(staged_head_ + kept++) & (kStaged - 1)] = e;
  }
  staged_count_ = kept;
  pulse_open_ = false;
  // Its direction edge may have been dropped unexecuted: write the direction again next time.
  dir_level_ = -1;
  // The next motion (and a GPO change) may go right away: only edges that will really run bound
  // them. Ring order matters only among those: the pulse thread drops the aborted edges ahead of
  // them as soon as they reach the head (abort_epoch is set before the abort is submitted).
  last_t_ = std::max(motion_floor_t_, nonmotion_t_);
  last_pushed_t_ = std::min(last_pushed_t_, last_t_);
}

void EdgeEmitter::cut(Nanos t, rt::Phase phase) noexcept {
  // The motion's edges after the cut that were still staged never reach the ring; the pulse
  // thread drops the ones that did.
  std::size_t kept = 0;
  Nanos newest = std::max(t, nonmotion_t_);
  for (std::size_t i = 0; i < staged_count_; ++i) {
    const rt::Edge e = staged_[(staged_head_ + i) & (kStaged - 1)];
    if ((e.flags & rt::edge_flag::kMotion) != 0 && e.epoch == epoch_ && e.t > t) continue;
    staged_[(staged_head_ + kept++) & (kStaged - 1)] = e;
    newest = std::max(newest, e.t);
  }
  staged_count_ = kept;
  last_t_ = newest;
  last_pushed_t_ = std::min(last_pushed_t_, newest);
  // Step k's pulse is open again: its trailing edge is planned with the next step.
  base_flags_ |= rt::edge_flag::kReplacement;
  pulse_open_ = true;
  step_t_ = t;
  step_flags_ = static_cast<std::uint8_t>(base_flags_ | static_cast<std::uint8_t>(phase));
}

void EdgeEmitter::gpo(bool level, Nanos now) noexcept {
  // Not part of any motion: as soon as the ring's order allows (behind edges already pushed).
  const Nanos t = std::max(now, last_pushed_t_);
  stage_sorted(make_edge(t, OutputLine::kGpo, level ? 1 : 0, 0, 0));
  nonmotion_t_ = std::max(nonmotion_t_, t);
}

void EdgeEmitter::pulse_format(bool step_dir, Nanos now, bool motion_running) noexcept {
  want_step_dir_ = step_dir;
  // A motion in progress keeps its format; the next one starts with the new one.
  if (motion_running || step_dir == step_dir_) return;
  step_dir_ = step_dir;
  if (dir_level_ != 0) {
    // The direction line becomes the CCW pulse line (or back): leave it at its idle level.
    const Nanos t = std::max(now, last_pushed_t_);
    stage_sorted(make_edge(t, OutputLine::kDir, 0, 0, 0));
    nonmotion_t_ = std::max(nonmotion_t_, t);
    dir_level_ = 0;
  }
}

}  // namespace stepmod::planner
