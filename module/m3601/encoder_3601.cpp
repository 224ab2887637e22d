// 3601 encoder functions: encoder move, preset encoder, diagnostic feedback and the encoder
// follower (3601 manual Ch.4 "Encoder Move", "Preset Encoder Position", "Diagnostic Feedback",
// "Encoder Follower"; digest 7.12).
#include <algorithm>

#include "module/m3601/params_3601.hpp"
#include "module/m3601/personality_3601.hpp"

namespace stepmod::module::m3601 {

namespace {

constexpr std::uint16_t kDirectionBits = cmd_msw::kManualCw | cmd_msw::kManualCcw;
// Follower updates to the planner: at most one per this much encoder time; the rest of a burst is
// sent by the next count or the next scan (keeps the planner's command queue free at high
// encoder rates, costs at most this much latency while the master moves).
constexpr Nanos kFollowUpdateNs = 50 * kNsPerUs;
constexpr std::int32_t kMaxFollowerRate = 2000;  // words 6/7, steps/ms/s
constexpr std::int32_t kMaxFollowerRatio = 32767;

std::int64_t floor_div(std::int64_t a, std::int64_t b) noexcept {
  const std::int64_t q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

}  // namespace

// ---- Encoder move (absolute/relative with command LSW bit 2) -----------------------------------

// Called by command_move once the target, profile and CE-14 checks have passed. The target is in
// encoder counts; the motion is a Run with the programmed profile, and the deceleration starts
// when the encoder reaches the target (encoder_move_watch), so it overshoots by the deceleration
// distance, as the manual says.
void Personality3601::command_encoder_move(const ImageWords& out, bool absolute) {
  const auto target = target_words(out);
  const auto profile = read_profile(out, true);
  if (!target || !profile) return;  // command_move has already refused these
  // Absolute: compared with the encoder count, not the position, so no valid position is needed
  // (Ch.4 "Absolute Encoder moves will be negative ... if the target position is less than the
  // current encoder position"; CE-06 is about the Current Position an absolute move starts from).
  const std::int64_t goal = absolute ? static_cast<std::int64_t>(*target) : encoder_ + *target;
  const std::int64_t counts = goal - encoder_;
  const planner::Direction dir = counts < 0 ? planner::Direction::kCcw : planner::Direction::kCw;
  if (inputs_block_start(dir)) return;  // A15
  // A new move clears the previous move's outcome (3601-MC-03, HLD-C1, IE-C1, STP-C1).
  clear_move_outcome();
  if (counts == 0) {
    status_.move_complete = true;  // already on the count: nothing to output
    return;
  }
  if (inputs_.active(InputLine::kExternal)) {
    // Digest 7.6 (inferred): External already active → one step, then a stop without Hold.
    if (start_move_steps(dir == planner::Direction::kCw ? 1 : -1, *profile)) {
      activity_ = Activity::kEncoderMove;
      stop_cause_ = StopCause::kExternal;
      encoder_watch_ = false;
    }
    return;
  }
  planner::RunSpec run;
  run.dir = dir;
  run.vs = cfg_.starting_speed;
  run.vp = profile->vp;
  run.accel = profile->accel;
  run.decel = profile->decel;
  if (motion_.start_run(run) == 0) {
    reject();  // the planner queue is full: refuse rather than lose the command
    return;
  }
  activity_ = Activity::kEncoderMove;
  dir_ = dir;
  move_decel_ = profile->decel;
  stop_cause_ = StopCause::kNone;
  encoder_target_ = goal;
  encoder_watch_ = true;
  encoder_stop_pending_ = false;
}

void Personality3601::encoder_move_watch() {
  if (!encoder_watch_ || stop_cause_ != StopCause::kNone) return;
  const bool reached =
      dir_ == planner::Direction::kCw ? encoder_ >= encoder_target_ : encoder_ <= encoder_target_;
  if (!reached) return;
  encoder_watch_ = false;
  // Digest 7.12 #7: the count is compared only while command LSW bit 2 is still set; a PLC that
  // cleared MSW and LSW makes the move miss its count and keep going (only E-stop, External or
  // Immediate Stop end it then). Clearing only the MSW is harmless.
  if (!(lsw_ & cmd_lsw::kEncoderMove)) return;
  // Reaching the count is the move's normal end (StopCause::kNone → Move Complete, 3601-MC-01).
  if (!motion_.stop(move_decel_)) encoder_stop_pending_ = true;
}

// ---- Preset Encoder (MSW bit 10) ---------------------------------------------------------------

void Personality3601::command_preset_encoder(const ImageWords& out) {
  // 3601-CE-11: the quadrature encoder must be configured.
  if (!cfg_.has(cfg_msw::kQuadratureEncoder)) {
    reject();
    return;
  }
  const auto value = preset_value(out);
  if (!value) return;
  // Not under a motion that steers by the count (the manual does not say; an encoder move's
  // target would silently move). The follower cannot get here (CE-39 / CE-15).
  if (activity_ == Activity::kEncoderMove) {
    reject();
    return;
  }
  encoder_ = *value;  // position and Move Complete are left as they are
}

// ---- Per scan and per count ---------------------------------------------------------------------

void Personality3601::encoder_scan(const ImageWords& out) {
  // Diagnostic feedback (config bit 9, step/direction only): the register counts the module's
  // own pulses, one count per step with the direction line's sense. Counted incrementally, so a
  // preset, a configuration or a homing that writes the register just works.
  const std::int64_t steps = motion_.steps();
  if (cfg_.has(cfg_msw::kDiagnosticFeedback)) encoder_ += steps - diag_steps_;
  diag_steps_ = steps;

  if (activity_ == Activity::kEncoderMove && encoder_stop_pending_ && motion_.stop(move_decel_)) {
    encoder_stop_pending_ = false;
  }
  follower_scan(out, static_cast<std::uint16_t>(out.w[out_word::kMsw]));
}

void Personality3601::encoder_changed(Nanos t) {
  if (activity_ == Activity::kEncoderMove) {
    encoder_move_watch();
    return;
  }
  if (activity_ != Activity::kFollower) return;
  const std::int64_t d = encoder_ - follow_.last_encoder;
  follow_.last_encoder = encoder_;
  // No direction bit: no output, and the counts are not owed later either.
  if (follow_.sense == 0 || d == 0 || follow_.leaving) return;
  // Output = counts x multiplier / divisor; the fraction is kept so that the total is exact.
  follow_.rem += d * follow_.sense * follow_.mul;
  const std::int64_t q = floor_div(follow_.rem, follow_.div);
  follow_.rem -= q * follow_.div;
  if (follow_.count_t > 0 && t > follow_.count_t) {
    // Accel/decel 0: owed steps go out at the master's own rate (x ratio).
    const double rate = 1e9 / static_cast<double>(t - follow_.count_t);
    follow_.speed = rate * follow_.mul / follow_.div;
  }
  follow_.count_t = t;
  if (q == 0) return;
  follow_.target += q;
  dir_ = q > 0 ? planner::Direction::kCw : planner::Direction::kCcw;  // DIR-01, A24 limits
  follow_.dirty = true;
  follower_send(t, false);
}

// ---- Encoder follower (firmware 4.1) ------------------------------------------------------------
//
// Follower mode is command LSW bit 7 (status LSW bit 7 shows it, 3601-LSW-01). MSW bit 7 outputs
// steps in the encoder's sense, bit 8 in the reverse sense, neither nothing. The planner runs one
// follow motion per direction session: it is told the pulse count to reach as the encoder counts
// and closes the gap as fast as words 6/7 allow (0 = at the master's own rate).

void Personality3601::command_follower(const ImageWords& out, planner::Direction dir) {
  if (activity_ != Activity::kFollower && !follower_enter()) return;
  if (follow_.dir_bit != 0) return;  // follower_scan has seen the other bit (CE-38)
  if (!follower_params(out)) {
    follower_cut();
    return;
  }
  follow_.dir_bit = dir == planner::Direction::kCw ? cmd_msw::kManualCw : cmd_msw::kManualCcw;
  follow_.sense = dir == planner::Direction::kCw ? 1 : -1;
  follow_.last_encoder = encoder_;
  follow_.count_t = 0;
  follow_.speed = 0.0;
  if (!follow_.motion) follower_start_motion();  // else: once the previous one has finished
}

bool Personality3601::follower_enter() {
  if (status_.command_error) return false;  // 3601-CE-L1
  // 3601-CE-34: no quadrature encoder configured.
  if (!cfg_.has(cfg_msw::kQuadratureEncoder)) {
    reject();
    return false;
  }
  // 3601-CE-35: another motion is running; it runs to completion.
  if (moving()) {
    reject();
    return false;
  }
  // 3601-CE-41: S-curve acceleration cannot be used.
  if (lsw_ & cmd_lsw::kSCurve) {
    reject();
    return false;
  }
  // 3601-CE-42 / A24: "cannot be started when either of the end limit switches are active";
  // the manual names no error, the digest recommends CE.
  if (inputs_.active(InputLine::kCwLimit) || inputs_.active(InputLine::kCcwLimit)) {
    reject();
    return false;
  }
  // Entering is the start of a move operation: the previous outcome is cleared (3601-MC-03,
  // HLD-C1, IE-C1, STP-C1).
  clear_move_outcome();
  activity_ = Activity::kFollower;
  stop_cause_ = StopCause::kNone;
  dir_ = planner::Direction::kCw;
  follow_ = Follower{};
  follow_.last_encoder = encoder_;
  follow_.target = motion_.steps();
  return true;
}

// Words 2/3 multiplier and divisor (plain integers 1..32767), 4/5 zero, 6/7 accel/decel 0..2000,
// no S-curve; read when a direction bit is set and every scan while it stays set (the ratio and
// ramps may change on the fly). Without a direction bit nothing is output and the words are not
// looked at.
bool Personality3601::follower_params(const ImageWords& out) {
  const std::int32_t mul = static_cast<std::int16_t>(out.w[out_word::kTargetMsw]);
  const std::int32_t div = static_cast<std::int16_t>(out.w[out_word::kTargetLsw]);
  const std::int32_t accel = static_cast<std::int16_t>(out.w[out_word::kAccel]);
  const std::int32_t decel = static_cast<std::int16_t>(out.w[out_word::kDecel]);
  // 3601-CE-36: multiplier or divisor outside 1..32767.
  if (mul < 1 || mul > kMaxFollowerRatio || div < 1 || div > kMaxFollowerRatio) {
    reject();
    return false;
  }
  // 3601-CE-37: the speed words must be 0.
  if (out.w[out_word::kSpeedMsw] != 0 || out.w[out_word::kSpeedLsw] != 0) {
    reject();
    return false;
  }
  // 3601-CE-41: S-curve selected.
  if (lsw_ & cmd_lsw::kSCurve) {
    reject();
    return false;
  }
  // 3601-CE-04 / IP-02: accel or decel outside the follower's 0..2000.
  if (accel < 0 || accel > kMaxFollowerRate || decel < 0 || decel > kMaxFollowerRate) {
    reject_profile();
    return false;
  }
  if (div != follow_.div) {
    // The fraction already owed is carried over to the new divisor (less than one step lost at
    // most, once per change).
    follow_.rem = floor_div(follow_.rem * div, follow_.div);
  }
  if (accel != follow_.accel || decel != follow_.decel) follow_.dirty = true;
  follow_.mul = mul;
  follow_.div = div;
  follow_.accel = accel;
  follow_.decel = decel;
  return true;
}

planner::FollowSpec Personality3601::follower_spec() const noexcept {
  planner::FollowSpec f;
  f.target = follow_.target - follow_.base;
  f.vs = cfg_.starting_speed;
  f.vmax = kMaxSpeed;
  // Rate not known yet (first count): the starting speed, which any motor can jump to.
  const double vs = std::max(1.0, static_cast<double>(cfg_.starting_speed));
  f.speed =
      std::clamp(follow_.speed > 0.0 ? follow_.speed : vs, vs, static_cast<double>(kMaxSpeed));
  f.accel = follow_.accel > 0 ? rate_from_word(follow_.accel) : 0.0;
  f.decel = follow_.decel > 0 ? rate_from_word(follow_.decel) : 0.0;
  return f;
}

void Personality3601::follower_start_motion() {
  follow_.base = motion_.steps();  // no motion of ours is busy: the count is final
  if (motion_.start_follow(follower_spec()) == 0) return;  // queue full: the next scan retries
  follow_.running = true;
  follow_.motion = true;
  follow_.dirty = false;
  follow_.sent_t = 0;
}

void Personality3601::follower_send(Nanos t, bool force) {
  if (!follow_.dirty || !follow_.running) return;
  if (!force && follow_.sent_t != 0 && t - follow_.sent_t < kFollowUpdateNs) return;
  if (motion_.follow(follower_spec())) {
    follow_.dirty = false;
    follow_.sent_t = force ? 0 : t;
  }
}

void Personality3601::follower_cut() {
  // "the 3601 module will stop outputting steps": the pulse train is cut. Not an Immediate Stop
  // command, and the position register still counts every step output: PI is not set.
  if (follow_.motion) motion_.immediate_stop();
  follower_exit();
}

void Personality3601::follower_exit() {
  activity_ = Activity::kIdle;
  stop_cause_ = StopCause::kNone;
  status_.stopped = true;  // 3601-STP-05: set after leaving encoder-follower mode
  follow_ = Follower{};
}

void Personality3601::follower_scan(const ImageWords& out, std::uint16_t msw) {
  const bool lsw7 = (lsw_ & cmd_lsw::kEncoderFollower) != 0;
  const bool was7 = (prev_lsw_ & cmd_lsw::kEncoderFollower) != 0;
  const auto rising = static_cast<std::uint16_t>(msw & ~prev_msw_);
  const std::uint16_t dirs = msw & kDirectionBits;

  // 3601-CE-39: any command bit but 7/8 (Hold included) while LSW bit 7 is set. Raised before the
  // command is dispatched, which then ignores it (CE-L1).
  if (lsw7 && (rising & (cmd_msw::kCommandMask | cmd_msw::kReserved14) &
               static_cast<std::uint16_t>(~kDirectionBits))) {
    reject();
    if (activity_ == Activity::kFollower) follower_cut();
    return;
  }

  if (activity_ != Activity::kFollower) {
    if (!lsw7 || was7 || status_.command_error) return;
    // LSW bit 7 rising: follower mode (a direction bit rising in the same scan then starts the
    // output in command_follower).
    if (moving()) {
      reject();  // 3601-CE-35: the running motion completes
      return;
    }
    follower_enter();
    return;
  }

  // The follow motion has ended.
  if (follow_.motion && !motion_.busy()) {
    follow_.motion = false;
    follow_.running = false;
  }
  if (stop_cause_ == StopCause::kFault || stop_cause_ == StopCause::kImmediate) {
    // E-stop, a limit in the output direction (A24) or the PLC leaving Run: fault_stop /
    // immediate_stop have set IE/PI; follower mode is left once the pulses have stopped.
    if (!follow_.motion) follower_exit();
    return;
  }
  if (follow_.leaving) {
    if (!follow_.motion) follower_exit();
    return;
  }
  if (!lsw7) {
    if (dirs != 0) {
      reject();  // 3601-CE-40: LSW bit 7 cleared while a direction bit is still set
      follower_cut();
      return;
    }
    // Leaving follower mode: the steps already owed still go out (the count stays exact), then
    // the motion ends and Stopped is set (3601-STP-05).
    follow_.leaving = true;
    follow_.sense = 0;
    if (follow_.running) {
      follower_send(0, true);
      motion_.stop(move_decel_);
      follow_.running = false;
    }
    if (!follow_.motion) follower_exit();
    return;
  }
  // 3601-CE-41 on the fly.
  if (lsw_ & cmd_lsw::kSCurve) {
    reject();
    follower_cut();
    return;
  }
  if (follow_.dir_bit != 0) {
    if (dirs == kDirectionBits || (dirs != 0 && dirs != follow_.dir_bit)) {
      // 3601-CE-38: the direction changed without a scan with the command word at 0 (both bits
      // at once is CE-02 as well).
      reject();
      follower_cut();
      return;
    }
    if (dirs == 0) {
      // No direction bit: no more output; the steps already owed still go out.
      follow_.dir_bit = 0;
      follow_.sense = 0;
      if (follow_.running) {
        follower_send(0, true);
        motion_.stop(move_decel_);
        follow_.running = false;
      }
      return;
    }
    // Ratio and ramps may change on the fly (checked every scan).
    if (!follower_params(out)) {
      follower_cut();
      return;
    }
    if (!follow_.motion) follower_start_motion();
    follower_send(0, true);
  }
}

}  // namespace stepmod::module::m3601
