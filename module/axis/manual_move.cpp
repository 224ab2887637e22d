// Manual (jog) moves and registration moves (3601 manual Ch.4 "Manual Move", "Registration
// Move") and the minimum registration distance.
#include <algorithm>
#include <cstdlib>

#include "module/axis/manual_move.hpp"
#include "planner/profile.hpp"

namespace stepmod::module::axis {

// Manual Move + / - (level held): 3601 manual Ch.4 "Manual Move". With target
// words != 0 it is a Registration Move (A3: firmware >= 3.1 semantics; the old-firmware errors
// 3601-CE-16 / IP-08 are not emulated).
void ManualMove::command(const AxisCommand& c, planner::Direction dir, Nanos now) {
  if (ax_.moving()) {
    ax_.reject(items::kMoveWhileMoving, "a jog while a motion is running");  // 3601-CE-03
    return;
  }
  const auto target = c.target;
  if (!target) {
    ax_.reject_profile(items::kOutOfRange, "jog target words out of range");  // 3601-CE-04
    return;
  }
  const auto profile = ax_.read_profile(c, false);  // Vp < Vs is legal for manual moves (CE-05)
  if (!profile) return;
  const bool registration = *target != 0;
  if (registration && !registration_start_allowed(*target, profile->vp, profile->decel)) return;
  // 3601-IE-03: a manual move toward an active end limit raises IE and does not move; so does
  // one with the E-stop active (A15).
  if (ax_.inputs_block_start(dir)) return;
  ax_.clear_move_outcome();
  ax_.dir = dir;
  ax_.move_decel = profile->decel;
  begin_run(c, dir, *profile, now);
  // A plain manual move started with the External input active outputs one step, then stops
  // (3601 Ch.6 "External Input"). A registration move gets here with the External input active
  // only where a minimum distance allows it (3602 Ch.4 "Registration Move"; never on the 3601,
  // 3601-CE-27): it runs, and the active input triggers it once the minimum distance is out.
  const bool external = !registration && ax_.inputs.active(InputLine::kExternal);
  if (start_motion(dir, *profile, external) == 0) {
    one_shot_held_ = false;
    ax_.reject(items::kPlannerFull);  // refuse rather than lose the command
    return;
  }
  ax_.fire(AxisEvent::kManualStarted);
  if (external) ax_.fire(AxisEvent::kExternalStop);
}

// The run's parameters at its start, and its kind: registration (a count), one-shot (Vp = 0) or
// plain.
void ManualMove::begin_run(const AxisCommand& c, planner::Direction dir, const Profile& p,
                           Nanos now) {
  run_ = Run{};
  run_.key = dir == planner::Direction::kCw ? CommandKind::kManualCw : CommandKind::kManualCcw;
  run_.target = c.target;
  run_.speed = c.speed;
  run_.accel = c.accel;
  run_.decel = c.decel;
  run_.vp = static_cast<std::int32_t>(p.vp);
  // Ramped mode only when the initial Vp is above Vs; otherwise constant-speed mode (3601 Ch.4
  // "Manual Move").
  run_.ramped = p.vp > ax_.cfg.starting_speed;
  if (*c.target != 0) {
    run_.kind = Kind::kRegistration;
    run_.count = *c.target;
    // The distance in force when the move starts: a new one programmed meanwhile (no command set
    // after the bit's release) applies to the next registration move.
    run_.dmin = min_registration_;
    run_.start_steps = ax_.motion.steps();
    run_.start_t = now;
  } else if (p.vp == 0) {
    run_.kind = Kind::kOneShot;
  }
  one_shot_held_ = run_.kind == Kind::kOneShot;
}

// The planner's motion: a single pulse for a one-shot (Vp = 0; 3601-STP-N1: no Stopped on
// release) or with the External input active, else a run. The motion's epoch; 0: refused.
std::uint32_t ManualMove::start_motion(planner::Direction dir, const Profile& p, bool external) {
  if (p.vp == 0 || external) {
    planner::MoveSpec one;
    one.steps = 1;
    one.dir = dir;
    one.vs = ax_.cfg.starting_speed;
    one.vp = ax_.cfg.starting_speed;
    one.accel = p.accel;
    one.decel = p.decel;
    return ax_.motion.start_move(one);
  }
  planner::RunSpec run;
  run.dir = dir;
  run.vs = ax_.cfg.starting_speed;
  run.vp = p.vp;  // <= vs: constant-speed mode, no ramps (planner)
  run.accel = p.accel;
  run.decel = p.decel;
  return ax_.motion.start_run(run);
}

// The start checks of a registration move (3601 manual Ch.4 "New Error Bit Functions"); false
// after raising the error. The move does not start.
bool ManualMove::registration_start_allowed(std::int32_t count, double vp,
                                            const planner::Ramp& decel) {
  // 3202-CE-12 / IP-07: a module without registration moves takes no target with a jog.
  if (!ax_.rules.has_registration) {
    ax_.reject_profile(items::kJogWithTarget, "manual move with target %d (must be 0)",
                       static_cast<int>(count));
    return false;
  }
  // 3601-CE-29 / IP-14: a negative registration count.
  if (count < 0) {
    ax_.reject_profile(items::kRegNegative);
    return false;
  }
  // 3601-CE-04 / IP-02: the target words' range (3601: -8,388,608 ... 8,388,607).
  if (count > ax_.rules.registration_max) {
    ax_.reject_profile(items::kOutOfRange, "registration count out of range");
    return false;
  }
  // Inferred (the manual does not cover it): a registration move needs a speed; a one-shot
  // (Vp = 0) has no stop condition to count from, so target != 0 with Vp = 0 is refused as an
  // invalid profile rather than silently ignoring the target.
  if (vp == 0) {
    ax_.reject_profile(items::kOutOfRange, "registration move at speed 0");
    return false;
  }
  // 3601-CE-27 / IP-12: started with the External input active, whatever the minimum distance
  // (the 3602 only with a minimum distance of 0, 3602 Ch.2 "Registration Move").
  if (ax_.inputs.active(InputLine::kExternal) &&
      (ax_.rules.registration_external_always_error || min_registration_ == 0)) {
    ax_.reject_profile(items::kRegExternal);
    return false;
  }
  // 3601-CE-28 / IP-13: fewer steps than the deceleration from Vp to Vs needs at the programmed
  // decel and type (3601 Ch.4 "Registration Move": 4,950 for Vs 1,000, Vp 10,000, decel 10). The
  // small tolerance only absorbs floating-point rounding of an exact integer distance.
  if (vp > ax_.cfg.starting_speed) {
    const double need = planner::ramp_distance(vp, ax_.cfg.starting_speed, decel);
    if (static_cast<double>(count) < need - 1e-9 * need) {
      ax_.reject_profile(items::kRegTooShort);
      return false;
    }
  }
  return true;
}

// Runtime changes and bit releases, every command-mode scan.
void ManualMove::scan(const AxisCommand& c, const CommandSet& rising, Nanos now) {
  const bool held = c.commands.has(run_.key);
  // 3601-DIR-01: the one-shot's direction bit stays on until its bit is reset, pulse or not.
  if (one_shot_held_ && !held) one_shot_held_ = false;
  if (ax_.activity() != Activity::kManual) return;

  switch (run_.kind) {
    case Kind::kOneShot:
      // The single pulse ends by itself; a release is no stop request (3601-STP-N1) and speed
      // changes have nothing left to act on.
      return;
    case Kind::kPlain:
      // A released bit was turned into a controlled stop by levels() in this same scan; A11:
      // then the words are not checked (zeroing all eight words is no error on this firmware).
      if (ax_.stop_cause() != StopCause::kNone || !held) return;
      runtime_checks(c);
      return;
    case Kind::kRegistration:
      registration_scan(c, rising, held, now);
      return;
  }
}

// A registration move's scan: the count may not change, a Hold before the trigger, the release
// and the External input as the registration condition (3601 Ch.4 "Registration Move").
void ManualMove::registration_scan(const AxisCommand& c, const CommandSet& rising, bool held,
                                   Nanos now) {
  if (ax_.stop_cause() != StopCause::kNone) {
    // After the trigger speed changes are ignored, but the count still may not change while the
    // bit is held (3601-CE-31 / IP-16).
    const StopCause cause = ax_.stop_cause();
    if (run_.triggered && held && (cause == StopCause::kRelease || cause == StopCause::kExternal) &&
        c.target != run_.target) {
      error_stop(items::kRegCountChanged);
    }
    return;
  }
  if (!held) {
    if (hold_before_trigger(rising)) return;
    if (run_.released_since < 0) run_.released_since = now;
  } else {
    run_.released_since = -1;
    runtime_checks(c);
    if (ax_.stop_cause() != StopCause::kNone) return;  // stopped by an invalid change
  }
  // The External input's level is also followed here (its edges come through on_input).
  if (!ax_.inputs.active(InputLine::kExternal)) {
    run_.external_since = -1;
  } else if (run_.external_since < 0) {
    run_.external_since = now;
  }
  Nanos since = -1;
  StopCause cause = StopCause::kNone;
  if (run_.released_since >= 0) {
    since = run_.released_since;
    cause = StopCause::kRelease;
  }
  if (run_.external_since >= 0 && (since < 0 || run_.external_since < since)) {
    since = run_.external_since;
    cause = StopCause::kExternal;
  }
  if (since >= 0) registration_check(now, since, cause);
}

// 3601-CE-26 / A45: Hold before the registration condition has been acted on: CE and a plain
// controlled stop with the programmed decel; the registration count is not output. (The Hold bit
// replaces the manual bit, so this is also the scan in which the bit drops: the release is not
// taken as the trigger.) With CE already latched the Hold command is ignored (3601-CE-L1) and the
// release is the registration input as usual. True when the Hold was acted on.
bool ManualMove::hold_before_trigger(const CommandSet& rising) {
  if (!rising.has(CommandKind::kHold) || ax_.latches().command_error) return false;
  ax_.reject(items::kHoldNotHoldable, "Hold during a registration move");
  if (ax_.fire(AxisEvent::kReleaseStop)) ax_.motion.stop(ax_.move_decel);
  return true;
}

// Speed / accel / decel / target changes while the bit is held (3601 manual Ch.4 "Manual Move",
// "New Error Bit Functions").
void ManualMove::runtime_checks(const AxisCommand& c) {
  const bool registration = run_.kind == Kind::kRegistration;
  // 3601-CE-30 / IP-15: a target written into a plain manual move (it started with 0 / 0);
  // 3601-CE-31 / IP-16: the registration count changed after the start.
  if (c.target != run_.target) {
    error_stop(registration ? items::kRegCountChanged : items::kJogTargetWritten);
    return;
  }
  // Accel / decel changes alone are not looked at until the speed words change.
  if (c.speed == run_.speed) {
    return;
  }
  // 3601-CE-17 / IP-09: no speed change in constant-speed mode (initial Vp <= Vs).
  if (!run_.ramped) {
    error_stop(items::kJogConstantSpeed);
    return;
  }
  const auto& speed = c.speed;
  // 3601-CE-19 / IP-10: the new speed (an unencodable one included) and both rates must be
  // valid; A13: a change to speed 0 counts as invalid.
  if (!ax_.speed_in_range(speed) || *speed == 0 || !ax_.rate_in_range(c.accel) ||
      !ax_.rate_in_range(c.decel)) {
    error_stop(speed && *speed == 0 ? items::kJogSpeedZero : items::kJogInvalidChange);
    return;
  }
  if (registration) {
    // 3601-CE-32 / IP-17: a registration move's speed may only be lowered (any increase over
    // the speed in force is refused: the start check of CE-28 was made for that speed).
    if (*speed > run_.vp) {
      error_stop(items::kRegSpeedIncreased);
      return;
    }
    // 3601-CE-33 / IP-18: accel or decel different from the start's, together with the speed.
    if (c.accel != run_.accel || c.decel != run_.decel) {
      error_stop(items::kRegRatesChanged);
      return;
    }
  }
  const planner::Ramp up{static_cast<double>(c.accel), c.shape};
  const planner::Ramp down{static_cast<double>(c.decel), c.shape};
  // The new speed may be below Vs (3601 Ch.4 "Manual Move"); the planner ramps to it with accel or
  // decel.
  ax_.motion.change_speed(static_cast<double>(*speed), up, down);
  ax_.move_decel = down;  // a later release stops with the new decel
  run_.vp = *speed;
  run_.speed = c.speed;
  run_.accel = c.accel;
  run_.decel = c.decel;
}

// An invalid runtime change: CE + IP and an immediate stop (A10: immediate on the 3601, and no
// PI: the 3601's PI list does not name it, and the step count stays exact). The move has
// ended, so Stopped follows as for any manual move that stopped (3601-STP-01). `why`: the item.
void ManualMove::error_stop(const Item& why) {
  ax_.reject_profile(why);
  ax_.motion.immediate_stop();
  ax_.fire(AxisEvent::kInvalidChange);
}

// Steps output by the running registration move up to time t, from the pulse thread's history;
// -1 if t is older than the history still held.
std::int64_t ManualMove::registration_steps_at(Nanos t) const noexcept {
  std::int64_t s = 0;
  if (!ax_.motion.steps_at(t, s)) return -1;
  return std::llabs(s - run_.start_steps);
}

// The registration condition has been present since `present_since` (level-triggered, 3601 Ch.4
// "Registration Move" step 3). It counts once the move has output more than Dmin steps (A42: 3601
// steps > Dmin; Dmin = 0 disables the rule). If it was already present when the (Dmin+1)-th step
// went out, the registration starts at that step's own time, found in the step history: the count
// after the trigger is then exact (R steps after step Dmin+1), independent of the scan period, as
// the firmware's step-counting would make it. Otherwise it starts at the time the condition
// appeared (the External edge's timestamp, or the scan that saw the bit reset).
void ManualMove::registration_check(Nanos now, Nanos present_since, StopCause cause) {
  // A condition present since before the move started (an External edge stamped then and
  // delivered late) counts from the start: the steps of a motion before it are not this move's.
  present_since = std::max(present_since, run_.start_t);
  Nanos t = present_since;
  const std::int64_t dmin = run_.dmin;
  if (dmin != 0) {
    // The count is known to be <= Dmin up to `checked_until` (the last check that found it so):
    // the (Dmin+1)-th step lies after it, well inside the step history.
    const Nanos lo_bound = std::max(present_since, run_.checked_until);
    if (registration_steps_at(lo_bound) <= dmin) {  // -1 (older than the history): too
      if (registration_steps_at(now) <= dmin) {
        run_.checked_until = now;  // still inside the minimum distance
        return;
      }
      // Earliest time in (lo_bound, now] with more than Dmin steps: that step's own time.
      Nanos lo = lo_bound;
      Nanos hi = now;
      while (hi - lo > 1) {
        const Nanos mid = lo + (hi - lo) / 2;
        if (registration_steps_at(mid) > dmin) {
          hi = mid;
        } else {
          lo = mid;
        }
      }
      t = hi;
    } else {
      t = lo_bound;
    }
  }
  run_.triggered = true;
  // Stopped when the count has been output (3601-STP-01).
  ax_.fire(cause == StopCause::kRelease ? AxisEvent::kReleaseStop : AxisEvent::kExternalStop);
  // Exactly R further steps, the deceleration included (3601 Ch.4 "Registration Move", planner).
  ax_.motion.stop_after(t, run_.count, registration_steps_at(t));
}

// The store bit rising with no command bit set: Program Minimum Registration Move Distance (3601
// manual Ch.4 "New Command Bit").
void ManualMove::store_min_registration(const AxisCommand& c) {
  // The dialect's word rules (words that must be 0 with the store flag).
  if (c.words_invalid) {
    ax_.reject(items::kWordsNotZero, "words that must be 0 with the store flag are not");
    return;
  }
  // 3601-CE-25: outside 0 ... 8,388,607 or negative (CE only; the value in force is kept).
  const auto& d = c.target;
  if (!d || *d < 0 || *d > ax_.rules.registration_max) {
    ax_.reject(items::kMinRegRange);
    return;
  }
  min_registration_ = *d;  // shown as "distance set" (3601-LSW-01)
}

// Input edges during a manual move: a registration move takes the External input as its
// trigger (3601 Ch.6 "External Input"); the limits and the E-stop keep the generic rules
// (axis_inputs.cpp).
bool ManualMove::on_input(const InputEvent& e, bool now_active) {
  if (run_.kind != Kind::kRegistration || e.line != InputLine::kExternal) {
    return false;
  }
  if (run_.triggered || ax_.stop_cause() != StopCause::kNone) return true;
  if (!now_active) {
    run_.external_since = -1;
    return true;
  }
  if (run_.external_since < 0) run_.external_since = e.t;
  Nanos since = run_.external_since;
  StopCause cause = StopCause::kExternal;
  if (run_.released_since >= 0 && run_.released_since < since) {
    since = run_.released_since;
    cause = StopCause::kRelease;
  }
  registration_check(e.t, since, cause);
  return true;
}

std::optional<planner::Direction> ManualMove::one_shot_direction(
    const CommandSet& held) const noexcept {
  if (!one_shot_held_ || !held.has(run_.key)) return std::nullopt;
  return run_.key == CommandKind::kManualCw ? planner::Direction::kCw : planner::Direction::kCcw;
}

// Level-held: the manual move runs while its command is held.
void ManualMove::levels(const AxisCommand& c) {
  if (ax_.activity() != Activity::kManual || ax_.stop_cause() != StopCause::kNone) return;
  if (owns_release()) return;  // one-shot / registration: scan() handles the release
  if (!c.commands.has(run_.key)) {
    // 3601-STP-01: releasing the bit is a controlled stop to the starting speed. Acted on even
    // while CE is set: a stop request is never ignored. A11: only the command word needs to be
    // cleared; on current firmware zeroing all eight words is not an error.
    if (ax_.fire(AxisEvent::kReleaseStop)) ax_.motion.stop(ax_.move_decel);
  }
}

bool ManualMove::owns_release() const noexcept {
  return run_.kind != Kind::kPlain;
}

}  // namespace stepmod::module::axis
