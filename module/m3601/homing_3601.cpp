// 3601 Find Home + / - (3601 manual Ch.3 item 10, Ch.4 "Find Home" and its notes, Ch.6 HI/IE/PI
// lists; digest 3.2, 7.11 sequences H-A .. H-D, 8 A8 A12 A15 A44 A49).
//
// The four homing options are step tables (A12: the 3601's figures did not survive, the digest's
// written step lists are used and must stay replaceable): a table row says "in step S, on event E,
// do A and go to step T". What is common to every option (end limits, H-C; E-stop; the start) is
// code below the tables.
#include <initializer_list>
#include <span>

#include "module/m3601/params_3601.hpp"
#include "module/m3601/personality_3601.hpp"
#include "module/m3601/words_3601.hpp"

namespace stepmod::module::m3601 {

namespace {

using planner::Direction;

constexpr Nanos kPause = 2 * kNsPerSec;  // digest 7.11: every homing pause is 2 s

std::uint8_t variant_of(const Config3601& c) {
  const bool marker = c.has(cfg_msw::kMarkerHoming);
  const bool backplane = c.has(cfg_msw::kBackplaneProximity);
  if (!marker) return backplane ? 1 : 0;
  return backplane ? 3 : 2;  // CFG-10/11 guarantee exactly one proximity source
}

InputLine limit_toward(Direction d) {
  return d == Direction::kCw ? InputLine::kCwLimit : InputLine::kCcwLimit;
}

}  // namespace

struct HomingTable {
  using Step = Personality3601::HomingStep;
  using Event = Personality3601::HomingEvent;

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

  // Option 1, H-A: home limit switch only (digest 7.11 H-A steps 1..7).
  static constexpr Row kSwitchOnly[] = {
      {Step::kSearch, Event::kHomeRise, Action::kStopRamp, Step::kFoundStop},     // 2-3
      {Step::kFoundStop, Event::kMotionEnd, Action::kPause, Step::kPause1},       // 3
      {Step::kReverse, Event::kHomeFall, Action::kStopRamp, Step::kReverseStop},  // 4-6
      {Step::kCreep, Event::kHomeRise, Action::kStopAtHome, Step::kFinishing},    // 7
  };

  // Option 2, H-B: home switch gated by the backplane proximity bit. The home input is ignored
  // until the bit rises; the move-off and the H-C reversal watch the bit, not the home input
  // ([01] Ch.4 Note 2 under "Home Limit Switch Active..."; A12).
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

  // The row for `ev` in `step` of homing option variant + 1 (digest 3.2 table), or nullptr.
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

// Find Home + (MSW bit 5) / Find Home - (bit 6): 3601 manual Ch.4 "Find Home".
void Personality3601::command_home(const ImageWords& out, planner::Direction dir) {
  // 3601-CE-03: a homing is a move; none may start while another runs.
  if (moving()) {
    reject();
    return;
  }
  // 3601-CE-10: "S-Curve acceleration profiles are not allowed during a homing operation."
  if (lsw_ & cmd_lsw::kSCurve) {
    reject();
    return;
  }
  // 3601-CE-13 / HI-03: Find Home + needs a configured CW limit, Find Home - a CCW limit.
  if (!cfg_.has(dir == Direction::kCw ? cfg_msw::kCwLimitUsed : cfg_msw::kCcwLimitUsed)) {
    reject();
    status_.home_invalid = true;
    return;
  }
  // 3601-HI-02: the target words must be 0. A8: CE as well, no motion.
  if (out.w[out_word::kTargetMsw] != 0 || out.w[out_word::kTargetLsw] != 0) {
    reject();
    status_.home_invalid = true;
    return;
  }
  // Digest 6.4 row 2: a homing's out-of-range speed, accel or decel raises CE + HI.
  const auto speed = speed_words(out);
  const std::int32_t accel = static_cast<std::int16_t>(out.w[out_word::kAccel]);
  const std::int32_t decel = static_cast<std::int16_t>(out.w[out_word::kDecel]);
  if (!speed || *speed > kMaxSpeed || !rate_in_range(accel) || !rate_in_range(decel)) {
    reject();
    status_.home_invalid = true;
    return;
  }
  // 3601-HI-01 / CE-05 / IP-01: Vp < Vs (IP too: the manual's IP #1 is unconditional, 6.4).
  if (*speed < cfg_.starting_speed) {
    reject_profile();
    status_.home_invalid = true;
    return;
  }
  // A15: no move starts while the E-stop is active.
  if (inputs_.active(InputLine::kEStop)) {
    status_.input_error = true;
    return;
  }

  homing_ = Homing{};
  homing_.dir = dir;
  homing_.variant = variant_of(cfg_);
  homing_.vp = *speed;
  // Constant acceleration only (digest 7.11; S-curve was refused above).
  homing_.accel = {rate_from_word(accel), planner::AccelShape::kConstant};
  homing_.decel = {rate_from_word(decel), planner::AccelShape::kConstant};
  // A44: the proximity bit acts only when configured. Its transitions count from now on.
  const bool backplane = cfg_.has(cfg_msw::kBackplaneProximity);
  homing_.prox = backplane && (lsw_ & cmd_lsw::kBackplaneProximity);
  // "Home input active at the start": the home input, except for option 4 where the backplane
  // bit stands for it ([01] figure notes: "The Home Input shown above can be either the Home
  // Limit Switch or the Backplane Proximity bit").
  const bool home_active = homing_.variant == 3 ? homing_.prox : inputs_.active(InputLine::kHome);
  // [01] Ch.4 Note 2 under "End Limit Switch Active...": the limit ahead already active -> begin
  // at the reversal, no wait (H-C step 4). The opposite limit active: home normally.
  const bool limit_ahead = inputs_.active(limit_toward(dir));
  const bool reverse_first = limit_ahead || home_active;
  const Direction first = reverse_first ? planner::opposite(dir) : dir;
  // A15: a first motion into the (opposite) limit that is already active would be the limit
  // error of 3601-HI-05 at once; refuse it without moving (the position stays as it was).
  if (reverse_first && inputs_.active(limit_toward(first))) {
    status_.home_invalid = true;
    status_.input_error = true;
    return;
  }

  clear_move_outcome();
  activity_ = Activity::kHoming;
  homing_.limit_reversed = limit_ahead;
  homing_.step = reverse_first ? HomingStep::kReverse : HomingStep::kSearch;
  homing_run(first, false);
}

// Starts one motion of the sequence: Vp with ramps, or the creep at Vs without (digest 7.11).
bool Personality3601::homing_run(planner::Direction d, bool creep) {
  planner::RunSpec run;
  run.dir = d;
  run.vs = cfg_.starting_speed;
  run.vp = creep ? static_cast<double>(cfg_.starting_speed) : homing_.vp;
  run.accel = homing_.accel;
  run.decel = homing_.decel;
  if (motion_.start_run(run) == 0) {
    // The planner queue is full: the sequence cannot go on; refuse rather than hang.
    activity_ = Activity::kIdle;
    homing_.segment = false;
    reject();
    status_.position_invalid = true;
    return false;
  }
  dir_ = d;  // 3601-DIR-01: the status direction bits follow the segment under way
  move_decel_ = homing_.decel;
  stop_cause_ = StopCause::kNone;
  homing_.segment = true;
  return true;
}

void Personality3601::homing_event(HomingEvent ev) {
  using Action = HomingTable::Action;
  if (activity_ != Activity::kHoming || stop_cause_ != StopCause::kNone) return;
  const HomingTable::Row* row = HomingTable::find(homing_.variant, homing_.step, ev);
  if (row == nullptr) {
    // A motion that ended where no row expects it (a run never ends by itself): the sequence
    // cannot continue; end it as an interrupted motion.
    if (ev == HomingEvent::kMotionEnd) {
      activity_ = Activity::kIdle;
      status_.position_invalid = true;
      status_.stopped = true;
    }
    return;  // any other event has no meaning in this step (e.g. the home input in H-B search)
  }
  homing_.step = row->to;
  switch (row->action) {
    case Action::kNone:
      break;
    case Action::kStopRamp:
      motion_.stop(homing_.decel);
      break;
    case Action::kSlowToVs:
      // Never below Vs; keep running at Vs if reached (digest 7.11 H-B step 3).
      if (homing_.vp > cfg_.starting_speed) {
        motion_.change_speed(cfg_.starting_speed, homing_.accel, homing_.decel);
      }
      break;
    case Action::kStopAtHome:
      // "Stop at the instant the Home input goes inactive -> active": no deceleration; the pulse
      // thread drops the rest of the motion at its next loop.
      motion_.immediate_stop();
      break;
    case Action::kPause:
      homing_.pause_end = -1;
      break;  // armed by the next scan
    case Action::kRunReverse:
      homing_run(planner::opposite(homing_.dir), false);
      break;
    case Action::kRunCreep:
      homing_run(homing_.dir, true);
      break;
    case Action::kComplete:
      // [01] Ch.4 "Find Home": "the 3601 will set the At Home input bit, and then reset both the
      // current position and the encoder position to zero. If the capture value is present, it
      // too will be reset to zero." Done once the motion has ended, so the step count is final.
      activity_ = Activity::kIdle;
      set_position(0);
      encoder_ = 0;
      capture_ = 0;
      status_.at_home = true;            // 3601-AH-01
      status_.position_invalid = false;  // 3601-PI-C1
      status_.home_invalid = false;      // 3601-HI-C1 (A7)
      break;                             // 3601-STP-N1: no Stopped after a homing
  }
}

// An end limit became active during the homing ([01] Ch.4 "Find Home"; digest 7.11 H-C).
void Personality3601::homing_limit(bool ahead) {
  if (ahead && homing_.limit_reversed &&
      (homing_.step == HomingStep::kLimitStop || homing_.step == HomingStep::kPause1)) {
    return;  // the same limit again before the reversal has begun (contact bounce): nothing new
  }
  // 3601-HI-05 / IE-05 / PI-06: the limit opposite to the commanded direction, reached first.
  // 3601-HI-04 / IE-04 / PI-05: the other limit after the reversal from the first.
  // A12: the commanded-direction limit again after that reversal is a homing failure too.
  if (!ahead || homing_.limit_reversed) {
    homing_fail();
    return;
  }
  // H-C: immediate stop ("essentially an emergency stop"), wait 2 s, reverse at Vp until the
  // home (proximity) signal has been passed, then as H-A steps 6-7.
  homing_.limit_reversed = true;
  if (homing_.segment) {
    motion_.immediate_stop();
    homing_.step = HomingStep::kLimitStop;
  } else {
    homing_.step = HomingStep::kPause1;  // during a pause (the axis is at rest): wait 2 s anew
    homing_.pause_end = -1;
  }
}

// Digest 6.4 "Homing overtravel error": HI + IE + PI, immediate stop. 3601-STP-04: Stopped is
// not set for a limit met during homing.
void Personality3601::homing_fail() {
  homing_.limit_error = true;
  status_.home_invalid = true;
  fault_stop();  // immediate stop, IE, PI
}

void Personality3601::homing_scan(Nanos now) {
  // The backplane proximity bit is a level in the command LSW; its transitions are events
  // (A44: only when configured and only while homing).
  if (cfg_.has(cfg_msw::kBackplaneProximity)) {
    const bool p = (lsw_ & cmd_lsw::kBackplaneProximity) != 0;
    if (p != homing_.prox) {
      homing_.prox = p;
      homing_event(p ? HomingEvent::kProxRise : HomingEvent::kProxFall);
    }
  }
  homing_timers(now);
}

void Personality3601::homing_timers(Nanos now) {
  if (activity_ != Activity::kHoming || stop_cause_ != StopCause::kNone) return;
  if (homing_.step != HomingStep::kPause1 && homing_.step != HomingStep::kPause2) return;
  if (homing_.pause_end < 0) {
    homing_.pause_end = now + kPause;  // the motion's end was seen at this scan
  } else if (now >= homing_.pause_end) {
    homing_event(HomingEvent::kPauseOver);
  }
}

void Personality3601::homing_on_input(const gpio::InputEvent& e, bool was_active, bool now_active) {
  // Stopping already (home reached, error, Immediate Stop): later edges change nothing.
  if (stop_cause_ != StopCause::kNone || homing_.step == HomingStep::kFinishing) return;
  switch (e.line) {
    case InputLine::kEStop:
      // 3601-IE-01 / PI-03 / STP-02; A49: IE + PI, no HI. The homing is a motion in progress
      // for its whole sequence, pauses included (digest 7.16).
      if (now_active && !was_active) fault_stop();
      return;
    case InputLine::kCwLimit:
    case InputLine::kCcwLimit:
      if (now_active && !was_active) homing_limit(e.line == limit_toward(homing_.dir));
      return;
    case InputLine::kHome:
      if (now_active != was_active) {
        homing_event(now_active ? HomingEvent::kHomeRise : HomingEvent::kHomeFall);
      }
      return;
    case InputLine::kEncZ:
      // The marker is the encoder's Z line (no "used"/active-level configuration): high = marker.
      if (e.level) homing_event(HomingEvent::kMarker);
      return;
    default:
      return;  // digest 7.11: the External input has no effect; capture is handled generically
  }
}

void Personality3601::homing_motion_ended(StopCause cause) {
  if (cause == StopCause::kImmediate || cause == StopCause::kFault) {
    // Immediate Stop command, PLC stop, E-stop or a limit error: the homing is over. PI was set
    // by immediate_stop(). 3601-STP-02/03: Stopped, except after a limit error (STP-04).
    activity_ = Activity::kIdle;
    if (!homing_.limit_error) status_.stopped = true;
    return;
  }
  if (!homing_.segment) return;  // a pause: no motion to end
  homing_.segment = false;
  homing_event(HomingEvent::kMotionEnd);
}

}  // namespace stepmod::module::m3601
