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

  // Each start returns the new motion's epoch (0 if the planner queue was full).
  std::uint32_t start_move(const MoveSpec& m) noexcept {
    Command c;
    c.kind = CommandKind::kMove;
    c.move = m;
    return start(c);
  }
  std::uint32_t start_run(const RunSpec& r) noexcept {
    Command c;
    c.kind = CommandKind::kRun;
    c.run = r;
    return start(c);
  }
  std::uint32_t start_blend(const BlendSpec& b) noexcept {
    Command c;
    c.kind = CommandKind::kBlend;
    c.blend = b;
    return start(c);
  }
  // Encoder follower: a follow motion (FollowSpec), then its new targets. stop() ends it once it
  // has reached its target and is at rest; immediate_stop() cuts it.
  std::uint32_t start_follow(const FollowSpec& f) noexcept {
    Command c;
    c.kind = CommandKind::kFollow;
    c.follow = f;
    return start(c);
  }
  bool follow(const FollowSpec& f) noexcept {
    Command c;
    c.kind = CommandKind::kFollowUpdate;
    c.follow = f;
    return send(c);
  }
  bool change_speed(double vp, Ramp accel, Ramp decel) noexcept {
    Command c;
    c.kind = CommandKind::kChangeSpeed;
    c.run.vp = vp;
    c.run.accel = accel;
    c.run.decel = decel;
    return send(c);
  }
  bool stop(Ramp decel) noexcept {
    Command c;
    c.kind = CommandKind::kStop;
    c.ramp = decel;
    return send(c);
  }
  bool stop_after(Nanos t, std::int64_t steps) noexcept {
    // Exactness backstop in the pulse thread (AxisControl::limit_steps): the count at t plus
    // `steps` in the motion's direction, once the motion's own edges have started to run.
    std::int64_t at_t = 0;
    if (fb_.epoch.load(std::memory_order_acquire) == epoch_ && steps_at(t, at_t)) {
      const bool ccw = (fb_.flags.load(std::memory_order_acquire) & rt::edge_flag::kCcw) != 0;
      ctl_.limit_steps.store(at_t + (ccw ? -steps : steps), std::memory_order_relaxed);
      ctl_.limit_epoch.store(epoch_, std::memory_order_release);
    }
    Command c;
    c.kind = CommandKind::kStopAfter;
    c.t = t;
    c.steps = steps;
    return send(c);
  }
  // Immediate stop: takes effect in the pulse thread at its next loop, planner or not.
  void immediate_stop() noexcept {
    ctl_.abort_epoch.store(epoch_, std::memory_order_release);
    Command c;
    c.kind = CommandKind::kAbort;
    send(c);
  }
  // The configured output format: true = step + direction, false = CW + CCW pulse lines.
  bool set_pulse_format(bool step_dir) noexcept {
    Command c;
    c.kind = CommandKind::kSetPulseFormat;
    c.level = step_dir;
    return send(c);
  }
  bool set_gpo(bool level) noexcept {
    Command c;
    c.kind = CommandKind::kSetGpo;
    c.level = level;
    return send(c);
  }

  // Feedback, as last published by the pulse thread.
  std::uint32_t epoch() const noexcept { return epoch_; }
  bool busy() const noexcept { return fb_.finished_epoch.load(std::memory_order_acquire) < epoch_; }
  std::int64_t steps() const noexcept { return fb_.steps.load(std::memory_order_acquire); }
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

  // Late-edge guard (rt::PulseEngine::set_late_limit), decoded from the pulse thread's feedback.
  struct LateFault {
    std::uint32_t count = 0;  // faults of this axis since start
    std::uint32_t epoch = 0;  // the motion last cut (0: none yet)
    std::int64_t step = 0;    // the axis step count when it was cut
    Nanos late_ns = 0;        // how late its next edge would have been written
    Nanos worst_late_ns = 0;  // the largest late_ns so far
  };
  LateFault late_fault() const noexcept {
    LateFault f;
    f.count = fb_.late_faults.load(std::memory_order_acquire);  // first: the details follow it
    f.epoch = fb_.fault_epoch.load(std::memory_order_relaxed);
    f.step = fb_.fault_step.load(std::memory_order_relaxed);
    f.late_ns = fb_.fault_late_ns.load(std::memory_order_relaxed);
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
  std::uint32_t start(Command& c) noexcept {
    c.axis = axis_;
    c.epoch = epoch_ + 1;
    if (!sink_.submit(c)) return 0;
    epoch_ = c.epoch;
    return epoch_;
  }
  bool send(Command& c) noexcept {
    c.axis = axis_;
    c.epoch = epoch_;
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
