// Encoder functions of one axis: the encoder move, Preset Encoder and diagnostic feedback (3601
// manual Ch.4 "Encoder Move", "Preset Encoder Position", "Diagnostic Feedback").
// The encoder register itself is AxisState::encoder (homing, configuration and capture use it).
#include "module/axis/encoder.hpp"

namespace stepmod::module::axis {

// ---- Encoder move ----------------------------------------------------------------------------

// Called by the axis's absolute/relative move once the target, profile and CE-14 checks have
// passed. The target is in encoder counts; the motion is a Run with the programmed profile, and the
// deceleration starts when the encoder reaches the target (watch), so it overshoots by the
// deceleration distance, as the manual says.
void Encoder::move(const AxisCommand& c, bool absolute) {
  const auto& target = c.target;
  const auto profile = ax_.read_profile(c, true);
  if (!target || !profile) return;  // command_move has already refused these
  // Absolute: compared with the encoder count, not the position, so no valid position is needed
  // (Ch.4 "Absolute Encoder moves will be negative ... if the target position is less than the
  // current encoder position"; CE-06 is about the Current Position an absolute move starts from).
  const std::int64_t goal = absolute ? static_cast<std::int64_t>(*target) : ax_.encoder + *target;
  const std::int64_t counts = goal - ax_.encoder;
  const planner::Direction dir = counts < 0 ? planner::Direction::kCcw : planner::Direction::kCw;
  if (ax_.inputs_block_start(dir)) return;  // A15
  // A new move clears the previous move's outcome (3601-MC-03, HLD-C1, IE-C1, STP-C1).
  ax_.clear_move_outcome();
  if (counts == 0) {
    ax_.fire(AxisEvent::kAtTarget);  // already on the count: nothing to output
    return;
  }
  if (ax_.inputs.active(InputLine::kExternal)) {
    // 3601 Ch.6 "External Input" (inferred for encoder moves): External already active → one step,
    // then a stop without Hold.
    if (ax_.start_move_steps(dir == planner::Direction::kCw ? 1 : -1, *profile,
                             AxisEvent::kEncoderMoveStarted)) {
      ax_.fire(AxisEvent::kExternalStop);
      watch_ = false;
    }
    return;
  }
  planner::RunSpec run;
  run.dir = dir;
  run.vs = ax_.cfg.starting_speed;
  run.vp = profile->vp;
  run.accel = profile->accel;
  run.decel = profile->decel;
  if (ax_.motion.start_run(run) == 0) {
    ax_.reject(
        items::kPlannerFull);  // the planner queue is full: refuse rather than lose the command
    return;
  }
  ax_.fire(AxisEvent::kEncoderMoveStarted);
  ax_.dir = dir;
  ax_.move_decel = profile->decel;
  target_ = goal;
  watch_ = true;
  stop_pending_ = false;
}

void Encoder::watch(const AxisCommand& c, Nanos t) {
  if (!watch_ || ax_.stop_cause() != StopCause::kNone) return;
  const bool reached =
      ax_.dir == planner::Direction::kCw ? ax_.encoder >= target_ : ax_.encoder <= target_;
  if (!reached) return;
  watch_ = false;
  // 3601 Ch.4 "Encoder Move": the count is compared only while the encoder-move flag is still set;
  // a PLC that cleared it makes the move miss its count and keep going (only E-stop, External or
  // Immediate Stop end it then). Clearing only the command is harmless.
  if (!c.encoder_move) return;
  // Reaching the count is the move's normal end (StopCause::kNone → Move Complete, 3601-MC-01).
  // The ramp starts at the count's own time (issue 12 item 9), not after the queued edges.
  if (!ax_.motion.stop(ax_.move_decel, t)) stop_pending_ = true;
}

// ---- Preset Encoder --------------------------------------------------------------------------

void Encoder::preset(const AxisCommand& c) {
  // 3601-CE-11: the quadrature encoder must be configured.
  if (!ax_.cfg.quadrature_encoder) {
    ax_.reject(items::kPresetEncoderNoEncoder);
    return;
  }
  // The dialect's word rules (3601-CE-09 / CE-15) were checked at dispatch; 3601-CE-04: range.
  if (!ax_.target_in_range(c.target)) {
    ax_.reject(items::kOutOfRange, "encoder preset out of range");
    return;
  }
  // Not under a motion that steers by the count (the manual does not say; an encoder move's
  // target would silently move). The follower cannot get here (CE-39 / CE-15).
  if (ax_.activity() == Activity::kEncoderMove) {
    ax_.reject(items::kMoveWhileMoving, "Preset Encoder while an encoder move runs");
    return;
  }
  ax_.write_encoder(*c.target);  // position and Move Complete are left as they are
}

// ---- Per scan --------------------------------------------------------------------------------

void Encoder::scan() {
  // Diagnostic feedback (step/direction only): the register counts the module's
  // own pulses, one count per step with the direction line's sense. Counted incrementally, so a
  // preset, a configuration or a homing that writes the register just works.
  const std::int64_t steps = ax_.motion.steps();
  if (ax_.cfg.diagnostic_feedback) ax_.encoder += steps - diag_steps_;
  diag_steps_ = steps;

  if (ax_.activity() == Activity::kEncoderMove && stop_pending_ &&
      ax_.motion.stop(ax_.move_decel)) {
    stop_pending_ = false;
  }
}

}  // namespace stepmod::module::axis
