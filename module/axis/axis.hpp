#pragma once
// One axis (3601, 3602) or channel (3202): everything the manuals say an axis does, fed decoded
// configuration and commands (axis_config.hpp, axis_command.hpp), input edges and time, and
// producing a decoded status (axis_status.hpp). What differs between the modules comes from its
// ModuleRules (rules.hpp); which word and bit carries what is the dialects' business
// (module/m3601/...). The features are objects that own their state: Homing, ManualMove, Blend,
// Encoder, Follower; they share the axis' AxisState, whose activity, stop cause and latches
// change only through the table of transitions (axis_transitions.hpp, docs/axis-states.md).
//
// Files: axis.cpp (modes, the scan, the end of a motion, the status), axis_commands.cpp (command
// edges and the plain commands), axis_inputs.cpp (input edges, capture).
#include <optional>
#include <string_view>

#include "module/axis/axis_command.hpp"
#include "module/axis/axis_config.hpp"
#include "module/axis/axis_state.hpp"
#include "module/axis/axis_status.hpp"
#include "module/axis/blend.hpp"
#include "module/axis/encoder.hpp"
#include "module/axis/follower.hpp"
#include "module/axis/homing.hpp"
#include "module/axis/manual_move.hpp"
#include "module/axis/quadrature_decoder.hpp"
#include "module/axis/rules.hpp"
#include "planner/motion_port.hpp"

namespace stepmod::module::axis {

class Axis {
 public:
  Axis(const ModuleRules& rules, AxisIo& io, planner::MotionPort& motion);
  Axis(const Axis&) = delete;
  Axis& operator=(const Axis&) = delete;

  // One I/O scan. `configuration`: the dialect's verdict on this image read as configuration
  // words (the decoded configuration, or nullopt for the manual's configuration error); it is
  // looked at only while the axis is in configuration mode.
  void scan(const AxisCommand& c, const std::optional<AxisConfig>& configuration, Nanos now);
  // An input edge (electrical level, own timestamp), between scans.
  void on_input(const InputEvent& e);
  // The PLC left Run mode (3601-PI-07), or shutdown: immediate stop of a motion under way.
  void plc_stopped(const Item& why = items::kPiPlcStopped);
  // The dialect's verdict on the configuration words of this scan, before scan(): the checklist
  // number of its Configuration Error item (0: valid) and a sentence; recorded as the reason when
  // the axis takes an invalid configuration. `text` must outlive the scan (a literal).
  void set_configuration_fault(unsigned number, std::string_view text) noexcept {
    cfg_fault_number_ = number;
    cfg_fault_text_ = text;
  }
  // The last reason recorded for an error bit (docs/error-reasons.md).
  const ErrorReason& reason() const noexcept { return st_.reason; }

  // The 3202's blend message for this channel (3202 Ch.5 "Blend Move Programming"): 3202-IP-15
  // before the channel is configured, else Blend::program. Returns whether the profile was stored.
  bool program_blend(const BlendFirstBlock& first, std::span<const BlendSegmentBlock> segments);
  // A blend message that names no channel (3202-IP-11, A23): Invalid Profile on every channel.
  void set_invalid_profile(const Item& why = items::kBlendNoChannel) noexcept {
    st_.fire(AxisEvent::kProfileInvalid);
    st_.note(why);
    st_.explain_new_errors();
  }

  // The status after the last scan (or input edge).
  AxisStatus status() const noexcept;
  bool in_configuration_mode() const noexcept { return config_mode_; }
  // For a drive-enable output (daemon/drive_enable.hpp): a configuration is in force, the axis is
  // in configuration mode, an E-stop input is active.
  struct DriveState {
    bool configured = false;
    bool configuration_mode = false;
    bool estop = false;
  };
  DriveState drive_state() const noexcept {
    return {st_.configured, config_mode_, st_.estop_active()};
  }
  // The input lines as the axis sees them: electrical levels, and which the configuration uses
  // (for a console's inputs panel; the active states are in the status).
  const InputBank& inputs() const noexcept { return st_.inputs; }

  // ---- Coordinated motion (the 3602's interpolated moves: module/m3602/interpolated_move.hpp).
  // A coordinator outside the axis starts the motion on this axis' MotionPort, one part of a
  // path, and ends it. Meanwhile the axis reports its motion bits from its own feedback, handles
  // its limits and E-stop as for a move (immediate stop, IE, PI), turns Hold and the External
  // input into a stop of the whole path along it (MotionPort::hold_path), and leaves the
  // outcome (MC, Hold) to the coordinator, which knows when every axis of the path has ended.
  //
  // Configured, enabled and in command mode: the axis can take part in a coordinated motion.
  bool commandable() const noexcept { return st_.configured && !st_.cfg.disabled && !config_mode_; }
  const AxisConfig& config() const noexcept { return st_.cfg; }
  // A motion is in progress (docs/axis-states.md "States"), coordinated or not.
  bool moving() const noexcept { return st_.moving(); }
  // A15 at a coordinated start heading `dir` on this axis (nullopt: not moving): an active
  // E-stop, or the end limit toward `dir` -> Input Error, true (the motion must not start).
  bool inputs_block_start(std::optional<planner::Direction> dir);
  // The coordinator has started this axis' part of the motion (or resumed it): a new motion's
  // outcome is cleared (MC, Hold, IE), the axis is moving until end_coordinated.
  void begin_coordinated(planner::Ramp decel);
  // Why the coordinated motion is stopping early (kNone: it runs to its end).
  StopCause stop_cause() const noexcept { return st_.stop_cause(); }
  // The coordinator stops this axis' part: kImmediate / kFault cut it at once (PI); kHold /
  // kExternal mark the controlled stop another axis asked the path for.
  void stop_coordinated(StopCause cause);
  // Every axis of the motion has ended: the outcome on this axis.
  enum class CoordinatedEnd : std::uint8_t { kComplete, kHeld, kStopped };
  void end_coordinated(CoordinatedEnd end);
  // A coordinated command refused: Command Error (with Invalid Profile for a profile error), its
  // item and sentence recorded with it (AxisState::reject), so that the scan that shows the bit
  // shows its reason.
  void reject_coordinated(bool invalid_profile, const Item& item, const char* text) noexcept {
    if (invalid_profile) {
      st_.reject_profile(item, "%s", text);
    } else {
      st_.reject(item, "%s", text);
    }
  }
  // After a coordinator has acted on the axis outside its scan: an error bit it set without a
  // reason gets its list's general one now, not at the next scan (every shown bit has a reason).
  void explain_new_errors() noexcept { st_.explain_new_errors(); }
  // A Resume of a held coordinated motion, accepted by this axis' rules (Hold state, the profile
  // in range and >= Vs): the new vector profile, once, for the coordinator.
  std::optional<Profile> take_coordinated_resume() noexcept {
    auto p = coordinated_resume_;
    coordinated_resume_.reset();
    return p;
  }

 private:
  // Modes (3601 Ch.3, 3602 Ch.8, 3202 Ch.3).
  void take_configuration(const std::optional<AxisConfig>& configuration);
  void enter_command_mode();
  // Command mode (axis_commands.cpp).
  void command_mode_scan(const AxisCommand& c, Nanos now);
  void command_edge(const AxisCommand& c, const CommandSet& rising, Nanos now);
  // The rules every command edge passes first (CE-L1, several commands, undefined bits, not
  // configured, the word rules): the one command to act on, or none (refused or ignored).
  std::optional<CommandKind> admitted_command(const AxisCommand& c, const CommandSet& rising);
  void dispatch_command(const AxisCommand& c, CommandKind kind, Nanos now);
  void command_move(const AxisCommand& c, bool absolute);
  // `now`: the scan that saw the Hold; its deceleration starts there (issue 12 item 9).
  void command_hold(Nanos now);
  void command_resume(const AxisCommand& c);
  void command_immediate_stop();
  void command_preset_position(const AxisCommand& c);
  void command_reset_errors();
  void input_edge(const InputEvent& e);        // on_input() without the reason check
  void count_encoder_edge(Nanos t);            // an A / B edge: X4 decoding, the encoder register
  void capture_at(Nanos t);                    // the capture input's active edge
  void input_during_motion(InputLine line, Nanos t);  // an input that became active
  void limit_during_motion(bool cw_limit);
  // The pulse thread has ended the motion: its outcome in the status latches.
  void poll_motion_end();
  void cut_late_motion();           // the pulse thread's late-edge fault: an immediate stop
  void follow_coordinated_steps();  // the direction bits of a coordinated motion
  // Whether the motion runs, as this scan sees it (status()).
  bool busy_this_scan() const noexcept;
  // An encoder count changed at `t` (X4 decoding).
  void encoder_changed(Nanos t);

  AxisState st_;
  QuadratureDecoder quadrature_;
  Homing homing_;
  ManualMove manual_;
  Blend blend_;
  Encoder encoder_;
  Follower follower_;

  // The motion as poll_motion_end() found it: the pulse thread ends a motion at any instant, and
  // one scan's status must show the running motion or its outcome, not a moment in between.
  bool busy_at_poll_ = false;
  std::uint32_t epoch_at_poll_ = 0;

  bool config_mode_ = false;
  bool config_after_motion_ = false;   // CE-01: mode requested while moving
  std::optional<AxisConfig> pending_;  // last configuration accepted in configuration mode
  std::int64_t held_target_ = 0;       // Hold/Resume: the held move's absolute target
  std::int64_t move_target_ = 0;       // absolute target of the running abs/rel move
  // Coordinated motion: the step count at the last scan and whether the motion has stepped (the
  // direction bits come from the axis' own steps), and a Resume for the coordinator.
  std::int64_t coordinated_steps_ = 0;
  bool coordinated_stepped_ = false;
  std::optional<Profile> coordinated_resume_;
  // The previous scan's command image: edges are found against it (3601 Ch.4 general note 3).
  // After the scan
  // it is this scan's image, which the status reads.
  AxisCommand prev_;
  unsigned cfg_fault_number_ = 0;  // set_configuration_fault()
  std::string_view cfg_fault_text_;
  unsigned cfg_fault_noted_ =
      0;  // the fault last recorded (a bad configuration is re-read every scan)
};

}  // namespace stepmod::module::axis
