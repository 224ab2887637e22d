// 3601 discrete inputs and encoder: what an input edge does, at the edge's own timestamp
// (3601 manual Ch.1 "Inputs", Ch.6 "Emergency Stop Input", "External Input", "Capture Input").
#include "module/m3601/personality_3601.hpp"
#include "module/m3601/words_3601.hpp"

namespace stepmod::module::m3601 {

void Personality3601::on_input(const gpio::InputEvent& e) {
  const bool was_active = inputs_.active(e.line);
  inputs_.set_level(e.line, e.level);

  if (e.line == InputLine::kEncA || e.line == InputLine::kEncB) {
    // X4 decoding runs on every edge so the decoder never loses the phase; the register counts
    // only while the quadrature encoder is configured (moving or not, digest 7.12).
    const int d =
        quadrature_.update(inputs_.level(InputLine::kEncA), inputs_.level(InputLine::kEncB));
    if (d != 0 && configured_ && cfg_.has(cfg_msw::kQuadratureEncoder)) {
      encoder_ += d;
      encoder_changed(e.t);
    }
    return;
  }
  if (!configured_ || config_mode_) return;
  const bool now_active = inputs_.active(e.line);
  if (activity_ == Activity::kHoming) {
    // Homing has its own rules for the home input, the marker, the limits and the E-stop.
    homing_on_input(e, was_active, now_active);
    if (e.line != InputLine::kCapture) return;
  }
  if (now_active == was_active) return;

  if (now_active && e.line == InputLine::kCapture) {
    // Capture: the encoder count if the quadrature encoder is configured, otherwise the motor
    // position, latched at the edge's own time (digest 7.13).
    if (cfg_.has(cfg_msw::kQuadratureEncoder)) {
      capture_ = encoder_;
    } else {
      std::int64_t steps_then = 0;
      capture_ = (motion_.steps_at(e.t, steps_then) ? steps_then : motion_.steps()) - origin_;
    }
    return;
  }
  if (!moving() || stop_cause_ == StopCause::kImmediate || stop_cause_ == StopCause::kFault) return;
  if (activity_ == Activity::kManual && manual_on_input(e, now_active)) return;

  if (now_active && e.line == InputLine::kEStop) {
    fault_stop();  // 3601-IE-01, PI-03, STP-02
    return;
  }
  if (now_active && (e.line == InputLine::kCwLimit || e.line == InputLine::kCcwLimit)) {
    const bool cw_limit = e.line == InputLine::kCwLimit;
    // 3601-IE-02 / PI-04 / STP-04: absolute and relative moves stop at either limit; a manual
    // move only at the limit in its direction of travel, so that it can be driven off a limit.
    const bool in_travel_direction = cw_limit == (dir_ == planner::Direction::kCw);
    const bool either_limit = activity_ == Activity::kMove || activity_ == Activity::kBlend ||
                              activity_ == Activity::kEncoderMove;  // digest 7.7
    if (either_limit || in_travel_direction) fault_stop();          // blends too (3601-IE-02)
    return;
  }
  // Digest 7.10 rule 8: blends ignore the External input.
  if (now_active && e.line == InputLine::kExternal && stop_cause_ == StopCause::kNone &&
      activity_ != Activity::kBlend && activity_ != Activity::kFollower) {  // 7.6: no effect
    // 3601-HLD-02: a controlled stop to the Hold state for absolute/relative moves; a
    // controlled stop (Stopped) for manual moves (digest 7.6).
    stop_cause_ = StopCause::kExternal;
    motion_.stop(move_decel_, e.t);  // the ramp starts at the edge (issue 12 item 9)
  }
}

}  // namespace stepmod::module::m3601
