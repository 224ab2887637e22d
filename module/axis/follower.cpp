// The encoder follower (3601 manual Ch.4 "Encoder Follower", firmware 4.1).
#include <algorithm>

#include "module/axis/follower.hpp"

namespace stepmod::module::axis {

namespace {

// Follower updates to the planner: at most one per this much encoder time; the rest of a burst is
// sent by the next count or the next scan (keeps the planner's command queue free at high
// encoder rates, costs at most this much latency while the master moves).
constexpr Nanos kFollowUpdateNs = 50 * kNsPerUs;
constexpr std::int32_t kMaxFollowerRatio = 32767;  // multiplier and divisor 1 ... 32767

std::int64_t floor_div(std::int64_t a, std::int64_t b) noexcept {
  const std::int64_t q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

}  // namespace

void Follower::counted(Nanos t) {
  if (ax_.activity() != Activity::kFollower) return;
  const std::int64_t d = ax_.encoder - f_.last_encoder;
  f_.last_encoder = ax_.encoder;
  // No direction bit: no output, and the counts are not owed later either.
  if (f_.sense == 0 || d == 0 || f_.leaving) return;
  // Output = counts x multiplier / divisor; the fraction is kept so that the total is exact.
  f_.rem += d * f_.sense * f_.mul;
  const std::int64_t q = floor_div(f_.rem, f_.div);
  f_.rem -= q * f_.div;
  if (f_.count_t > 0 && t > f_.count_t) {
    // Accel/decel 0: owed steps go out at the master's own rate (x ratio).
    const double rate = 1e9 / static_cast<double>(t - f_.count_t);
    f_.speed = rate * f_.mul / f_.div;
  }
  f_.count_t = t;
  if (q == 0) return;
  f_.target += q;
  ax_.dir = q > 0 ? planner::Direction::kCw : planner::Direction::kCcw;  // DIR-01, A24 limits
  f_.dirty = true;
  send(t, false);
}

// ---- Encoder follower (firmware 4.1) ------------------------------------------------------------
//
// Follower mode is a level flag, shown in the status (3601-LSW-01). Manual + outputs steps in the
// encoder's sense, Manual - in the reverse sense, neither nothing. The planner runs one follow
// motion per direction session: it is told the pulse count to reach as the encoder counts and
// closes the gap as fast as accel/decel allow (0 = at the master's own rate).

void Follower::command(const AxisCommand& c, planner::Direction dir) {
  if (ax_.activity() != Activity::kFollower && !enter(c)) return;
  if (f_.key) return;  // scan() has seen the other direction (CE-38)
  if (!params(c)) {
    cut();
    return;
  }
  f_.key = dir == planner::Direction::kCw ? CommandKind::kManualCw : CommandKind::kManualCcw;
  f_.sense = dir == planner::Direction::kCw ? 1 : -1;
  f_.last_encoder = ax_.encoder;
  f_.count_t = 0;
  f_.speed = 0.0;
  if (!f_.motion) start_motion();  // else: once the previous one has finished
}

bool Follower::enter(const AxisCommand& c) {
  if (ax_.latches().command_error) return false;  // 3601-CE-L1
  // 3601-CE-34: no quadrature encoder configured.
  if (!ax_.cfg.quadrature_encoder) {
    ax_.reject(items::kFollowerNoEncoder);
    return false;
  }
  // 3601-CE-35: another motion is running; it runs to completion.
  if (ax_.moving()) {
    ax_.reject(items::kFollowerWhileMoving);
    return false;
  }
  // 3601-CE-41: S-curve acceleration cannot be used.
  if (c.s_curve()) {
    ax_.reject(items::kFollowerSCurve);
    return false;
  }
  // 3601-CE-42 / A24: "cannot be started when either of the end limit switches are active";
  // the manual names no error; CE, as for the other follower refusals.
  if (ax_.inputs.active(InputLine::kCwLimit) || ax_.inputs.active(InputLine::kCcwLimit)) {
    ax_.reject(items::kFollowerLimit);
    return false;
  }
  // Entering is the start of a move operation: the previous outcome is cleared (3601-MC-03,
  // HLD-C1, IE-C1, STP-C1).
  ax_.clear_move_outcome();
  ax_.fire(AxisEvent::kFollowerEntered);
  ax_.dir = planner::Direction::kCw;
  f_ = Session{};
  f_.last_encoder = ax_.encoder;
  f_.target = ax_.motion.steps();
  return true;
}

// Multiplier and divisor (plain integers 1..32767), speed 0, accel/decel 0..the module's maximum
// (0 = at the master's rate), no S-curve; read when a direction is set and every scan while it
// stays set (the ratio and ramps may change on the fly). Without a direction nothing is output
// and the parameters are not looked at.
bool Follower::params(const AxisCommand& c) {
  const std::int32_t mul = c.ratio_multiplier;
  const std::int32_t div = c.ratio_divisor;
  const std::int64_t accel = c.accel;
  const std::int64_t decel = c.decel;
  // 3601-CE-36: multiplier or divisor outside 1..32767.
  if (mul < 1 || mul > kMaxFollowerRatio || div < 1 || div > kMaxFollowerRatio) {
    ax_.reject(items::kFollowerRatio, "follower ratio %lld/%lld out of 1..32767",
               static_cast<long long>(mul), static_cast<long long>(div));
    return false;
  }
  // 3601-CE-37: the speed words must be 0.
  if (!c.speed || *c.speed != 0) {
    ax_.reject(items::kFollowerSpeed);
    return false;
  }
  // 3601-CE-41: S-curve selected.
  if (c.s_curve()) {
    ax_.reject(items::kFollowerSCurve);
    return false;
  }
  // 3601-CE-04 / IP-02: accel or decel outside the follower's 0 ... maximum (rules.hpp).
  if (accel < 0 || accel > ax_.rules.accel_max || decel < 0 || decel > ax_.rules.accel_max) {
    ax_.reject_profile(items::kOutOfRange, "follower accel or decel out of range");
    return false;
  }
  if (div != f_.div) {
    // The fraction already owed is carried over to the new divisor (less than one step lost at
    // most, once per change).
    f_.rem = floor_div(f_.rem * div, f_.div);
  }
  if (accel != f_.accel || decel != f_.decel) f_.dirty = true;
  f_.mul = mul;
  f_.div = div;
  f_.accel = accel;
  f_.decel = decel;
  return true;
}

planner::FollowSpec Follower::spec() const noexcept {
  planner::FollowSpec f;
  f.target = f_.target - f_.base;
  f.vs = ax_.cfg.starting_speed;
  f.vmax = ax_.rules.speed_max;
  // Rate not known yet (first count): the starting speed, which any motor can jump to.
  const double vs = std::max(1.0, static_cast<double>(ax_.cfg.starting_speed));
  f.speed =
      std::clamp(f_.speed > 0.0 ? f_.speed : vs, vs, static_cast<double>(ax_.rules.speed_max));
  f.accel = static_cast<double>(f_.accel);  // 0 = jump
  f.decel = static_cast<double>(f_.decel);
  return f;
}

void Follower::start_motion() {
  f_.base = ax_.motion.steps();  // no motion of ours is busy: the count is final
  if (ax_.motion.start_follow(spec()) == 0) return;  // queue full: the next scan retries
  f_.running = true;
  f_.motion = true;
  f_.dirty = false;
  f_.sent_t = 0;
}

void Follower::send(Nanos t, bool force) {
  if (!f_.dirty || !f_.running) return;
  if (!force && f_.sent_t != 0 && t - f_.sent_t < kFollowUpdateNs) return;
  if (ax_.motion.follow(spec())) {
    f_.dirty = false;
    f_.sent_t = force ? 0 : t;
  }
}

void Follower::cut() {
  // "the 3601 module will stop outputting steps": the pulse train is cut. Not an Immediate Stop
  // command, and the position register still counts every step output: PI is not set.
  if (f_.motion) ax_.motion.immediate_stop();
  exit();
}

void Follower::exit() {
  ax_.fire(AxisEvent::kFollowerLeft);  // 3601-STP-05: Stopped after leaving follower mode
  f_ = Session{};
}

void Follower::scan(const AxisCommand& c, const AxisCommand& prev) {
  const bool follower_flag = c.follower;
  const CommandSet rising = c.commands.rising_since(prev.commands);
  // 3601-CE-39: any command but Manual + / - (Hold included) while the follower flag is set.
  // Raised before the command is dispatched, which then ignores it (CE-L1).
  if (follower_flag && !rising.without(CommandKind::kManualCw, CommandKind::kManualCcw).empty()) {
    ax_.reject(items::kFollowerOtherCommand);
    if (ax_.activity() == Activity::kFollower) cut();
    return;
  }
  if (ax_.activity() != Activity::kFollower) {
    if (follower_flag && !prev.follower && !ax_.latches().command_error) flag_rose(c);
    return;
  }
  // The follow motion has ended.
  if (f_.motion && !ax_.motion.busy()) {
    f_.motion = false;
    f_.running = false;
  }
  if (ax_.stop_cause() == StopCause::kFault || ax_.stop_cause() == StopCause::kImmediate) {
    // E-stop, a limit in the output direction (A24) or the PLC leaving Run: fault_stop /
    // immediate_stop have set IE/PI; follower mode is left once the pulses have stopped.
    if (!f_.motion) exit();
    return;
  }
  if (f_.leaving) {
    if (!f_.motion) exit();
    return;
  }
  if (!follower_flag) {
    flag_cleared(c);
  } else if (c.s_curve()) {
    // 3601-CE-41 on the fly.
    ax_.reject(items::kFollowerSCurve);
    cut();
  } else if (f_.key) {
    steer(c);
  }
}

void Follower::flag_rose(const AxisCommand& c) {
  // The follower flag rising: follower mode (a direction bit rising in the same scan then starts
  // the output in command_follower).
  if (ax_.moving()) {
    ax_.reject(items::kFollowerWhileMoving);  // 3601-CE-35: the running motion completes
    return;
  }
  enter(c);
}

void Follower::flag_cleared(const AxisCommand& c) {
  if (c.commands.has(CommandKind::kManualCw) || c.commands.has(CommandKind::kManualCcw)) {
    // 3601-CE-40: the flag cleared while a direction is still set.
    ax_.reject(items::kFollowerReleased);
    cut();
    return;
  }
  // Leaving follower mode: the steps already owed still go out (the count stays exact), then
  // the motion ends and Stopped is set (3601-STP-05).
  f_.leaving = true;
  stop_output();
  if (!f_.motion) exit();
}

void Follower::steer(const AxisCommand& c) {
  const bool cw = c.commands.has(CommandKind::kManualCw);
  const bool ccw = c.commands.has(CommandKind::kManualCcw);
  if (*f_.key == CommandKind::kManualCw ? ccw : cw) {
    // 3601-CE-38: the direction changed without a scan with the command word at 0 (both bits
    // at once is CE-02 as well).
    ax_.reject(items::kFollowerDirection);
    cut();
    return;
  }
  if (!cw && !ccw) {
    // No direction bit: no more output; the steps already owed still go out.
    f_.key.reset();
    stop_output();
    return;
  }
  // Ratio and ramps may change on the fly (checked every scan).
  if (!params(c)) {
    cut();
    return;
  }
  if (!f_.motion) start_motion();
  send(0, true);
}

void Follower::stop_output() {
  f_.sense = 0;
  if (f_.running) {
    send(0, true);
    ax_.motion.stop(ax_.move_decel);
    f_.running = false;
  }
}

}  // namespace stepmod::module::axis
