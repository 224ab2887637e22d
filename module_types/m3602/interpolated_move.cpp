// The 3602's interpolated move: acceptance, start, the two axes kept together, the end (3602
// manual Ch.3 "Interpolated Move Profiles", Ch.9 Tables 9.9, 9.23-9.26).
#include "module_types/m3602/interpolated_move.hpp"
#include "module_types/m3602/rules_3602.hpp"

#include <cmath>
#include <cstdio>

#include "core/enum_names.hpp"
#include "module/axis/rules.hpp"
#include "module_types/m3602/circle_methods.hpp"
#include "module_types/m3602/interpolated_items.hpp"

namespace stepmod::module::m3602 {

namespace {

using axis::StopCause;
using End = axis::Axis::CoordinatedEnd;

bool is_abort(StopCause c) noexcept {
  return c == StopCause::kImmediate || c == StopCause::kFault;
}

// The direction an axis starts in along the path (A15 at the start): a line's component, an
// arc's tangent at S (S - C rotated a quarter turn in the sense of the sweep). nullopt: this
// axis does not move at first.
struct StartDirections {
  std::optional<planner::Direction> x;
  std::optional<planner::Direction> y;
};
std::optional<planner::Direction> direction_of(double v, double scale) noexcept {
  if (std::fabs(v) <= 1e-12 * scale) return std::nullopt;
  return v > 0 ? planner::Direction::kCw : planner::Direction::kCcw;
}
StartDirections start_directions(const planner::PathSpec& p) noexcept {
  if (p.shape == planner::PathShape::kLine) {
    return {direction_of(static_cast<double>(p.end_x), 1.0),
            direction_of(static_cast<double>(p.end_y), 1.0)};
  }
  // S - C = (-cx, -cy); CCW tangent (cy, -cx), CW tangent (-cy, cx).
  const double s = p.sweep > 0 ? 1.0 : -1.0;
  const double scale = std::hypot(p.centre_x, p.centre_y);
  return {direction_of(s * p.centre_y, scale), direction_of(-s * p.centre_x, scale)};
}

bool external_active(const axis::Axis& a) noexcept {
  return (a.status().inputs_active >> static_cast<unsigned>(InputLine::kExternal)) & 1u;
}

// The reason's sentence of each circle fault (3602-CE-I7), in GeometryFault order from
// kRadiiDiffer.
constexpr auto kFirstCircleFault = static_cast<std::size_t>(GeometryFault::kRadiiDiffer);
constexpr std::array<std::string_view, 5> kCircleFaultTexts = {
    "circle: start and end radii differ", "circle: end point = start point",
    "circle: the three points are on a line", "circle: radius below half the chord",
    "circle: radius above 2,147,483,647"};
static_assert(static_cast<std::size_t>(GeometryFault::kRadiusTooLarge) + 1 ==
              kFirstCircleFault + kCircleFaultTexts.size());

}  // namespace

axis::AxisCommand InterpolatedMove::filter_axis2(const axis::AxisCommand& c) {
  const axis::CommandSet rising = c.commands.rising_since(axis2_prev_);
  axis2_prev_ = c.commands;
  if (state_ == State::kRunning && !rising.empty()) {
    // 3602-CE-I2 (Immediate Stop on axis 2 does not stop the path), A46 (any other command):
    // refused, Command Error on axis 1.
    reject(items::kPathAxis2Command, "axis 2 command while a path runs");
    axis2_refused_ = axis2_refused_.with(rising);
  }
  axis2_refused_ = axis2_refused_.common(c.commands);  // released bits are forgotten
  axis::AxisCommand filtered = c;
  filtered.commands = c.commands.minus(axis2_refused_);
  return filtered;
}

void InterpolatedMove::scan(const std::optional<InterpolatedCommand>& words) {
  if (state_ == State::kRunning) {
    carry_stops();
    poll_end();
  }
  // A new move on axis 1 (or a configuration) ends the Hold state: nothing left to resume.
  if (state_ == State::kHeld && !x_.status().hold) state_ = State::kIdle;
  if (const auto p = x_.take_coordinated_resume()) resume(*p);

  // The command fires on the 0->1 edge of axis 1's interpolation bits (3602 manual Table 9.4 note).
  // In configuration mode axis 1's words are configuration words, not a command.
  const bool requested = words.has_value() && !x_.in_configuration_mode();
  const bool rising = requested && !requested_;
  requested_ = requested;
  if (rising) command(*words);
}

void InterpolatedMove::after_input() {
  if (state_ == State::kRunning) carry_stops();
}

void InterpolatedMove::command(const InterpolatedCommand& c) {
  if (!admissible(c)) return;
  if (const std::optional<planner::PathSpec> spec = path_of(c)) begin_path(*spec);
}

bool InterpolatedMove::admissible(const InterpolatedCommand& c) {
  // 3602-CE-L1: while axis 1's Command Error is set, no command is looked at.
  if (x_.status().command_error) return false;
  switch (c.fault) {
    case InterpolationFault::kNone:
      break;
    case InterpolationFault::kPattern:  // 3602-CE-I6 (A34)
      reject(items::kPathPattern, "path bits 10..14 name no method");
      return false;
    case InterpolationFault::kCommandBits:  // 3602-CE-03
      reject(items::kPathWithCommandBit, "a command MSW bit with the path bits");
      return false;
    case InterpolationFault::kReserved:  // 3602-CE-I5 / IP-18 (and CE-I4: stale words 8..15)
      reject_profile(items::kPathReserved, "reserved words of the path block not 0");
      return false;
    case InterpolationFault::kRange:  // 3602-CE-05 / IP-02
      reject_profile(axis::items::kOutOfRange, "a path coordinate out of range");
      return false;
  }
  // 3602-CE-I3: both axes configured, enabled and in command mode.
  if (refuse_not_ready(x_, 1) || refuse_not_ready(y_, 2)) return false;
  // 3602-CE-04: a move while either axis moves; the running motion is unaffected.
  if (state_ == State::kRunning || x_.moving() || y_.moving()) {
    reject(axis::items::kMoveWhileMoving, "a path while an axis moves");
    return false;
  }
  return true;
}

bool InterpolatedMove::refuse_not_ready(const axis::Axis& a, unsigned number) noexcept {
  if (a.commandable()) return false;
  const char* why = a.in_configuration_mode()    ? "is in configuration mode"
                    : a.drive_state().configured ? "is disabled"
                                                 : "is not configured";
  char text[48];
  std::snprintf(text, sizeof text, "path: axis %u %s", number, why);
  reject(items::kPathAxesNotReady, text);
  return true;
}

std::optional<planner::PathSpec> InterpolatedMove::path_of(const InterpolatedCommand& c) {
  // The vector profile: 3602-CE-05 / IP-02 ranges, 3602-CE-06 / IP-01 Vp >= Vs of axis 1 (A37).
  const axis::ModuleRules& rules = kRules3602;
  const std::int32_t vs = x_.config().starting_speed;
  const auto rate_ok = [](std::int64_t r) {
    return r >= kRules3602.accel_min && r <= kRules3602.accel_max;
  };
  if (c.speed < 1 || c.speed > rules.speed_max || !rate_ok(c.accel) || !rate_ok(c.decel)) {
    reject_profile(axis::items::kOutOfRange, "path speed, accel or decel out of range");
    return std::nullopt;
  }
  if (c.speed < vs) {
    char text[48];
    std::snprintf(text, sizeof text, "path Vp %d is below Vs %d", static_cast<int>(c.speed),
                  static_cast<int>(vs));
    reject_profile(axis::items::kVpBelowVs, text);
    return std::nullopt;
  }
  // 3602-CE-07 / IP-17: absolute coordinates need both positions valid.
  const axis::AxisStatus sx = x_.status();
  const axis::AxisStatus sy = y_.status();
  if (c.absolute && (sx.position_invalid || sy.position_invalid)) {
    reject_profile(axis::items::kAbsoluteWithPi, "absolute path with a position invalid");
    return std::nullopt;
  }
  // 3602-CE-I7 (A36) / IP-03 (A32): the geometry, or no motion.
  const PathGeometry g = path_geometry(c, sx.position, sy.position);
  if (!geometry_ok(g.fault)) return std::nullopt;
  planner::PathSpec spec = g.spec;
  spec.vs = vs;
  spec.vp = c.speed;
  spec.accel = {static_cast<double>(c.accel), c.shape};
  spec.decel = {static_cast<double>(c.decel), c.shape};
  return spec;
}

bool InterpolatedMove::geometry_ok(GeometryFault fault) noexcept {
  if (fault == GeometryFault::kNone) return true;
  if (fault == GeometryFault::kOverflow) {
    reject_profile(axis::items::kProfileOverflow, "the path does not fit 32-bit registers");
  } else {
    const std::string_view text = enum_name(fault, kCircleFaultTexts, kFirstCircleFault);
    reject_profile(items::kPathGeometry, text.data());  // of a literal: NUL-terminated
  }
  return false;
}

void InterpolatedMove::begin_path(const planner::PathSpec& spec) {
  // A15: an E-stop, or a limit ahead of an axis' first steps: Input Error, no motion. Both axes
  // are looked at, so each reports its own input.
  const StartDirections d = start_directions(spec);
  const bool x_blocked = x_.inputs_block_start(d.x);
  const bool y_blocked = y_.inputs_block_start(d.y);
  if (x_blocked || y_blocked) return;

  spec_ = spec;
  started_ = false;
  if (spec.shape == planner::PathShape::kLine && spec.end_x == 0 && spec.end_y == 0) {
    // Already at the end point: nothing to output, the move is complete on both axes.
    x_.begin_coordinated(spec.decel);
    y_.begin_coordinated(spec.decel);
    x_.end_coordinated(End::kComplete);
    y_.end_coordinated(End::kComplete);
    return;
  }
  if (external_active(x_) || external_active(y_)) {
    // A17: External active at the start: no motion, axis 1 in Hold; Resume starts the path.
    x_.begin_coordinated(spec.decel);
    y_.begin_coordinated(spec.decel);
    x_.end_coordinated(End::kHeld);
    y_.end_coordinated(End::kStopped);
    state_ = State::kHeld;
    held_y_steps_ = py_.steps();
    return;
  }
  start(false);
}

bool InterpolatedMove::start(bool resume) {
  const bool started =
      resume ? group_.resume(spec_.vp, spec_.accel, spec_.decel) : group_.start(spec_);
  if (!started) {
    reject(axis::items::kPlannerFull, "planner queue full: the path does not start");
    return false;
  }
  x_.begin_coordinated(spec_.decel);
  y_.begin_coordinated(spec_.decel);
  state_ = State::kRunning;
  started_ = true;
  return true;
}

// A stop one axis took is a stop of the path: an immediate stop (Immediate Stop on axis 1, a
// limit, an E-stop, the late-edge guard) cuts the other axis too, both positions invalid
// (3602-PI-04, PI-07); a controlled stop (Hold, External) already stops the whole path in the
// planner (MotionPort::hold_path), the other axis only learns why.
void InterpolatedMove::carry_stops() {
  const StopCause cx = x_.stop_cause();
  const StopCause cy = y_.stop_cause();
  if (is_abort(cx) || is_abort(cy)) {
    if (!is_abort(cx)) x_.stop_coordinated(StopCause::kImmediate);
    if (!is_abort(cy)) y_.stop_coordinated(StopCause::kImmediate);
    return;
  }
  if (cx != StopCause::kNone && cy == StopCause::kNone) y_.stop_coordinated(cx);
  if (cy != StopCause::kNone && cx == StopCause::kNone) x_.stop_coordinated(cy);
}

// The path has ended when both axes' parts have: the outcome on both (3602-MC-01: Move Complete
// on both axes; HLD-01: Hold on axis 1, where Resume is given).
void InterpolatedMove::poll_end() {
  if (px_.busy() || py_.busy()) return;
  const StopCause cx = x_.stop_cause();
  const StopCause cy = y_.stop_cause();
  if (is_abort(cx) || is_abort(cy)) {
    x_.end_coordinated(End::kStopped);
    y_.end_coordinated(End::kStopped);
    state_ = State::kIdle;
  } else if (cx != StopCause::kNone || cy != StopCause::kNone) {
    x_.end_coordinated(End::kHeld);
    y_.end_coordinated(End::kStopped);
    state_ = State::kHeld;
    held_y_steps_ = py_.steps();
  } else {
    x_.end_coordinated(End::kComplete);
    y_.end_coordinated(End::kComplete);
    state_ = State::kIdle;
  }
}

// Resume on axis 1 (interpolation bits 0, A39: the Resume block's speed, accel and decel as
// vector values; axis 1 has checked them and its Hold state).
void InterpolatedMove::resume(const axis::Profile& p) {
  // Axis 2 must still be where the hold left it, idle and in command mode.
  if (refuse_not_ready(y_, 2)) return;
  if (y_.moving()) {
    reject(axis::items::kMoveWhileMoving, "path Resume while axis 2 moves");
    return;
  }
  if (state_ != State::kHeld || py_.steps() != held_y_steps_) {
    reject(axis::items::kResumeNotHeld, "path Resume: axis 2 has left the path");
    return;
  }
  if (x_.inputs_block_start(std::nullopt) || y_.inputs_block_start(std::nullopt)) return;
  spec_.vp = p.vp;
  spec_.accel = p.accel;
  spec_.decel = p.decel;
  if (external_active(x_) || external_active(y_)) return;  // A17: still held, no motion
  start(started_);
}

}  // namespace stepmod::module::m3602
