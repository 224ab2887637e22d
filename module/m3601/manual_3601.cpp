// 3601 manual moves and registration moves (3601 manual Ch.4 "Manual Move", "Registration
// Move"; digest 7.8, 7.9) and the minimum registration distance.
#include <algorithm>
#include <cstdlib>

#include "module/m3601/params_3601.hpp"
#include "module/m3601/personality_3601.hpp"
#include "planner/profile.hpp"

namespace stepmod::module::m3601 {

// Manual Move + / - (MSW bits 7/8, level held): 3601 manual Ch.4 "Manual Move". With target
// words != 0 it is a Registration Move (A3: firmware >= 3.1 semantics; the old-firmware errors
// 3601-CE-16 / IP-08 are not emulated).
void Personality3601::command_manual(const ImageWords& out, planner::Direction dir) {
  if (moving()) {
    reject();  // 3601-CE-03
    return;
  }
  const auto target = target_words(out);
  if (!target) {
    reject_profile();  // 3601-CE-04
    return;
  }
  const auto profile = read_profile(out, false);  // Vp < Vs is legal for manual moves (CE-05)
  if (!profile) return;
  const bool registration = *target != 0;
  if (registration && !registration_start_allowed(*target, profile->vp, profile->decel)) return;
  // 3601-IE-03: a manual move toward an active end limit raises IE and does not move; so does
  // one with the E-stop active (A15).
  if (inputs_block_start(dir)) return;
  clear_move_outcome();
  activity_ = Activity::kManual;
  dir_ = dir;
  move_decel_ = profile->decel;
  stop_cause_ = StopCause::kNone;

  manual_ = ManualRun{};
  manual_.bit = dir == planner::Direction::kCw ? cmd_msw::kManualCw : cmd_msw::kManualCcw;
  for (unsigned i = 0; i < manual_.words.size(); ++i) manual_.words[i] = out.w[i];
  manual_.vp = static_cast<std::int32_t>(profile->vp);
  // Ramped mode only when the initial Vp is above Vs; otherwise constant-speed mode (digest 7.8).
  manual_.ramped = profile->vp > cfg_.starting_speed;
  if (registration) {
    manual_.kind = ManualKind::kRegistration;
    manual_.count = *target;
    // The distance in force when the move starts: a new one programmed meanwhile (MSW = 0 after
    // the bit's release) applies to the next registration move.
    manual_.dmin = min_registration_;
    manual_.start_steps = motion_.steps();
  } else if (profile->vp == 0) {
    manual_.kind = ManualKind::kOneShot;
  }
  one_shot_held_ = manual_.kind == ManualKind::kOneShot;

  // One-shot (Vp = 0, digest 7.8; 3601-STP-N1: no Stopped on release) and a start with the
  // External input active (digest 7.6: one step, then stop) both output a single pulse. A
  // registration move never gets here with the External input active (3601-CE-27).
  const bool external = inputs_.active(InputLine::kExternal);
  std::uint32_t epoch = 0;
  if (profile->vp == 0 || external) {
    planner::MoveSpec one;
    one.steps = 1;
    one.dir = dir;
    one.vs = cfg_.starting_speed;
    one.vp = cfg_.starting_speed;
    one.accel = profile->accel;
    one.decel = profile->decel;
    epoch = motion_.start_move(one);
    if (external) stop_cause_ = StopCause::kExternal;
  } else {
    planner::RunSpec run;
    run.dir = dir;
    run.vs = cfg_.starting_speed;
    run.vp = profile->vp;  // <= vs: constant-speed mode, no ramps (planner)
    run.accel = profile->accel;
    run.decel = profile->decel;
    epoch = motion_.start_run(run);
  }
  if (epoch == 0) {
    activity_ = Activity::kIdle;
    stop_cause_ = StopCause::kNone;
    one_shot_held_ = false;
    reject();
  }
}

// The start checks of a registration move (3601 manual Ch.4 "New Error Bit Functions"); false
// after raising the error. The move does not start.
bool Personality3601::registration_start_allowed(std::int32_t count, double vp,
                                                 const planner::Ramp& decel) {
  // 3601-CE-29 / IP-14: a negative registration count.
  if (count < 0) {
    reject_profile();
    return false;
  }
  // 3601-CE-04 / IP-02: the target words' range is -8,388,608 ... 8,388,607.
  if (count > kMaxTarget) {
    reject_profile();
    return false;
  }
  // Inferred (the manual does not cover it): a registration move needs a speed; a one-shot
  // (Vp = 0) has no stop condition to count from, so target != 0 with Vp = 0 is refused as an
  // invalid profile rather than silently ignoring the target.
  if (vp == 0) {
    reject_profile();
    return false;
  }
  // 3601-CE-27 / IP-12: started with the External input active, whatever the minimum distance.
  if (inputs_.active(InputLine::kExternal)) {
    reject_profile();
    return false;
  }
  // 3601-CE-28 / IP-13: fewer steps than the deceleration from Vp to Vs needs at the programmed
  // decel and type (digest 7.9 worked example: 4,950 for Vs 1,000, Vp 10,000, decel 10). The
  // small tolerance only absorbs floating-point rounding of an exact integer distance.
  if (vp > cfg_.starting_speed) {
    const double need = planner::ramp_distance(vp, cfg_.starting_speed, decel);
    if (static_cast<double>(count) < need - 1e-9 * need) {
      reject_profile();
      return false;
    }
  }
  return true;
}

// Runtime changes and bit releases, every command-mode scan.
void Personality3601::manual_scan(const ImageWords& out, Nanos now) {
  const auto msw = static_cast<std::uint16_t>(out.w[out_word::kMsw]);
  const bool held = (msw & manual_.bit) != 0;
  // 3601-DIR-01: the one-shot's direction bit stays on until its bit is reset, pulse or not.
  if (one_shot_held_ && !held) one_shot_held_ = false;
  if (activity_ != Activity::kManual) return;

  switch (manual_.kind) {
    case ManualKind::kOneShot:
      // The single pulse ends by itself; a release is no stop request (3601-STP-N1) and speed
      // changes have nothing left to act on.
      return;
    case ManualKind::kPlain:
      // A released bit was turned into a controlled stop by handle_levels in this same scan; A11:
      // then the words are not checked (zeroing all eight words is no error on this firmware).
      if (stop_cause_ != StopCause::kNone || !held) return;
      manual_runtime_checks(out);
      return;
    case ManualKind::kRegistration:
      break;
  }

  if (stop_cause_ != StopCause::kNone) {
    // After the trigger speed changes are ignored (digest 7.9 step 5), but the count still may
    // not change while the bit is held (3601-CE-31 / IP-16).
    if (manual_.triggered && held &&
        (stop_cause_ == StopCause::kRelease || stop_cause_ == StopCause::kExternal) &&
        (out.w[out_word::kTargetMsw] != manual_.words[out_word::kTargetMsw] ||
         out.w[out_word::kTargetLsw] != manual_.words[out_word::kTargetLsw])) {
      manual_error_stop();
    }
    return;
  }

  if (!held) {
    // 3601-CE-26 / A45: Hold before the registration condition has been acted on: CE and a plain
    // controlled stop with the programmed decel; the registration count is not output. (The
    // Hold bit replaces the manual bit, so this is also the scan in which the bit drops: the
    // release is not taken as the trigger.) With CE already latched the Hold command is ignored
    // (3601-CE-L1) and the release is the registration input as usual.
    const bool hold_rising = (msw & cmd_msw::kHold) && !(prev_msw_ & cmd_msw::kHold);
    if (hold_rising && !status_.command_error) {
      reject();
      stop_cause_ = StopCause::kRelease;
      motion_.stop(move_decel_);
      return;
    }
    if (manual_.released_since < 0) manual_.released_since = now;
  } else {
    manual_.released_since = -1;
    manual_runtime_checks(out);
    if (stop_cause_ != StopCause::kNone) return;  // stopped by an invalid change
  }
  // The External input's level is also followed here (its edges come through manual_on_input).
  if (!inputs_.active(InputLine::kExternal)) {
    manual_.external_since = -1;
  } else if (manual_.external_since < 0) {
    manual_.external_since = now;
  }
  Nanos since = -1;
  StopCause cause = StopCause::kNone;
  if (manual_.released_since >= 0) {
    since = manual_.released_since;
    cause = StopCause::kRelease;
  }
  if (manual_.external_since >= 0 && (since < 0 || manual_.external_since < since)) {
    since = manual_.external_since;
    cause = StopCause::kExternal;
  }
  if (since >= 0) registration_check(now, since, cause);
}

// Speed / accel / decel / target changes while the bit is held (3601 manual Ch.4 "Manual Move",
// "New Error Bit Functions").
void Personality3601::manual_runtime_checks(const ImageWords& out) {
  const auto& w = out.w;
  const bool registration = manual_.kind == ManualKind::kRegistration;
  // 3601-CE-30 / IP-15: a target written into a plain manual move (it started with 0 / 0);
  // 3601-CE-31 / IP-16: the registration count changed after the start.
  if (w[out_word::kTargetMsw] != manual_.words[out_word::kTargetMsw] ||
      w[out_word::kTargetLsw] != manual_.words[out_word::kTargetLsw]) {
    manual_error_stop();
    return;
  }
  // Accel / decel changes alone are not looked at until the speed words change.
  if (w[out_word::kSpeedMsw] == manual_.words[out_word::kSpeedMsw] &&
      w[out_word::kSpeedLsw] == manual_.words[out_word::kSpeedLsw]) {
    return;
  }
  // 3601-CE-17 / IP-09: no speed change in constant-speed mode (initial Vp <= Vs).
  if (!manual_.ramped) {
    manual_error_stop();
    return;
  }
  const auto speed = speed_words(out);
  const std::int32_t accel = static_cast<std::int16_t>(w[out_word::kAccel]);
  const std::int32_t decel = static_cast<std::int16_t>(w[out_word::kDecel]);
  // 3601-CE-19 / IP-10: the new speed (LSW outside 0..999 included) and both rates must be
  // valid; A13: a change to speed 0 counts as invalid.
  if (!speed || *speed == 0 || *speed > kMaxSpeed || !rate_in_range(accel) ||
      !rate_in_range(decel)) {
    manual_error_stop();
    return;
  }
  if (registration) {
    // 3601-CE-32 / IP-17: a registration move's speed may only be lowered (any increase over
    // the speed in force is refused: the start check of CE-28 was made for that speed).
    if (*speed > manual_.vp) {
      manual_error_stop();
      return;
    }
    // 3601-CE-33 / IP-18: accel or decel different from the start's, together with the speed.
    if (w[out_word::kAccel] != manual_.words[out_word::kAccel] ||
        w[out_word::kDecel] != manual_.words[out_word::kDecel]) {
      manual_error_stop();
      return;
    }
  }
  const planner::AccelShape shape = shape_from_lsw(lsw_);
  const planner::Ramp up{rate_from_word(accel), shape};
  const planner::Ramp down{rate_from_word(decel), shape};
  // The new speed may be below Vs (digest 7.8); the planner ramps to it with accel or decel.
  motion_.change_speed(static_cast<double>(*speed), up, down);
  move_decel_ = down;  // a later release stops with the new decel
  manual_.vp = *speed;
  for (unsigned i = out_word::kSpeedMsw; i <= out_word::kDecel; ++i) manual_.words[i] = w[i];
}

// An invalid runtime change: CE + IP and an immediate stop (A10: immediate on the 3601, and no
// PI: the 3601's PI list does not name it, and the step count stays exact). The move has
// ended, so Stopped follows as for any manual move that stopped (3601-STP-01).
void Personality3601::manual_error_stop() {
  reject_profile();
  motion_.immediate_stop();
  stop_cause_ = StopCause::kImmediate;
}

// Steps output by the running registration move up to time t, from the pulse thread's history;
// -1 if t is older than the history still held.
std::int64_t Personality3601::registration_steps_at(Nanos t) const noexcept {
  std::int64_t s = 0;
  if (!motion_.steps_at(t, s)) return -1;
  return std::llabs(s - manual_.start_steps);
}

// The registration condition has been present since `present_since` (level-triggered, digest
// 7.9 step 3). It counts once the move has output more than Dmin steps (A42: 3601 steps > Dmin;
// Dmin = 0 disables the rule). If it was already present when the (Dmin+1)-th step went out,
// the registration starts at that step's own time, found in the step history: the count after
// the trigger is then exact (R steps after step Dmin+1), independent of the scan period, as
// the firmware's step-counting would make it. Otherwise it starts at the time the condition
// appeared (the External edge's timestamp, or the scan that saw the bit reset).
void Personality3601::registration_check(Nanos now, Nanos present_since, StopCause cause) {
  Nanos t = present_since;
  const std::int64_t dmin = manual_.dmin;
  if (dmin != 0) {
    // The count is known to be <= Dmin up to `checked_until` (the last check that found it so):
    // the (Dmin+1)-th step lies after it, well inside the step history.
    const Nanos lo_bound = std::max(present_since, manual_.checked_until);
    if (registration_steps_at(lo_bound) <= dmin) {  // -1 (older than the history): too
      if (registration_steps_at(now) <= dmin) {
        manual_.checked_until = now;  // still inside the minimum distance
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
  manual_.triggered = true;
  stop_cause_ = cause;  // Stopped when the count has been output (3601-STP-01)
  // Exactly R further steps, the deceleration included (digest 7.9 step 4, planner).
  motion_.stop_after(t, manual_.count);
}

// Command LSW bit 10 rising with MSW = 0: Program Minimum Registration Move Distance (3601
// manual Ch.4 "New Command Bit"; digest 3.8).
void Personality3601::command_min_registration(const ImageWords& out) {
  // Word 1 must be exactly bit 10 and words 4..7 zero.
  if (lsw_ != cmd_lsw::kStoreMinRegistration) {
    reject();
    return;
  }
  if (!words_zero(out, out_word::kSpeedMsw, out_word::kDecel)) {
    reject();
    return;
  }
  // 3601-CE-25: outside 0 ... 8,388,607 or negative (CE only; the value in force is kept).
  const auto d = target_words(out);
  if (!d || *d < 0 || *d > kMaxTarget) {
    reject();
    return;
  }
  min_registration_ = *d;  // status LSW bit 10 = (distance != 0), 3601-LSW-01
}

// Input edges during a manual move: a registration move takes the External input as its
// trigger (digest 7.6); the limits and the E-stop keep the generic rules (inputs_3601.cpp).
bool Personality3601::manual_on_input(const gpio::InputEvent& e, bool now_active) {
  if (manual_.kind != ManualKind::kRegistration || e.line != InputLine::kExternal) {
    return false;
  }
  if (manual_.triggered || stop_cause_ != StopCause::kNone) return true;
  if (!now_active) {
    manual_.external_since = -1;
    return true;
  }
  if (manual_.external_since < 0) manual_.external_since = e.t;
  Nanos since = manual_.external_since;
  StopCause cause = StopCause::kExternal;
  if (manual_.released_since >= 0 && manual_.released_since < since) {
    since = manual_.released_since;
    cause = StopCause::kRelease;
  }
  registration_check(e.t, since, cause);
  return true;
}

std::uint16_t Personality3601::manual_status_msw() const noexcept {
  // prev_msw_ is this scan's command MSW when the status image is composed.
  if (!one_shot_held_ || !(prev_msw_ & manual_.bit)) return 0;
  return manual_.bit == cmd_msw::kManualCw ? status_msw::kMovingCw : status_msw::kMovingCcw;
}

bool Personality3601::manual_owns_release() const noexcept {
  return manual_.kind != ManualKind::kPlain;
}

}  // namespace stepmod::module::m3601
