#pragma once
// Edge emission for one axis: turns "a step at time t" into the line edges the pulse thread
// writes, and owns everything that is about lines rather than motion: the step pulse width, the
// direction set-up time, the pulse format (step + direction or CW + CCW pulses), the direction
// line's level, the staging of edges in time order ahead of the ring, and the step history.
// The step sources (planner/step_source.hpp) only say when each step is, in which direction and
// in which phase; whether that needs a direction edge first, and how wide its pulse is, is
// decided here.
//
// Step + direction format, one step after a direction change, then two steps:
//
//              _____________________________________________
//   DIR   ____/            direction set-up                  (level: 1 = CW, 0 = CCW)
//             |<------ dir_setup_ns ------>|
//                                          ______            ______       ______
//   STEP  ________________________________/      \__________/      \_____/      \____
//                                         |<---->|          |<---->|
//                                      step_pulse_ns     min(step_pulse_ns, period / 2)
//
// CW + CCW format: CW steps pulse the step line, CCW steps the direction line; no set-up.
//
// Verbs (in the order a motion uses them): begin -> launch -> step ... [rest] ... -> end.
// Abort, cut, gpo and pulse_format may come at any time; flush pushes what is staged. Owned by the
// planner thread.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "core/spsc_ring.hpp"
#include "planner/motion_request.hpp"
#include "planner/planner.hpp"
#include "planner/step_source.hpp"
#include "rt/edge.hpp"

namespace stepmod::planner {

// Step/direction format: the direction line is high while the axis runs CW (position increasing)
// and low for CCW, as the simulated drive reads it (gpio/sim_machine.cpp). Lines idle low.
inline constexpr std::uint8_t kDirLevelCcw = 0;
inline constexpr std::uint8_t kDirLevelCw = 1;

class EdgeEmitter {
 public:
  EdgeEmitter(SpscRing<rt::Edge>* ring, AxisTiming timing) noexcept;

  // A new motion `epoch` starting in `dir` (the pulse format asked for last applies from here).
  // If its first step is known (`first`) and the direction line must change before it, the
  // motion's time 0 must lie lead() after the direction edge, which launch() writes.
  void begin(std::uint32_t epoch, Direction dir, const FirstStep& first) noexcept;
  Nanos lead() const noexcept { return lead_; }
  // The motion's time 0 is `origin`: the direction edge of begin(), if it needs one.
  void launch(Nanos origin) noexcept;
  // Step k of the motion (a source's answer, planner/step_source.hpp); returns the time of its
  // leading edge. A step in another direction than the previous one ends the open pulse, turns
  // (later steps pulse the line of its direction) and, in step/direction format, writes the
  // direction line at least dir_setup_ns before the step (later than s.t if it must). With
  // s.width 0 the pulse stays open until the next step or end() (its full width, or half the
  // period if shorter), else it is a whole pulse that wide.
  Nanos step(const SourceStep& s, std::int64_t k) noexcept;
  // The next step lies at t_next and is not planned yet (a path axis waiting for its next
  // crossing): the open pulse ends now (its full width, or half the time to t_next if shorter).
  void rest(Nanos t_next) noexcept;
  // The earliest edge the step `s` will need (its direction set-up if it turns).
  Nanos first_edge_of(const SourceStep& s) const noexcept {
    return s.dir != dir_ ? s.t - timing_.dir_setup_ns : s.t;
  }
  // Ends the motion: the open pulse ends with kLast, or (no pulse open) a marker edge at
  // max(t, newest edge) rewrites the direction line at its level, carrying kLast.
  void end(Nanos t) noexcept;
  // Immediate stop of every motion up to `epoch`: their staged edges are dropped (the pulse
  // thread drops the pushed ones) and the direction level becomes unknown.
  void abort(std::uint32_t epoch) noexcept;
  // A cut (rt/edge_cut.hpp) accepted at step k's leading edge t: the motion's staged edges after
  // t are dropped, step k's pulse is open again, and later edges carry kReplacement.
  void cut(Nanos t, rt::Phase phase) noexcept;
  // Not part of any motion, as soon as the ring's order allows.
  void gpo(bool level, Nanos now) noexcept;
  // Applied at once when no motion is running, else from the next begin().
  void pulse_format(bool step_dir, Nanos now, bool motion_running) noexcept;

  // Pushes staged edges up to `horizon` while the ring has room.
  void flush(Nanos horizon) noexcept;
  bool staged_empty() const noexcept { return staged_count_ == 0; }
  Nanos head_t() const noexcept { return staged_[staged_head_].t; }  // !staged_empty()
  Nanos last_t() const noexcept { return last_t_; }                  // newest staged or pushed
  Nanos last_pushed_t() const noexcept { return last_pushed_t_; }    // newest in the ring
  Nanos nonmotion_t() const noexcept { return nonmotion_t_; }        // newest GPO/format edge
  bool step_dir_format() const noexcept { return step_dir_; }

  // Step history of the current motion: time of step k (while k is within the last kHistory),
  // and the number of steps (of the `planned` so far) at or before t.
  static constexpr std::size_t kHistory = 1u << 14;
  Nanos step_time(std::int64_t k) const noexcept {
    return history_[static_cast<std::size_t>(k) & (kHistory - 1)];
  }
  std::int64_t steps_at(Nanos t, std::int64_t planned) const noexcept;

 private:
  static constexpr std::size_t kStaged = 64;
  // Whether the direction line must be written before the next step (a change, or unknown).
  bool direction_pending() const noexcept { return dir_level_ != dir_target(); }
  // Later steps pulse the line of `dir`.
  void turn(Direction dir) noexcept;
  // Writes the direction line for the motion's direction at t.
  void direction(Nanos t, rt::Phase phase) noexcept;
  // step(): a turn or an unwritten direction line before step s; returns the step's time.
  Nanos set_up_direction(const SourceStep& s) noexcept;
  void open_pulse(Nanos t, rt::Phase phase, std::int64_t k) noexcept;
  void whole_pulse(Nanos t, rt::Phase phase, Nanos width, std::int64_t k) noexcept;
  std::uint8_t dir_target() const noexcept {
    return step_dir_ ? (dir_ == Direction::kCcw ? kDirLevelCcw : kDirLevelCw) : 0;
  }
  rt::Edge make_edge(Nanos t, OutputLine line, std::uint8_t level, std::int8_t dpos,
                     std::uint8_t flags) const noexcept;
  std::uint8_t take_first(std::uint8_t flags) noexcept;
  void stage(const rt::Edge& e) noexcept;
  void stage_sorted(const rt::Edge& e) noexcept;

  SpscRing<rt::Edge>* ring_;
  AxisTiming timing_;

  bool step_dir_ = true;
  bool want_step_dir_ = true;  // format asked for; applied when no motion is in progress
  int dir_level_ = 0;  // -1: unknown (an aborted motion's direction edge may have been dropped)
  Nanos last_t_ = std::numeric_limits<Nanos>::min();
  Nanos last_pushed_t_ = std::numeric_limits<Nanos>::min();
  Nanos motion_floor_t_ = std::numeric_limits<Nanos>::min();  // last_t_ before the newest motion
  Nanos nonmotion_t_ = std::numeric_limits<Nanos>::min();

  // The current motion's stream.
  std::uint32_t epoch_ = 0;
  Direction dir_ = Direction::kCw;
  OutputLine line_ = OutputLine::kStep;
  std::uint8_t base_flags_ = 0;  // kMotion | kCcw | kReplacement
  bool first_pending_ = true;    // kFirst not yet given to an edge
  bool pulse_open_ = false;      // a step's leading edge staged, its trailing edge not yet
  Nanos step_t_ = 0;             // the newest step's leading edge
  std::uint8_t step_flags_ = 0;  // its flags (without kFirst)
  bool lead_edge_ = false;       // begin(): a direction edge before the first step
  Nanos lead_ = 0;               // time 0 this long after it
  rt::Phase lead_phase_ = rt::Phase::kCruise;

  std::array<rt::Edge, kStaged> staged_{};  // generated, not yet in the ring, in time order
  std::size_t staged_head_ = 0;
  std::size_t staged_count_ = 0;
  std::array<Nanos, kHistory> history_{};  // history_[k % kHistory] = time of step k
};

// The per-step path, inline.
inline rt::Edge EdgeEmitter::make_edge(Nanos t, OutputLine line, std::uint8_t level,
                                       std::int8_t dpos, std::uint8_t flags) const noexcept {
  rt::Edge e;
  e.t = t;
  e.epoch = (flags & rt::edge_flag::kMotion) != 0 ? epoch_ : 0;
  e.line = line;
  e.level = level;
  e.dpos = dpos;
  e.flags = flags;
  return e;
}

inline std::uint8_t EdgeEmitter::take_first(std::uint8_t flags) noexcept {
  if (!first_pending_) return flags;
  first_pending_ = false;
  return flags | rt::edge_flag::kFirst;
}

inline void EdgeEmitter::stage(const rt::Edge& e) noexcept {
  if (staged_count_ == kStaged) {
    // Only reachable with a ring far too small for the step rate: make room by pushing the
    // oldest edge early rather than losing an edge of the motion.
    if (!ring_->try_push(staged_[staged_head_])) return;
    last_pushed_t_ = staged_[staged_head_].t;
    staged_head_ = (staged_head_ + 1) & (kStaged - 1);
    --staged_count_;
  }
  staged_[(staged_head_ + staged_count_) & (kStaged - 1)] = e;
  ++staged_count_;
  if (e.t > last_t_) last_t_ = e.t;
}

inline Nanos EdgeEmitter::step(const SourceStep& s, std::int64_t k) noexcept {
  Nanos t = s.t;
  if (s.dir != dir_ || direction_pending()) [[unlikely]] {
    t = set_up_direction(s);
  }
  if (s.width > 0) [[unlikely]] {
    whole_pulse(t, s.phase, s.width, k);
  } else {
    open_pulse(t, s.phase, k);
  }
  return t;
}

inline void EdgeEmitter::open_pulse(Nanos t, rt::Phase phase, std::int64_t k) noexcept {
  const auto flags = static_cast<std::uint8_t>(base_flags_ | static_cast<std::uint8_t>(phase));
  if (pulse_open_) {
    // Trailing edge of the previous step: the configured width, or half the period if shorter.
    const Nanos w = std::min(timing_.step_pulse_ns, (t - step_t_) / 2);
    stage(make_edge(step_t_ + w, line_, 0, 0, step_flags_));
  }
  stage(make_edge(t, line_, 1, static_cast<std::int8_t>(sign(dir_)), take_first(flags)));
  history_[static_cast<std::size_t>(k) & (kHistory - 1)] = t;
  pulse_open_ = true;
  step_t_ = t;
  step_flags_ = flags;
}

}  // namespace stepmod::planner
