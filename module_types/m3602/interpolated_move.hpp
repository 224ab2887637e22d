#pragma once
// The 3602's interpolated move: one object, its state and its getters (the model: libgpiod's
// edge-event.c). It takes the decoded command (interpolated_command.hpp) on its 0->1 edge,
// applies the manual's acceptance rules, builds the path (circle_methods.hpp) and starts both
// axes' parts on one time base (planner::PathGroupPort, the planner's path group); while the path
// runs it keeps the two axes together (a stop on one is a stop of both), refuses axis 2's
// commands, and at the end gives both axes their outcome. Digest 7.14, 6.2 (CE-I*, IP-17/18,
// PI-07), A17, A34-A39, A46.
//
// The axes know their part as a coordinated motion (axis::Axis, "Coordinated motion"): the motion
// bits come from each axis' own feedback; their limits, E-stop, Hold and External input act on
// the axis that sees them, and this object carries the stop over to the other axis.
#include <cstdint>
#include <optional>

#include "module/axis/axis.hpp"
#include "module_types/m3602/circle_methods.hpp"
#include "module_types/m3602/interpolated_command.hpp"
#include "planner/motion_port.hpp"
#include "planner/path_group.hpp"
#include "planner/path_spec.hpp"

namespace stepmod::module::m3602 {

class InterpolatedMove {
 public:
  enum class State : std::uint8_t {
    kIdle,
    kRunning,  // both axes' parts under way (hold and External decelerations included)
    kHeld,     // stopped along the path by Hold or External, resumable from axis 1 (A39)
  };

  // x: axis 1 (the path's X, where commands and errors go), y: axis 2.
  InterpolatedMove(axis::Axis& x, planner::MotionPort& x_port, axis::Axis& y,
                   planner::MotionPort& y_port) noexcept
      : x_(x), px_(x_port), y_(y), py_(y_port), group_(x_port, y_port) {}
  InterpolatedMove(const InterpolatedMove&) = delete;
  InterpolatedMove& operator=(const InterpolatedMove&) = delete;

  // Before the axes' scan: axis 2's command image. While a path runs its commands are refused
  // with a Command Error on axis 1 (3602-CE-I2, A46) and kept from axis 2 until released.
  axis::AxisCommand filter_axis2(const axis::AxisCommand& c);
  // After the axes' scan: ends, stops carried over, a Resume, and this scan's interpolated
  // command (nullopt: axis 1's LSW bits 9..14 are 0).
  void scan(const std::optional<InterpolatedCommand>& words);
  // After an input edge reached the axes: a stop one axis took is carried over to the other.
  void after_input();

  State state() const noexcept { return state_; }
  // 3602-LSW-01: axis 1's status LSW bit 11.
  bool running() const noexcept { return state_ == State::kRunning; }
  // The path last started (relative to its start point; vs/vp/accel/decel its vector profile).
  const planner::PathSpec& path() const noexcept { return spec_; }

 private:
  void command(const InterpolatedCommand& c);
  // The command's own rules and the axes' state (CE-L1, CE-I6, CE-03, CE-I5, CE-05, CE-I3,
  // CE-04); false: ignored or rejected.
  bool admissible(const InterpolatedCommand& c);
  // The vector profile's rules (CE-05, CE-06, CE-07) and the geometry (CE-I7, IP-03): the path
  // relative to the start point, or nullopt (rejected).
  std::optional<planner::PathSpec> path_of(const InterpolatedCommand& c);
  // The geometry's refusal (CE-I7, IP-03), if any: false after it.
  bool geometry_ok(GeometryFault fault) noexcept;
  // An accepted path: blocked by inputs (A15), complete at once (at its end point), held from
  // the start (External, A17), or started on both axes.
  void begin_path(const planner::PathSpec& spec);
  // Rejections: every interpolated error is reported on axis 1 only (3602-CE-I1), with its item
  // and sentence (interpolated_items.hpp) recorded with the bit, in the same scan.
  void reject(const axis::Item& item, const char* text) noexcept {
    x_.reject_coordinated(false, item, text);
  }
  void reject_profile(const axis::Item& item, const char* text) noexcept {
    x_.reject_coordinated(true, item, text);
  }
  // 3602-CE-I3: axis `a` (1 or 2) is not configured, enabled and in command mode; true after
  // the refusal.
  bool refuse_not_ready(const axis::Axis& a, unsigned number) noexcept;
  // Both parts of `spec_` started on one time base; false if the planner refused one.
  bool start(bool resume);
  void carry_stops();
  void poll_end();
  void resume(const axis::Profile& p);

  axis::Axis& x_;
  planner::MotionPort& px_;
  axis::Axis& y_;
  planner::MotionPort& py_;
  planner::PathGroupPort group_;  // both axes' parts, started and resumed as one

  State state_ = State::kIdle;
  planner::PathSpec spec_;
  bool started_ = false;    // the held path has run (A17: a path held before its start has not)
  bool requested_ = false;  // last scan's interpolation bits, for the 0->1 edge
  std::int64_t held_y_steps_ = 0;  // axis 2's step count where the path was held
  axis::CommandSet axis2_prev_;
  axis::CommandSet axis2_refused_;  // refused commands, kept from axis 2 until released
};

}  // namespace stepmod::module::m3602
