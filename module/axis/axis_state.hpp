#pragma once
// What every feature of one axis shares: the decoded configuration, the motion under way and the
// registers, with the helpers the manuals' rules share (starting a move, the start checks, the
// stops). The activity, the stop cause and the status latches are read here and changed only by
// reporting an event to the table of transitions (axis_transitions.hpp). Each feature
// (homing.hpp, manual_move.hpp, blend.hpp, encoder.hpp, follower.hpp) owns its own state and gets
// this one by reference.
#include <algorithm>
#include <cstdarg>
#include <cstdint>
#include <optional>

#include "module/axis/axis_command.hpp"
#include "module/axis/axis_config.hpp"
#include "module/axis/axis_io.hpp"
#include "module/axis/axis_status.hpp"
#include "module/axis/axis_transitions.hpp"
#include "module/axis/error_items.hpp"
#include "module/axis/error_reason.hpp"
#include "module/axis/input_bank.hpp"
#include "module/axis/rules.hpp"
#include "planner/motion_port.hpp"

namespace stepmod::module::axis {

// A programmed speed with its two ramps, read from a command.
struct Profile {
  double vp = 0;
  planner::Ramp accel;
  planner::Ramp decel;
};

struct AxisState {
  AxisState(const ModuleRules& r, AxisIo& i, planner::MotionPort& m) noexcept
      : rules(r), io(i), motion(m) {}

  const ModuleRules& rules;
  AxisIo& io;
  planner::MotionPort& motion;
  InputBank inputs;

  AxisConfig cfg;
  bool configured = false;  // a valid configuration is in force
  planner::Direction dir = planner::Direction::kCw;
  planner::Ramp move_decel;  // the running motion's decel (controlled stops)

  // The activity, the stop cause and the latches: read here, changed only by reporting an event
  // to the table of transitions (axis_transitions.hpp, docs/axis-states.md).
  Activity activity() const noexcept { return machine_.activity(); }
  StopCause stop_cause() const noexcept { return machine_.stop_cause(); }
  Latches latches() const noexcept;
  // The Hold state belongs to a coordinated motion: its coordinator resumes it (Axis).
  bool hold_coordinated() const noexcept { return machine_.latched(Latch::kHoldCoordinated); }
  // True when the table has a row for `ev` in the present state (and it has been applied).
  bool fire(AxisEvent ev) noexcept { return machine_.fire(ev); }

  std::int64_t origin = 0;   // pulse count at which the reported position is 0
  std::int64_t encoder = 0;  // encoder register (X4 counts, or own steps with diagnostic feedback)
  std::int64_t capture = 0;  // captured value
  // Writing the register (homing, Preset Encoder, a configuration) sets it as of an instant: the
  // scan's, or the axis' last step if that is later. An A/B edge stamped at or before it but
  // delivered after it (input events reach the control thread some time after the pulse thread
  // has stepped and reported the motion's end) is motion of before the write: not counted.
  void write_encoder(std::int64_t value) noexcept {
    encoder = value;
    encoder_written_at = std::max(scan_now, motion.last_step_time());
  }
  bool counts_encoder_edge(Nanos t) const noexcept { return t > encoder_written_at; }
  Nanos scan_now = 0;            // the running scan's time (Axis::scan)
  Nanos encoder_written_at = 0;  // see write_encoder()

  bool moving() const noexcept { return activity() != Activity::kIdle; }
  std::int64_t position() const noexcept { return motion.steps() - origin; }
  void set_position(std::int64_t p) noexcept { origin = motion.steps() - p; }
  // A refusal (docs/error-reasons.md): Command Error (and Invalid Profile) set here, the item and
  // the sentence recorded with them; there is no refusal without its item. `fmt`: printf-style,
  // short (the image keeps 56 bytes with the item id); nullptr: the item's general description.
  void reject(const Item& item, const char* fmt = nullptr, ...) noexcept
      __attribute__((format(printf, 3, 4)));
  void reject_profile(const Item& item, const char* fmt = nullptr, ...) noexcept
      __attribute__((format(printf, 3, 4)));
  // Records why an error bit is being set (the caller sets it). Same `fmt` as reject().
  void note(const Item& item, const char* fmt = nullptr, ...) noexcept
      __attribute__((format(printf, 3, 4)));

  // Reasons (the image's block, docs/interface.md 3.4): the last one recorded. An error bit that
  // rises without a note gets its list's general reason at the next explain_new_errors() (every
  // error bit has a reason, even from a path that names no item).
  ErrorReason reason;
  void explain_new_errors() noexcept;

  // Ranges of the module (rules.hpp).
  bool speed_in_range(const std::optional<std::int32_t>& v) const noexcept {
    return v && *v >= 0 && *v <= rules.speed_max;
  }
  bool rate_in_range(std::int64_t steps_per_s2) const noexcept {
    return steps_per_s2 >= rules.accel_min && steps_per_s2 <= rules.accel_max;
  }
  bool target_in_range(const std::optional<std::int32_t>& v) const noexcept {
    return v && *v >= rules.target_min && *v <= rules.target_max;
  }

  // Speed, accel, decel and the S-curve selection of a command; nullopt after raising CE + IP for
  // an out-of-range value (3601-CE-04 / IP-02) or, when `ramped`, Vp < Vs (3601-CE-05 / IP-01).
  std::optional<Profile> read_profile(const AxisCommand& c, bool ramped);
  // Starts an absolute/relative move of `steps` (signed), reported as `started`; false (with CE)
  // if the planner refused.
  bool start_move_steps(std::int64_t steps, const Profile& p,
                        AxisEvent started = AxisEvent::kMoveStarted);
  // 3601-HLD-03: with the External input active a move outputs one step, then holds.
  void start_abs_rel(std::int64_t steps, const Profile& p);
  // What an input line does on this axis: the 3602's CW / CCW inputs are end limits, E-stops or
  // unused as configured (AxisConfig::cw_input / ccw_input); every other line is itself.
  InputLine role_of(InputLine line) const noexcept;
  // Any input acting as an E-stop is active (the E-stop terminal, or a CW / CCW input so set).
  bool estop_active() const noexcept;
  // The end limit toward `d` is configured as a limit and active.
  bool limit_active(planner::Direction d) const noexcept;
  // A15: no move starts while the E-stop is active or toward an active end limit. True (with
  // Input Error set) when the move must not start.
  bool inputs_block_start(planner::Direction d);
  // A new move clears the previous move's outcome (3601-MC-03, HLD-C1, IE-C1, STP-C1, AH-01).
  void clear_move_outcome() noexcept;
  void immediate_stop(StopCause cause);
  // Limit / E-stop: immediate stop, IE, PI (3601-IE-01/02); `item` and the input's name ("E-stop")
  // for the reason.
  void fault_stop(const Item& item, const char* input);

 private:
  void note_position_lost(const Item& item) noexcept;  // Position Invalid's reason at a cut

  AxisStateMachine machine_{rules};
  void vnote(const Item& item, const char* fmt, va_list args) noexcept;
  void record(ErrorList list, unsigned number, const char* text) noexcept;
  Latches explained_;         // the error bits as of the last explain_new_errors()
  bool noted_since_ = false;  // a reason was recorded since then
};

}  // namespace stepmod::module::axis
