#pragma once
// The module layer's handle on one axis' motion. Lives in the control thread. Starting, changing
// and stopping motions go to the planner as Commands; an immediate stop also goes straight to the
// pulse thread (AxisControl::abort_epoch) so that it never waits for the planner.
#include <cstdint>

#include "planner/motion_request.hpp"
#include "rt/axis_feedback.hpp"

namespace stepmod::planner {

class CommandSink {
 public:
  virtual ~CommandSink() = default;
  // Queues a command for the planner; false if the queue is full (the caller reports an error).
  virtual bool submit(const Command& c) noexcept = 0;
  // Queues a blend start (c.what: BlendStart) with its segment table, which travels through the
  // planner's blend slot of c.axis instead of the command. False if the queue is full or the
  // axis' previous blend has not been taken by the planner yet.
  virtual bool submit_blend(Command c, const BlendSpec& b) noexcept = 0;
};

class MotionPort {
 public:
  MotionPort(unsigned axis, CommandSink& sink, rt::AxisFeedback& feedback, rt::AxisControl& control,
             const rt::StepHistory& history) noexcept
      : axis_(static_cast<std::uint8_t>(axis)),
        sink_(sink),
        fb_(feedback),
        ctl_(control),
        history_(history) {}

  // Each start returns the new motion's epoch (0 if the planner queue was full). With a group
  // tag, the motion starts on the time base of its group (GroupTag): every member axis submits
  // its start with the same tag, one after the other, in the same scan.
  std::uint32_t start_move(const MoveSpec& m, GroupTag group = {}) noexcept {
    return start(m, group);
  }
  std::uint32_t start_run(const RunSpec& r, GroupTag group = {}) noexcept {
    return start(r, group);
  }
  std::uint32_t start_blend(const BlendSpec& b, GroupTag group = {}) noexcept {
    Command c = prepare_start(BlendStart{}, group);
    if (!sink_.submit_blend(c, b)) return 0;
    return started(c);
  }
  // Interpolated path (planner/path_spec.hpp): each of the two axes' ports starts its coordinate
  // with one shared GroupTag of size 2, in the same scan. hold_path on either port stops the
  // whole path along it; resume_path (both ports, one new tag) continues it to its end.
  std::uint32_t start_path(const PathSpec& p, PathCoordinate coordinate, GroupTag group) noexcept {
    return start(PathStart{p, coordinate}, group);
  }
  std::uint32_t resume_path(PathCoordinate coordinate, double vp, Ramp accel, Ramp decel,
                            GroupTag group) noexcept {
    return start(PathResume{coordinate, vp, accel, decel}, group);
  }
  bool hold_path(Ramp decel) noexcept { return send(PathHold{decel}); }
  // Encoder follower: a follow motion (FollowSpec), then its new targets. stop() ends it once it
  // has reached its target and is at rest; immediate_stop() cuts it.
  std::uint32_t start_follow(const FollowSpec& f) noexcept { return start(FollowStart{f}, {}); }
  bool follow(const FollowSpec& f) noexcept { return send(FollowUpdate{f}); }
  bool change_speed(double vp, Ramp accel, Ramp decel) noexcept {
    return send(SpeedChange{vp, accel, decel});
  }
  // Controlled stop, planned from the newest planned step (a lookahead, ~4 ms, after now).
  bool stop(Ramp decel) noexcept { return send(StopSpec{decel, kNoTrigger}); }
  // Controlled stop whose deceleration starts at its cause's time `trigger_t` (the input edge's
  // timestamp, the scan time of a Hold), or as soon after it as the planner can still replace the
  // queued edges (StopSpec).
  bool stop(Ramp decel, Nanos trigger_t) noexcept { return send(StopSpec{decel, trigger_t}); }
  // `done_at_t`: the motion's steps output up to t, when the caller knows them (the step history
  // and the motion's start count); -1: the planner converts t with the slip of now.
  bool stop_after(Nanos t, std::int64_t steps, std::int64_t done_at_t = -1) noexcept {
    // Exactness backstop in the pulse thread (AxisControl::limit_steps): the count at t plus
    // `steps` in the motion's direction, once the motion's own edges have started to run.
    std::int64_t at_t = 0;
    if (fb_.epoch.load(std::memory_order_acquire) == epoch_ && steps_at(t, at_t)) {
      const bool ccw = (fb_.flags.load(std::memory_order_acquire) & rt::edge_flag::kCcw) != 0;
      ctl_.limit_steps.store(at_t + (ccw ? -steps : steps), std::memory_order_relaxed);
      ctl_.limit_epoch.store(epoch_, std::memory_order_release);
    }
    return send(StopAfterSpec{t, steps, done_at_t});
  }
  // Immediate stop: takes effect in the pulse thread at its next loop, planner or not.
  void immediate_stop() noexcept {
    ctl_.abort_epoch.store(epoch_, std::memory_order_release);
    send(AbortSpec{});
  }
  // The configured output format: true = step + direction, false = CW + CCW pulse lines.
  bool set_pulse_format(bool step_dir) noexcept { return send(PulseFormatSpec{step_dir}); }
  bool set_gpo(bool level) noexcept { return send(GpoSpec{level}); }

  // Feedback, as last published by the pulse thread.
  std::uint32_t epoch() const noexcept { return epoch_; }
  bool busy() const noexcept { return fb_.finished_epoch.load(std::memory_order_acquire) < epoch_; }
  std::int64_t steps() const noexcept { return fb_.steps.load(std::memory_order_acquire); }
  // When the last step counted in steps() went out (0: none yet).
  Nanos last_step_time() const noexcept {
    (void)fb_.steps.load(std::memory_order_acquire);  // stored after last_step_t
    return fb_.last_step_t.load(std::memory_order_relaxed);
  }
  // Step count at a past time t (capture, registration): exact while t is within the history.
  bool steps_at(Nanos t, std::int64_t& out) const noexcept {
    return history_.steps_at(t, steps(), out);
  }
  // Where the current motion is, from its last executed edge: what the status words' moving /
  // accelerating / decelerating bits report. kIdle when no motion of ours is running.
  enum class Phase : std::uint8_t { kIdle, kAccelerating, kCruising, kDecelerating };
  Phase phase() const noexcept {
    if (!busy() || fb_.epoch.load(std::memory_order_acquire) != epoch_) return Phase::kIdle;
    switch (rt::Edge{.flags = fb_.flags.load(std::memory_order_acquire)}.phase()) {
      case rt::Phase::kAccel:
        return Phase::kAccelerating;
      case rt::Phase::kDecel:
        return Phase::kDecelerating;
      case rt::Phase::kCruise:
        break;
    }
    return Phase::kCruising;
  }
  unsigned axis() const noexcept { return axis_; }
  // The planned interval between the last two steps output (the programmed speed there, not
  // stretched by slip); 0 before a motion's second step.
  Nanos planned_interval() const noexcept {
    return fb_.step_interval_ns.load(std::memory_order_relaxed);
  }
  // How far the motion now running has slipped behind its plan (rt/slip.hpp): its Move Complete,
  // its stops and registration distances all come that much later on the wall clock.
  Nanos slip_ns() const noexcept {
    const std::uint64_t s = fb_.slip.load(std::memory_order_acquire);
    return rt::packed_epoch(s) == epoch_ ? Nanos{rt::packed_value(s)} * kNsPerUs : 0;
  }

  // Late-edge guard (rt::PulseEngine::set_late_limit), decoded from the pulse thread's feedback.
  struct LateFault {
    std::uint32_t count = 0;  // faults of this axis since start
    std::uint32_t epoch = 0;  // the motion last cut (0: none yet)
    std::int64_t step = 0;    // the axis step count when it was cut
    Nanos late_ns = 0;        // the pause at its next step (how late it would have been written)
    std::int64_t lag = 0;     // steps due during the pause (0: at or below Vs, not judged)
    Nanos interval_ns = 0;    // the planned step interval there (0: the motion's first step)
    Nanos worst_late_ns = 0;  // the largest late_ns so far
  };
  LateFault late_fault() const noexcept {
    LateFault f;
    f.count = fb_.late_faults.load(std::memory_order_acquire);  // first: the details follow it
    f.epoch = fb_.fault_epoch.load(std::memory_order_relaxed);
    f.step = fb_.fault_step.load(std::memory_order_relaxed);
    f.late_ns = fb_.fault_late_ns.load(std::memory_order_relaxed);
    f.lag = fb_.fault_lag.load(std::memory_order_relaxed);
    f.interval_ns = fb_.fault_interval_ns.load(std::memory_order_relaxed);
    f.worst_late_ns = fb_.worst_fault_late_ns.load(std::memory_order_relaxed);
    return f;
  }
  // The motion last started was cut by the late-edge guard: the module ends it as an immediate
  // stop (the pulse thread has already dropped its edges).
  bool late_faulted() const noexcept {
    return epoch_ != 0 && fb_.late_faults.load(std::memory_order_acquire) != 0 &&
           fb_.fault_epoch.load(std::memory_order_relaxed) == epoch_;
  }

 private:
  Command prepare_start(CommandPayload what, GroupTag group) const noexcept {
    Command c;
    c.axis = axis_;
    c.epoch = epoch_ + 1;
    c.group = group;
    c.what = what;
    return c;
  }
  std::uint32_t started(const Command& c) noexcept {
    epoch_ = c.epoch;
    return epoch_;
  }
  std::uint32_t start(CommandPayload what, GroupTag group) noexcept {
    const Command c = prepare_start(what, group);
    if (!sink_.submit(c)) return 0;
    return started(c);
  }
  bool send(CommandPayload what) noexcept {
    Command c;
    c.axis = axis_;
    c.epoch = epoch_;
    c.what = what;
    return sink_.submit(c);
  }

  std::uint8_t axis_;
  CommandSink& sink_;
  rt::AxisFeedback& fb_;
  rt::AxisControl& ctl_;
  const rt::StepHistory& history_;
  std::uint32_t epoch_ = 0;
};

}  // namespace stepmod::planner
