// One axis: configuration and command mode, the scan, the end of a motion, and the status.
// Commands are in axis_commands.cpp, input edges in axis_inputs.cpp.
#include "module/axis/axis.hpp"

namespace stepmod::module::axis {

Axis::Axis(const ModuleRules& rules, AxisIo& io, planner::MotionPort& motion)
    : st_(rules, io, motion),
      homing_(st_),
      manual_(st_),
      blend_(st_),
      encoder_(st_),
      follower_(st_) {
  st_.inputs.init(io, motion.axis());
  quadrature_.reset(st_.inputs.level(InputLine::kEncA), st_.inputs.level(InputLine::kEncB));
  // 3601-CFG-01: power-up in command mode with Configuration Error (the 3202: without).
  if (st_.latches().configuration_error) st_.note(items::kPowerUp);
  st_.explain_new_errors();
}

void Axis::scan(const AxisCommand& c, const std::optional<AxisConfig>& configuration, Nanos now) {
  st_.scan_now = now;
  poll_motion_end();
  if (config_mode_) {
    if (c.configuration_mode) {
      take_configuration(configuration);
    } else {
      // Issue 12 item 3; 3601 Ch.3 "Configuration Mode", Ch.4 general note 3 (commands act on a
      // 0->1 transition of their bit): the image that leaves configuration mode is already a
      // command image. Commands fire on a 0->1 edge, and the configuration words of the previous
      // scans are not command words: the previous command set is empty (enter_command_mode), so
      // a command written together with the mode bit's clearing is an edge and acts now (or gets
      // the manual's Command Error: several command bits, no valid configuration). Dropping it
      // would leave the PLC with no motion, no Move Complete and no error.
      enter_command_mode();
      command_mode_scan(c, now);
    }
  } else if (c.configuration_mode) {
    // 3601-CE-01: the mode bit while moving raises CE; the move finishes first, then the axis
    // enters configuration mode and CE clears (3601 Ch.3 "the stepper controller will finish its
    // current operation").
    if (st_.moving()) {
      if (!config_after_motion_) st_.reject(items::kConfigWhileMoving);
      config_after_motion_ = true;
      if (st_.activity() == Activity::kHoming) homing_.timers(now);  // its pauses go on meanwhile
    } else {
      if (config_after_motion_) st_.fire(AxisEvent::kCommandErrorCleared);
      config_after_motion_ = false;
      config_mode_ = true;
      take_configuration(configuration);
    }
  } else {
    config_after_motion_ = false;
    command_mode_scan(c, now);
  }
  prev_ = c;
  st_.explain_new_errors();
}

// In configuration mode the words are evaluated every scan (the verdict of unchanged words is
// the same): valid -> stored for the return to command mode and CfgE = 0; invalid -> CfgE = 1.
void Axis::take_configuration(const std::optional<AxisConfig>& configuration) {
  pending_ = configuration;
  st_.fire(configuration ? AxisEvent::kConfigurationAccepted : AxisEvent::kConfigurationRefused);
  if (configuration) {
    cfg_fault_noted_ = 0;
  } else if (cfg_fault_noted_ != cfg_fault_number_ || cfg_fault_number_ == 0) {
    // Once per fault: the words are read again every configuration scan.
    cfg_fault_noted_ = cfg_fault_number_;
    const auto n = static_cast<std::uint8_t>(cfg_fault_number_);
    Item item{ErrorList::kConfiguration, {}, ""};
    item.numbers.fill(n);                     // the dialect's own number, whatever the module
    std::string_view text = cfg_fault_text_;  // "#2 neither ...": the manual's number goes
    if (text.starts_with('#') && text.find(' ') != std::string_view::npos) {
      text.remove_prefix(text.find(' ') + 1);
    }
    st_.note(item, "%.*s", static_cast<int>(text.size()), text.data());
  }
}

// Leaving configuration mode (3601 Ch.3, 3601-CFG-13, 3601-PI-01).
void Axis::enter_command_mode() {
  config_mode_ = false;
  // Edges are detected against command images from here on, not the configuration words: the
  // previous command set is empty (3601 Ch.4 general note 3; see scan()).
  prev_ = AxisCommand{};
  // 3601 Ch.4 "Registration Move": the minimum registration distance is reset by every
  // configuration (3601-LSW-01 then reads 0).
  manual_.reset_min_registration();
  blend_.erase();  // 3601-CE-20: any configuration erases the stored blend profile
  if (!pending_) {
    st_.configured = false;  // CfgE stays set; commands are refused until a valid configuration
    return;
  }
  st_.cfg = *pending_;
  st_.configured = true;
  st_.inputs.configure(st_.cfg.inputs_used, st_.cfg.inputs_active_high);
  const bool step_dir = st_.cfg.step_dir_output;
  st_.io.set_pulse_format(st_.motion.axis(), step_dir);
  st_.motion.set_pulse_format(step_dir);
  st_.set_position(0);
  // A18 (b): the encoder and capture registers are zeroed by a configuration too.
  st_.write_encoder(0);
  st_.capture = 0;
  st_.fire(AxisEvent::kConfigured);
  st_.note(items::kPiConfigured);
  held_target_ = 0;
}

void Axis::poll_motion_end() {
  busy_at_poll_ = st_.motion.busy();
  epoch_at_poll_ = st_.motion.epoch();
  cut_late_motion();
  const Activity ended = st_.activity();
  if (ended == Activity::kCoordinated) {
    follow_coordinated_steps();  // its coordinator ends it (end_coordinated)
    return;
  }
  if (ended == Activity::kIdle || ended == Activity::kFollower || busy_at_poll_) return;
  // The outcome (Move Complete, Hold, Stopped) by activity and stop cause: the table's rows for
  // MotionEnded (docs/axis-states.md). A homing sequence is several motions and pauses: it goes
  // on, and ends when Homing says.
  const StopCause cause = st_.stop_cause();
  st_.fire(AxisEvent::kMotionEnded);
  if (ended == Activity::kHoming) {
    homing_.motion_ended(cause);
  } else if (ended == Activity::kBlend) {
    blend_.motion_ended();  // CE-23's self-clear (blend.cpp)
  } else if (ended == Activity::kMove &&
             (cause == StopCause::kHold || cause == StopCause::kExternal)) {
    held_target_ = move_target_;  // 3601-HLD-01/02/03: a held move keeps its target for Resume
  }
}

// Late-edge guard (issue 12; rt::PulseEngine::set_late_limit): the pulse thread cut the motion
// rather than burst its late steps out. The PLC sees what an Immediate Stop gives (3601-STP-03,
// PI-02: Stopped, Position Invalid), so its program re-homes; immediate_stop() also ends the
// planner's side of the motion. Once: afterwards the cause is kImmediate or the axis is idle.
void Axis::cut_late_motion() {
  const StopCause cause = st_.stop_cause();
  if (st_.moving() && cause != StopCause::kImmediate && cause != StopCause::kFault &&
      st_.motion.late_faulted()) {
    st_.immediate_stop(StopCause::kImmediate);
    st_.note(items::kPiLateEdge, "late-edge fault at step %lld: re-home",
             static_cast<long long>(st_.position()));
  }
}

// The direction bits of a coordinated motion follow the axis' own steps: on a path an axis
// reverses (arcs) or never steps at all (a line along the other axis).
void Axis::follow_coordinated_steps() {
  const std::int64_t steps = st_.motion.steps();
  if (steps != coordinated_steps_) {
    st_.dir = steps > coordinated_steps_ ? planner::Direction::kCw : planner::Direction::kCcw;
    coordinated_stepped_ = true;
    coordinated_steps_ = steps;
  }
}

bool Axis::inputs_block_start(std::optional<planner::Direction> dir) {
  if (dir) return st_.inputs_block_start(*dir);
  if (!st_.estop_active()) return false;
  st_.fire(AxisEvent::kStartBlocked);
  st_.note(items::kStartTowardLimit, "E-stop active: the path does not start");
  return true;
}

void Axis::begin_coordinated(planner::Ramp decel) {
  st_.clear_move_outcome();
  st_.fire(AxisEvent::kCoordinatedBegun);
  st_.move_decel = decel;
  coordinated_steps_ = st_.motion.steps();
  coordinated_stepped_ = false;
}

void Axis::stop_coordinated(StopCause cause) {
  if (st_.activity() != Activity::kCoordinated) return;
  if (cause == StopCause::kImmediate || cause == StopCause::kFault) {
    st_.immediate_stop(cause);  // 3602-PI-04 / PI-07: both axes' positions invalid
  } else if (cause == StopCause::kHold) {
    st_.fire(AxisEvent::kHoldRequested);  // only while it is not stopping already
  } else if (cause == StopCause::kExternal) {
    st_.fire(AxisEvent::kExternalStop);
  }
}

void Axis::end_coordinated(CoordinatedEnd end) {
  // 3602-MC-01: Move Complete on every axis of the path; 3602-HLD-01: Hold on the first.
  st_.fire(end == CoordinatedEnd::kComplete ? AxisEvent::kCoordinatedCompleted
           : end == CoordinatedEnd::kHeld   ? AxisEvent::kCoordinatedHeld
                                            : AxisEvent::kCoordinatedStopped);
}

bool Axis::program_blend(const BlendFirstBlock& first,
                         std::span<const BlendSegmentBlock> segments) {
  if (config_mode_ || !st_.configured) {
    st_.fire(AxisEvent::kProfileInvalid);  // 3202-IP-15
    st_.note(items::kBlendNotConfigured);
    st_.explain_new_errors();
    return false;
  }
  const bool ok = blend_.program(first, segments);
  st_.explain_new_errors();
  return ok;
}

void Axis::plc_stopped(const Item& why) {
  // 3601-PI-07: the PLC left Run mode while moving: motion stops, position invalid.
  if (st_.moving()) {
    st_.immediate_stop(StopCause::kImmediate);
    st_.note(why);
  }
  st_.explain_new_errors();
}

// A motion submitted in this scan runs from its submission; one that ended after the poll still
// runs for this scan, and the next scan's poll gives its outcome (Move Complete, Stopped, Hold)
// together with the moving bits' clearing.
bool Axis::busy_this_scan() const noexcept {
  return st_.motion.epoch() != epoch_at_poll_ ? st_.motion.busy() : busy_at_poll_;
}

AxisStatus Axis::status() const noexcept {
  AxisStatus s;
  const Latches l = st_.latches();
  s.configuration_mode = config_mode_;
  const bool pulsing = st_.activity() != Activity::kCoordinated || coordinated_stepped_;
  if (st_.moving() && busy_this_scan() && pulsing) {
    // 3601-DIR-01: direction of the pulses being output.
    s.moving_cw = st_.dir == planner::Direction::kCw;
    s.moving_ccw = !s.moving_cw;
    // 3601-ACC-01: the phase of the edge the pulse thread last wrote.
    const auto phase = st_.motion.phase();
    s.accelerating = phase == planner::MotionPort::Phase::kAccelerating;
    s.decelerating = phase == planner::MotionPort::Phase::kDecelerating;
  }
  // 3601-DIR-01: a one-shot's direction while its command is held (prev_: this scan's image).
  if (const auto d = manual_.one_shot_direction(prev_.commands)) {
    if (*d == planner::Direction::kCw) {
      s.moving_cw = true;
    } else {
      s.moving_ccw = true;
    }
  }
  static_cast<Latches&>(s) = l;  // as latched, but for Stopped:
  if (st_.rules.stopped_means_idle) {
    s.stopped = !st_.moving();  // 3602-STP-01
  } else {
    // 3601-STP-N1: never together with MC, AH or Hld.
    s.stopped = l.stopped && !l.move_complete && !l.at_home && !l.hold;
  }
  // Logical input states (A27: unused inputs read 0) and the proximity echo, which is live
  // whether or not homing is configured (A44).
  s.inputs_active = st_.inputs.active_bits();
  s.proximity_echo = prev_.backplane_proximity;
  s.blend_running = blend_.running();
  s.blend_acknowledge = blend_.acknowledge();
  s.follower_mode = st_.activity() == Activity::kFollower;
  s.min_registration_set = manual_.min_registration_set();
  s.position = st_.position();
  s.encoder = st_.encoder;
  s.capture = st_.capture;
  return s;
}

}  // namespace stepmod::module::axis
