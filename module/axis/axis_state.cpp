// The rules every motion of an axis shares (3601 Ch.2 "Starting Speed", Ch.4 "Hold Move", Ch.6
// "Emergency Stop Input"; A15).
#include "module/axis/axis_state.hpp"

namespace stepmod::module::axis {

Latches AxisState::latches() const noexcept {
  const auto on = [this](Latch l) { return machine_.latched(l); };
  return {.hold = on(Latch::kHold),
          .stopped = on(Latch::kStopped),
          .at_home = on(Latch::kAtHome),
          .move_complete = on(Latch::kMoveComplete),
          .home_invalid = on(Latch::kHomeInvalid),
          .invalid_profile = on(Latch::kInvalidProfile),
          .position_invalid = on(Latch::kPositionInvalid),
          .input_error = on(Latch::kInputError),
          .command_error = on(Latch::kCommandError),
          .configuration_error = on(Latch::kConfigurationError)};
}

std::optional<Profile> AxisState::read_profile(const AxisCommand& c, bool ramped) {
  // 3601-CE-04 / IP-02: speed, accel or decel outside its range.
  if (!speed_in_range(c.speed)) {
    reject_profile(items::kOutOfRange, "speed %lld out of range 0..%d",
                   static_cast<long long>(c.speed.value_or(-1)), rules.speed_max);
    return std::nullopt;
  }
  if (!rate_in_range(c.accel) || !rate_in_range(c.decel)) {
    reject_profile(items::kOutOfRange, "accel %lld or decel %lld steps/s2 out of range",
                   static_cast<long long>(c.accel), static_cast<long long>(c.decel));
    return std::nullopt;
  }
  // 3601-CE-05 / IP-01: Vp < Vs where the move ramps from the starting speed.
  if (ramped && *c.speed < cfg.starting_speed) {
    reject_profile(items::kVpBelowVs, "Vp %d is below Vs %d", static_cast<int>(*c.speed),
                   static_cast<int>(cfg.starting_speed));
    return std::nullopt;
  }
  return Profile{static_cast<double>(*c.speed),
                 {static_cast<double>(c.accel), c.shape},
                 {static_cast<double>(c.decel), c.shape}};
}

void AxisState::start_abs_rel(std::int64_t steps, const Profile& p) {
  if (inputs.active(InputLine::kExternal)) {
    if (start_move_steps(steps < 0 ? -1 : 1, p)) fire(AxisEvent::kExternalStop);
    return;
  }
  start_move_steps(steps, p);
}

bool AxisState::start_move_steps(std::int64_t steps, const Profile& p, AxisEvent started) {
  planner::MoveSpec spec;
  spec.steps = steps < 0 ? -steps : steps;
  spec.dir = steps < 0 ? planner::Direction::kCcw : planner::Direction::kCw;
  spec.vs = cfg.starting_speed;
  spec.vp = p.vp;
  spec.accel = p.accel;
  spec.decel = p.decel;
  if (motion.start_move(spec) == 0) {
    reject(items::kPlannerFull);  // refuse rather than lose the command
    return false;
  }
  fire(started);
  dir = spec.dir;
  move_decel = p.decel;
  return true;
}

InputLine AxisState::role_of(InputLine line) const noexcept {
  const auto as = [line](LimitFunction f) {
    return f == LimitFunction::kEStop ? InputLine::kEStop : line;
  };
  if (line == InputLine::kCwLimit) return as(cfg.cw_input);
  if (line == InputLine::kCcwLimit) return as(cfg.ccw_input);
  return line;
}

bool AxisState::estop_active() const noexcept {
  return inputs.active(InputLine::kEStop) ||
         (cfg.cw_input == LimitFunction::kEStop && inputs.active(InputLine::kCwLimit)) ||
         (cfg.ccw_input == LimitFunction::kEStop && inputs.active(InputLine::kCcwLimit));
}

bool AxisState::limit_active(planner::Direction d) const noexcept {
  const bool cw = d == planner::Direction::kCw;
  const auto line = cw ? InputLine::kCwLimit : InputLine::kCcwLimit;
  return (cw ? cfg.cw_input : cfg.ccw_input) == LimitFunction::kLimit && inputs.active(line);
}

bool AxisState::inputs_block_start(planner::Direction d) {
  if (!estop_active() && !limit_active(d)) return false;
  fire(AxisEvent::kStartBlocked);
  note(items::kStartTowardLimit, "%s active: the move does not start",
       estop_active()                 ? "E-stop"
       : d == planner::Direction::kCw ? "CW limit"
                                      : "CCW limit");
  return true;
}

void AxisState::clear_move_outcome() noexcept {
  // 3602-IE-C1: "if none of the inputs are active when the command is issued".
  const bool inputs_active = estop_active() || limit_active(planner::Direction::kCw) ||
                             limit_active(planner::Direction::kCcw);
  fire(inputs_active ? AxisEvent::kNewMoveInputsActive : AxisEvent::kNewMove);
}

void AxisState::immediate_stop(StopCause cause) {
  motion.immediate_stop();
  const bool commanded = cause == StopCause::kImmediate;
  fire(commanded ? AxisEvent::kImmediateStop : AxisEvent::kPathFault);
  note_position_lost(commanded ? items::kPiImmediateStop : items::kPiFault);
}

void AxisState::note_position_lost(const Item& item) noexcept {
  note(item, "stopped at %lld: the position is invalid", static_cast<long long>(position()));
}

void AxisState::fault_stop(const Item& item, const char* input) {
  // 3601-IE-01/02, PI-03/04, STP-02/04: limit / E-stop trip during a move: immediate stop, IE,
  // PI, Stopped.
  motion.immediate_stop();
  fire(AxisEvent::kInputFault);
  note_position_lost(items::kPiFault);
  note(item, "%s active: stopped at %lld", input, static_cast<long long>(position()));
}

}  // namespace stepmod::module::axis
