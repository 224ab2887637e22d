// Find Home + / - (3601 manual Ch.3 item 10, Ch.4 "Find Home" and its notes, Ch.6 HI/IE/PI lists;
// sequences H-A .. H-D: the step tables below; A8 A12 A15 A44 A49). The 3202 has the same four
// options; the 3602 the first two (rules.hpp).
//
// The four homing options are step tables (A12: the 3601's figures did not survive, the manual's
// written step lists are used and must stay replaceable): a table row says "in step S, on event E,
// do A and go to step T". What is common to every option (end limits, H-C; E-stop; the start) is
// code below the tables.
#include <initializer_list>
#include <span>

#include "module/axis/homing.hpp"

namespace stepmod::module::axis {

namespace {

using planner::Direction;

InputLine limit_toward(Direction d) {
  return d == Direction::kCw ? InputLine::kCwLimit : InputLine::kCcwLimit;
}

}  // namespace

struct HomingTable {
  using Step = Homing::Step;
  using Event = Homing::Event;

  enum class Action : std::uint8_t {
    kNone,
    kStopRamp,    // controlled stop with the programmed decel (to Vs, then stop)
    kSlowToVs,    // decelerate to Vs and keep running there (H-B, H-D after the proximity event)
    kStopAtHome,  // immediate stop: this is the home position
    kPause,       // the motion has ended: wait 2 s
    kRunReverse,  // opposite to the commanded direction at Vp (ramped)
    kRunCreep,    // commanded direction at Vs, no ramp
    kComplete,    // the final stop has ended: position, encoder, capture := 0, At Home
  };

  struct Row {
    Step from;
    Event on;
    Action action;
    Step to;
  };

  // Option 1, H-A: home limit switch only (3601 Ch.4 "Find Home", steps 1..7).
  static constexpr Row kSwitchOnly[] = {
      {Step::kSearch, Event::kHomeRise, Action::kStopRamp, Step::kFoundStop},     // 2-3
      {Step::kFoundStop, Event::kMotionEnd, Action::kPause, Step::kPause1},       // 3
      {Step::kReverse, Event::kHomeFall, Action::kStopRamp, Step::kReverseStop},  // 4-6
      {Step::kCreep, Event::kHomeRise, Action::kStopAtHome, Step::kFinishing},    // 7
  };

  // Option 2, H-B: home switch gated by the backplane proximity bit. The home input is ignored
  // until the bit rises; the move-off and the H-C reversal watch the bit, not the home input
  // (3601 manual Ch.4 Note 2 under "Home Limit Switch Active..."; A12).
  static constexpr Row kSwitchWithBackplane[] = {
      {Step::kSearch, Event::kProxRise, Action::kSlowToVs, Step::kApproach},
      {Step::kApproach, Event::kHomeRise, Action::kStopAtHome, Step::kFinishing},
      {Step::kReverse, Event::kProxFall, Action::kStopRamp, Step::kReverseStop},
      {Step::kCreep, Event::kProxRise, Action::kNone, Step::kApproach},  // already at Vs
  };

  // Option 3, H-D: marker pulse, the home input is the proximity.
  static constexpr Row kMarkerWithHome[] = {
      {Step::kSearch, Event::kHomeRise, Action::kSlowToVs, Step::kApproach},
      {Step::kApproach, Event::kMarker, Action::kStopAtHome, Step::kFinishing},
      {Step::kReverse, Event::kHomeFall, Action::kStopRamp, Step::kReverseStop},
      {Step::kCreep, Event::kHomeRise, Action::kNone, Step::kApproach},
  };

  // Option 4, H-D: marker pulse, the backplane bit is the proximity.
  static constexpr Row kMarkerWithBackplane[] = {
      {Step::kSearch, Event::kProxRise, Action::kSlowToVs, Step::kApproach},
      {Step::kApproach, Event::kMarker, Action::kStopAtHome, Step::kFinishing},
      {Step::kReverse, Event::kProxFall, Action::kStopRamp, Step::kReverseStop},
      {Step::kCreep, Event::kProxRise, Action::kNone, Step::kApproach},
  };

  // Every option: the pauses, the reversal, the creep and the end (H-A steps 3-7, H-C 3-7).
  static constexpr Row kCommon[] = {
      {Step::kLimitStop, Event::kMotionEnd, Action::kPause, Step::kPause1},  // H-C 3
      {Step::kPause1, Event::kPauseOver, Action::kRunReverse, Step::kReverse},
      {Step::kReverseStop, Event::kMotionEnd, Action::kPause, Step::kPause2},
      {Step::kPause2, Event::kPauseOver, Action::kRunCreep, Step::kCreep},
      {Step::kFinishing, Event::kMotionEnd, Action::kComplete, Step::kFinishing},
  };

  // The row for `ev` in `step` of homing option variant + 1 (3601 Ch.3), or nullptr.
  static const Row* find(std::uint8_t variant, Step step, Event ev) {
    static constexpr std::span<const Row> kTables[] = {kSwitchOnly, kSwitchWithBackplane,
                                                       kMarkerWithHome, kMarkerWithBackplane};
    for (const std::span<const Row> table : {kTables[variant], std::span<const Row>(kCommon)}) {
      for (const Row& r : table) {
        if (r.from == step && r.on == ev) return &r;
      }
    }
    return nullptr;
  }
};

// Find Home + / Find Home -: 3601 manual Ch.4 "Find Home".
void Homing::command(const AxisCommand& c, planner::Direction dir) {
  if (admitted(c, dir)) start(c, dir);
}

// The command's rules, in the manuals' order: false (with CE, HI or IE as each rule says) when
// the homing does not start.
bool Homing::admitted(const AxisCommand& c, planner::Direction dir) {
  // 3601-CE-03: a homing is a move; none may start while another runs.
  if (ax_.moving()) {
    ax_.reject(items::kMoveWhileMoving, "Find Home while a motion is running");
    return false;
  }
  // 3601-CE-10: "S-Curve acceleration profiles are not allowed during a homing operation."
  if (c.s_curve()) {
    ax_.reject(items::kHomeSCurve, "Find Home with an S-curve selected");
    if (ax_.rules.homing_s_curve_sets_home_invalid)
      ax_.fire(AxisEvent::kHomeInvalid);  // 3602-HI-02
    return false;
  }
  // 3601-CE-13 / HI-03: Find Home + needs a configured CW limit, Find Home - a CCW limit (not on
  // the 3602, 3602 Ch.4 "Homing the 3602").
  if (ax_.rules.homing_needs_limit_ahead && !ax_.cfg.used(limit_toward(dir))) {
    ax_.reject(items::kHomeNoLimit, "Find Home %s: no %s limit configured",
               dir == Direction::kCw ? "+" : "-", dir == Direction::kCw ? "CW" : "CCW");
    ax_.fire(AxisEvent::kHomeInvalid);
    return false;
  }
  // 3602-CE-12: a home-switch homing needs the home input configured (the 3601's configuration
  // check guarantees it there, 3601-CFG-02; the 3602 checks it at the command, 3602-CFG-N1).
  const bool switch_homing = ax_.cfg.homing == HomingVariant::kSwitch ||
                             ax_.cfg.homing == HomingVariant::kSwitchWithBackplane;
  if (switch_homing && !ax_.cfg.used(InputLine::kHome)) {
    ax_.reject(items::kHomeNoInput, "Find Home: the home input is not configured");
    return false;
  }
  // 3601-HI-02: the target words must be 0. A8: CE as well, no motion.
  if (!c.target || *c.target != 0) {
    ax_.reject(items::numbered(items::kHomeTarget, items::kHomeTargetHi, ax_.rules.type),
               "Find Home with a target %lld (must be 0)",
               static_cast<long long>(c.target.value_or(0)));
    ax_.fire(AxisEvent::kHomeInvalid);
    return false;
  }
  // 3601-CE-04 with the Home Invalid list: a homing's out-of-range speed, accel or decel raises
  // CE + HI.
  if (!ax_.speed_in_range(c.speed) || !ax_.rate_in_range(c.accel) || !ax_.rate_in_range(c.decel)) {
    ax_.reject(items::kOutOfRange, "Find Home: speed, accel or decel out of range");
    ax_.fire(AxisEvent::kHomeInvalid);
    return false;
  }
  // 3601-HI-01 / CE-05 / IP-01: Vp < Vs (IP too: the manual's IP #1 is unconditional, 6.4).
  if (*c.speed < ax_.cfg.starting_speed) {
    ax_.reject_profile(items::kVpBelowVs, "Find Home: Vp %d is below Vs %d",
                       static_cast<int>(*c.speed), static_cast<int>(ax_.cfg.starting_speed));
    ax_.fire(AxisEvent::kHomeInvalid);
    return false;
  }
  // A15: no move starts while the E-stop is active.
  if (ax_.estop_active()) {
    ax_.fire(AxisEvent::kStartBlocked);
    ax_.note(items::kStartTowardLimit, "E-stop active: homing does not start");
    return false;
  }
  return true;
}

// The sequence's first motion: away from an active home input or limit ahead, else the search.
void Homing::start(const AxisCommand& c, planner::Direction dir) {
  h_ = Sequence{};
  h_.dir = dir;
  h_.variant = static_cast<std::uint8_t>(ax_.cfg.homing);
  h_.vp = *c.speed;
  // Constant acceleration only (3601-CE-10; S-curve was refused above).
  h_.accel = {static_cast<double>(c.accel), planner::AccelShape::kConstant};
  h_.decel = {static_cast<double>(c.decel), planner::AccelShape::kConstant};
  // A44: the proximity bit acts only when configured. Its transitions count from now on.
  h_.prox = ax_.cfg.backplane_proximity && c.backplane_proximity;
  // "Home input active at the start": the home input, except for option 4 where the backplane
  // bit stands for it (3601 manual figure notes: "The Home Input shown above can be either the Home
  // Limit Switch or the Backplane Proximity bit").
  const bool home_active = ax_.cfg.homing == HomingVariant::kMarkerWithBackplane
                               ? h_.prox
                               : ax_.inputs.active(InputLine::kHome);
  // 3601 manual Ch.4 Note 2 under "End Limit Switch Active...": the limit ahead already active ->
  // begin at the reversal, no wait (H-C step 4). The opposite limit active: home normally.
  const bool limit_ahead = ax_.limit_active(dir);
  const bool reverse_first = limit_ahead || home_active;
  const Direction first = reverse_first ? planner::opposite(dir) : dir;
  // A15: a first motion into the (opposite) limit that is already active would be the limit
  // error of 3601-HI-05 at once; refuse it without moving (the position stays as it was).
  if (reverse_first && ax_.limit_active(first)) {
    ax_.fire(AxisEvent::kHomeInvalid);
    ax_.fire(AxisEvent::kStartBlocked);
    ax_.note(items::kHomingOppositeLimit, "homing: both limits active, no start");
    return;
  }

  ax_.clear_move_outcome();
  ax_.fire(AxisEvent::kHomingStarted);
  h_.limit_reversed = limit_ahead;
  h_.step = reverse_first ? Step::kReverse : Step::kSearch;
  run(first, false);
}

// Starts one motion of the sequence: Vp with ramps, or the creep at Vs without (3601 Ch.4
// "Find Home").
bool Homing::run(planner::Direction d, bool creep) {
  planner::RunSpec spec;
  spec.dir = d;
  spec.vs = ax_.cfg.starting_speed;
  spec.vp = creep ? static_cast<double>(ax_.cfg.starting_speed) : h_.vp;
  spec.accel = h_.accel;
  spec.decel = h_.decel;
  if (ax_.motion.start_run(spec) == 0) {
    // The planner queue is full: the sequence cannot go on; refuse rather than hang.
    ax_.fire(AxisEvent::kHomingStalled);
    h_.segment = false;
    ax_.reject(items::kPlannerFull, "planner queue full: homing stopped, re-home");
    return false;
  }
  ax_.dir = d;  // 3601-DIR-01: the status direction bits follow the segment under way
  ax_.move_decel = h_.decel;
  ax_.fire(AxisEvent::kHomingSegmentStarted);
  h_.segment = true;
  return true;
}

void Homing::event(Event ev) {
  using Action = HomingTable::Action;
  if (ax_.activity() != Activity::kHoming || ax_.stop_cause() != StopCause::kNone) return;
  const HomingTable::Row* row = HomingTable::find(h_.variant, h_.step, ev);
  if (row == nullptr) {
    // A motion that ended where no row expects it (a run never ends by itself): the sequence
    // cannot continue; end it as an interrupted motion.
    if (ev == Event::kMotionEnd) {
      ax_.fire(AxisEvent::kHomingEndedEarly);
      ax_.note(items::kPiFault, "homing motion ended early: re-home");
    }
    return;  // any other event has no meaning in this step (e.g. the home input in H-B search)
  }
  h_.step = row->to;
  switch (row->action) {
    case Action::kNone:
      break;
    case Action::kStopRamp:
      ax_.motion.stop(h_.decel);
      break;
    case Action::kSlowToVs:
      // Never below Vs; keep running at Vs if reached (3601 Ch.4 "Find Home", H-B step 3).
      if (h_.vp > ax_.cfg.starting_speed) {
        ax_.motion.change_speed(ax_.cfg.starting_speed, h_.accel, h_.decel);
      }
      break;
    case Action::kStopAtHome:
      // "Stop at the instant the Home input goes inactive -> active": no deceleration; the pulse
      // thread drops the rest of the motion at its next loop.
      ax_.motion.immediate_stop();
      break;
    case Action::kPause:
      h_.pause_end = -1;
      break;  // armed by the next scan
    case Action::kRunReverse:
      run(planner::opposite(h_.dir), false);
      break;
    case Action::kRunCreep:
      run(h_.dir, true);
      break;
    case Action::kComplete:
      // 3601 manual Ch.4 "Find Home": "the 3601 will set the At Home input bit, and then reset both
      // the current position and the encoder position to zero. If the capture value is present, it
      // too will be reset to zero." Done once the motion has ended, so the step count is final.
      ax_.set_position(0);
      ax_.write_encoder(0);
      ax_.capture = 0;
      ax_.fire(AxisEvent::kHomingCompleted);  // 3601-AH-01, PI-C1, HI-C1 (A7)
      break;                                  // 3601-STP-N1: no Stopped after a homing
  }
}

// An end limit became active during the homing (3601 Ch.4 "Find Home", H-C).
void Homing::limit(bool ahead) {
  if (ahead && h_.limit_reversed && (h_.step == Step::kLimitStop || h_.step == Step::kPause1)) {
    return;  // the same limit again before the reversal has begun (contact bounce): nothing new
  }
  // 3601-HI-05 / IE-05 / PI-06: the limit opposite to the commanded direction, reached first.
  // 3601-HI-04 / IE-04 / PI-05: the other limit after the reversal from the first.
  // A12: the commanded-direction limit again after that reversal is a homing failure too.
  if (!ahead || h_.limit_reversed) {
    fail();
    return;
  }
  // H-C: immediate stop ("essentially an emergency stop"), wait 2 s, reverse at Vp until the
  // home (proximity) signal has been passed, then as H-A steps 6-7.
  h_.limit_reversed = true;
  if (h_.segment) {
    ax_.motion.immediate_stop();
    h_.step = Step::kLimitStop;
  } else {
    h_.step = Step::kPause1;  // during a pause (the axis is at rest): wait 2 s anew
    h_.pause_end = -1;
  }
}

// 3601-HI-04/05, IE-04/05, PI-05/06: HI + IE + PI, immediate stop. 3601-STP-04: Stopped is
// not set for a limit met during homing.
void Homing::fail() {
  h_.limit_error = true;
  ax_.fire(AxisEvent::kHomeInvalid);
  ax_.fault_stop(items::kHomeLimitError, "homing: the wrong limit");  // immediate stop, IE, PI
}

// 3602-HI-07 (Ch.8 "Homing Timeout"): a homing not complete T seconds after the command (pauses
// included) stops and sets Home Invalid. A16: a controlled stop at the homing decel, PI unchanged.
// T = 0: no timeout (3601, 3202: always 0). The clock starts at the first scan of the sequence.
void Homing::timeout(Nanos now) {
  if (ax_.cfg.homing_timeout <= 0 || ax_.stop_cause() != StopCause::kNone ||
      h_.step == Step::kFinishing || h_.step == Step::kTimedOut) {
    return;
  }
  if (h_.deadline < 0) {
    h_.deadline = now + ax_.cfg.homing_timeout;
    return;
  }
  if (now < h_.deadline) return;
  ax_.fire(AxisEvent::kHomingTimedOut);
  ax_.note(items::kHomeTimeout, "homing timeout of %lld s expired",
           static_cast<long long>(ax_.cfg.homing_timeout / kNsPerSec));
  if (h_.segment) {
    h_.step = Step::kTimedOut;  // ends when the stop has (motion_ended)
    ax_.motion.stop(h_.decel);
  } else {
    ax_.fire(AxisEvent::kHomingOver);  // in a pause: at rest already
  }
}

void Homing::scan(const AxisCommand& c, Nanos now) {
  // The backplane proximity bit is a level of the command image; its transitions are events
  // (A44: only when configured and only while homing).
  if (ax_.cfg.backplane_proximity) {
    const bool p = c.backplane_proximity;
    if (p != h_.prox) {
      h_.prox = p;
      event(p ? Event::kProxRise : Event::kProxFall);
    }
  }
  timers(now);
}

void Homing::timers(Nanos now) {
  timeout(now);
  if (ax_.activity() != Activity::kHoming || ax_.stop_cause() != StopCause::kNone) return;
  if (h_.step != Step::kPause1 && h_.step != Step::kPause2) return;
  if (h_.pause_end < 0) {
    h_.pause_end = now + kHomingPause;  // the motion's end was seen at this scan
  } else if (now >= h_.pause_end) {
    event(Event::kPauseOver);
  }
}

void Homing::on_input(const InputEvent& e, bool was_active, bool now_active) {
  // Stopping already (home reached, error, Immediate Stop): later edges change nothing.
  if (ax_.stop_cause() != StopCause::kNone || h_.step == Step::kFinishing ||
      h_.step == Step::kTimedOut) {
    return;
  }
  // 3602-HI-06: the home input and an end limit active at the same time during homing.
  if (ax_.rules.homing_home_with_limit_is_error && now_active && !was_active &&
      ax_.inputs.active(InputLine::kHome) &&
      (ax_.limit_active(Direction::kCw) || ax_.limit_active(Direction::kCcw))) {
    fail();
    return;
  }
  // A 3602 CW / CCW input configured as an E-stop acts as one (AxisState::role_of).
  switch (ax_.role_of(e.line)) {
    case InputLine::kEStop:
      // 3601-IE-01 / PI-03 / STP-02; A49: IE + PI, no HI. The homing is a motion in progress
      // for its whole sequence, pauses included (docs/axis-states.md "States").
      if (now_active && !was_active) ax_.fault_stop(items::kEStop, "E-stop (homing)");
      return;
    case InputLine::kCwLimit:
    case InputLine::kCcwLimit:
      if (now_active && !was_active) limit(e.line == limit_toward(h_.dir));
      return;
    case InputLine::kHome:
      if (now_active != was_active) {
        event(now_active ? Event::kHomeRise : Event::kHomeFall);
      }
      return;
    case InputLine::kEncZ:
      // The marker is the encoder's Z line (no "used"/active-level configuration): high = marker.
      if (e.level) event(Event::kMarker);
      return;
    default:
      return;  // 3601 Ch.4 "Find Home": the External input has no effect; capture: generic
  }
}

void Homing::motion_ended(StopCause cause) {
  if (cause == StopCause::kImmediate || cause == StopCause::kFault) {
    // Immediate Stop command, PLC stop, E-stop or a limit error: the homing is over. PI was set
    // by immediate_stop(). 3601-STP-02/03: Stopped, except after a limit error (STP-04).
    ax_.fire(h_.limit_error ? AxisEvent::kHomingAbortedByLimit : AxisEvent::kHomingAborted);
    return;
  }
  if (!h_.segment) return;  // a pause: no motion to end
  h_.segment = false;
  if (h_.step == Step::kTimedOut) {
    ax_.fire(AxisEvent::kHomingOver);  // 3602-HI-07: the sequence is over
    return;
  }
  event(Event::kMotionEnd);
}

}  // namespace stepmod::module::axis
