// Input edges of one axis, each at its own timestamp (3601 manual Ch.1 "Inputs", Ch.6 "Emergency
// Stop Input", "External Input", "Capture Input"): the encoder, capture, and the limits, E-stop
// and External input of every motion but homing (which has its own rules, homing.cpp).
#include "module/axis/axis.hpp"

namespace stepmod::module::axis {

void Axis::on_input(const InputEvent& e) {
  input_edge(e);
  st_.explain_new_errors();  // an edge that set an error bit without a note
}

void Axis::input_edge(const InputEvent& e) {
  const bool was_active = st_.inputs.active(e.line);
  st_.inputs.set_level(e.line, e.level);

  if (e.line == InputLine::kEncA || e.line == InputLine::kEncB) {
    // X4 decoding runs on every edge so the decoder never loses the phase; the register counts
    // only while the quadrature encoder is configured (moving or not, digest 7.12), and only the
    // edges after its last write (AxisState::write_encoder).
    const int d =
        quadrature_.update(st_.inputs.level(InputLine::kEncA), st_.inputs.level(InputLine::kEncB));
    if (d != 0 && st_.configured && st_.cfg.quadrature_encoder && st_.counts_encoder_edge(e.t)) {
      st_.encoder += d;
      encoder_changed(e.t);
    }
    return;
  }
  if (!st_.configured || config_mode_) return;
  const bool now_active = st_.inputs.active(e.line);
  if (st_.activity == Activity::kHoming) {
    // Homing has its own rules for the home input, the marker, the limits and the E-stop.
    homing_.on_input(e, was_active, now_active);
    if (e.line != InputLine::kCapture) return;
  }
  if (now_active == was_active) return;

  if (now_active && e.line == InputLine::kCapture) {
    // Capture: the encoder count if the quadrature encoder is configured, otherwise the motor
    // position, latched at the edge's own time (digest 7.13).
    if (st_.cfg.quadrature_encoder) {
      st_.capture = st_.encoder;
    } else {
      std::int64_t steps_then = 0;
      st_.capture =
          (st_.motion.steps_at(e.t, steps_then) ? steps_then : st_.motion.steps()) - st_.origin;
    }
    return;
  }
  if (!st_.moving() || st_.stop_cause == StopCause::kImmediate ||
      st_.stop_cause == StopCause::kFault) {
    return;
  }
  if (st_.activity == Activity::kManual && manual_.on_input(e, now_active)) return;

  // A 3602 CW / CCW input acts as configured: an end limit, an E-stop, or nothing.
  const InputLine role = st_.role_of(e.line);
  if (now_active && role == InputLine::kEStop) {
    st_.fault_stop(items::kEStop, e.line == InputLine::kEStop     ? "E-stop"
                                  : e.line == InputLine::kCwLimit ? "CW input (E-stop)"
                                                                  : "CCW input (E-stop)");
    // 3601-IE-01, PI-03, STP-02; 3602-IE-01, PI-03
    return;
  }
  if (now_active && (role == InputLine::kCwLimit || role == InputLine::kCcwLimit)) {
    const bool cw_limit = e.line == InputLine::kCwLimit;
    // 3601-IE-02 / PI-04 / STP-04: absolute and relative moves stop at either limit; a manual
    // move only at the limit in its direction of travel, so that it can be driven off a limit.
    const bool in_travel_direction = cw_limit == (st_.dir == planner::Direction::kCw);
    const bool either_limit = st_.activity == Activity::kMove || st_.activity == Activity::kBlend ||
                              st_.activity == Activity::kEncoderMove ||
                              st_.activity == Activity::kCoordinated;  // digest 7.7
    if (either_limit || in_travel_direction) {                         // blends too (3601-IE-02)
      st_.fault_stop(items::kLimitInMove, cw_limit ? "CW limit" : "CCW limit");
    }
    return;
  }
  // Digest 7.10 rule 8: blends ignore the External input.
  if (now_active && e.line == InputLine::kExternal && st_.stop_cause == StopCause::kNone &&
      st_.activity != Activity::kBlend && st_.activity != Activity::kFollower) {  // 7.6
    // 3601-HLD-02: a controlled stop to the Hold state for absolute/relative moves; a
    // controlled stop (Stopped) for manual moves (digest 7.6).
    st_.stop_cause = StopCause::kExternal;
    if (st_.activity == Activity::kCoordinated) {
      st_.motion.hold_path(st_.move_decel);  // the whole path stops along it (digest 7.6)
    } else {
      st_.motion.stop(st_.move_decel, e.t);  // the ramp starts at the edge (issue 12 item 9)
    }
  }
}

void Axis::encoder_changed(Nanos t) {
  if (st_.activity == Activity::kEncoderMove) {
    encoder_.watch(prev_, t);  // prev_: the command image in force (the last scan's)
    return;
  }
  follower_.counted(t);
}

}  // namespace stepmod::module::axis
