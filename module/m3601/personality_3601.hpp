#pragma once
// The 3601 personality: what the 3601's firmware does with its eight output words, its inputs
// and its one axis (3601 manual; digest MODULES.md sections 3, 6.1 and 7).
#include <cstdint>

#include "gpio/backend.hpp"
#include "module/axis/input_bank.hpp"
#include "module/m3601/config_3601.hpp"
#include "module/personality.hpp"
#include "module/axis/quadrature_decoder.hpp"
#include "planner/motion_port.hpp"

namespace stepmod::module::m3601 {

class Personality3601 final : public Personality {
 public:
  Personality3601(gpio::Backend& backend, planner::MotionPort& motion);

  const ModuleShape& shape() const noexcept override;
  void on_input(const gpio::InputEvent& e) override;
  void scan(const ImageWords& out, ImageWords& in, Nanos now) override;
  void plc_stopped(Nanos now) override;
  void shutdown() override;

 private:
  // What the axis is doing; a motion is in progress from acceptance until the pulse thread
  // reports its end (digest 7.16).
  enum class Activity : std::uint8_t {
    kIdle,
    kMove,         // absolute / relative move (commands_3601.cpp)
    kEncoderMove,  // absolute / relative move to an encoder count (encoder_3601.cpp)
    kManual,       // manual move, and registration move (manual_3601.cpp)
    kHoming,       // Find Home + / - (homing_3601.cpp)
    kBlend,        // blend move (blend_3601.cpp)
    kFollower,     // encoder follower (encoder_3601.cpp)
  };
  // Why a motion is ending early; decides the status bits when it has ended.
  enum class StopCause : std::uint8_t { kNone, kHold, kExternal, kRelease, kImmediate, kFault };

  // Status and error latches (status word MSW bits), named as in the manual.
  struct Status {
    bool hold = false;
    bool stopped = false;
    bool at_home = false;
    bool move_complete = false;
    bool home_invalid = false;
    bool invalid_profile = false;
    bool position_invalid = false;
    bool input_error = false;
    bool command_error = false;
    bool configuration_error = true;  // 3601-CFG-01: power-up state
  };

  // The parameters of an absolute/relative move, kept for Hold/Resume.
  struct HeldMove {
    std::int64_t target = 0;  // absolute target in reported position units
  };

  // Mode handling (configuration <-> command, digest 7.15).
  void scan_configuration_mode(const ImageWords& out);
  void enter_command_mode();
  void compose_configuration_image(ImageWords& in) const;

  // Command mode.
  void command_mode_scan(const ImageWords& out, std::uint16_t msw, Nanos now);
  void poll_motion_end();
  void handle_levels(const ImageWords& out);
  void handle_command_edge(const ImageWords& out, std::uint16_t rising);
  void command_move(const ImageWords& out, bool absolute);
  void command_hold();
  void command_resume(const ImageWords& out);
  void command_immediate_stop();
  void command_preset_position(const ImageWords& out);
  void command_reset_errors(const ImageWords& out);
  void compose_command_image(ImageWords& in) const;

  // ==== Manual and registration moves (manual_3601.cpp) =======================================
  // Rising edge of a manual-move bit (without the follower bit).
  void command_manual(const ImageWords& out, planner::Direction dir);
  // Every command-mode scan: runtime changes of speed/accel/decel/target (3601-CE-17/19/30..33),
  // the release of a one-shot or registration move's bit, the registration trigger at `now`.
  void manual_scan(const ImageWords& out, Nanos now);
  // Command LSW bit 10 rising with MSW = 0: store the minimum registration distance.
  void command_min_registration(const ImageWords& out);
  // An input edge during a manual/registration move; true if it was fully handled here.
  bool manual_on_input(const gpio::InputEvent& e, bool now_active);
  // Status MSW direction bit of a one-shot manual move whose bit is still held (3601-DIR-01).
  std::uint16_t manual_status_msw() const noexcept;
  // True while the manual move's own bit release is handled by manual_scan (one-shot,
  // registration), not by handle_levels' plain controlled stop.
  bool manual_owns_release() const noexcept;
  // Registration helpers (manual_3601.cpp).
  bool registration_start_allowed(std::int32_t count, double vp, const planner::Ramp& decel);
  void manual_runtime_checks(const ImageWords& out);
  void manual_error_stop();
  void registration_check(Nanos now, Nanos present_since, StopCause cause);
  std::int64_t registration_steps_at(Nanos t) const noexcept;
  // ==== end manual and registration ============================================================

  // ==== Homing (homing_3601.cpp) ===============================================================
  void command_home(const ImageWords& out, planner::Direction dir);
  // Every command-mode scan while homing: pause timers, backplane proximity bit edges.
  void homing_scan(Nanos now);
  // Every input edge while homing (home, limits, E-stop, marker); the generic rules are skipped.
  void homing_on_input(const gpio::InputEvent& e, bool was_active, bool now_active);
  // A motion of the homing sequence has ended (the pulse thread finished or aborted it).
  void homing_motion_ended(StopCause cause);
  // The 2-s pauses; also called while the configuration-mode bit waits for the end (CE-01).
  void homing_timers(Nanos now);
  // Homing internals (homing_3601.cpp): the step tables' events and actions.
  friend struct HomingTable;
  enum class HomingStep : std::uint8_t;
  enum class HomingEvent : std::uint8_t;
  void homing_event(HomingEvent ev);
  void homing_limit(bool ahead);
  bool homing_run(planner::Direction d, bool creep);
  void homing_fail();
  // ==== end homing =============================================================================

  // ==== Blend moves (blend_3601.cpp) ===========================================================
  // Every command-mode scan: the programming handshake (LSW bits 8/9, acknowledge LSW bit 9).
  void blend_programming_scan(const ImageWords& out);
  void command_run_blend(const ImageWords& out, planner::Direction dir);
  // Status LSW bits owned by blends: running (8), acknowledge (9).
  std::uint16_t blend_status_lsw() const noexcept;
  // Hold while a blend runs (3601-CE-23): CE now, cleared by itself when the blend ends.
  void blend_hold();
  // A blend motion has ended (called by poll_motion_end instead of its generic outcome).
  void blend_motion_ended(StopCause cause);
  // A configuration erases the stored profile and any programming cycle (3601-CE-20).
  void blend_erase();
  // One programming block, read on a transmit rising edge; false if it holds an error.
  bool blend_first_block(const ImageWords& out);
  bool blend_segment_block(const ImageWords& out);
  // ==== end blend ==============================================================================

  // ==== Encoder: encoder move, preset encoder, follower (encoder_3601.cpp) =====================
  void command_encoder_move(const ImageWords& out, bool absolute);
  void command_preset_encoder(const ImageWords& out);
  // Rising edge of a manual-move bit with command LSW bit 7 (encoder follower).
  void command_follower(const ImageWords& out, planner::Direction dir);
  // Every command-mode scan: follower ratio/direction changes and rules, encoder-move target.
  void encoder_scan(const ImageWords& out);
  // After every encoder count change (X4 decoding or diagnostic feedback), at the edge's time.
  void encoder_changed(Nanos t);
  // Encoder move: the target crossed in the direction of travel starts the deceleration.
  void encoder_move_watch();
  // Follower helpers: the per-scan rules, entering (false after a CE), the parameter words
  // (false after a CE), the planner's follow motion, leaving (Stopped, 3601-STP-05).
  void follower_scan(const ImageWords& out, std::uint16_t msw);
  bool follower_enter();
  bool follower_params(const ImageWords& out);
  planner::FollowSpec follower_spec() const noexcept;
  void follower_start_motion();
  void follower_send(Nanos t, bool force);
  void follower_cut();   // a CE while following: output stops at once, follower mode is left
  void follower_exit();
  // ==== end encoder ============================================================================

  // Motion helpers.
  struct Profile {
    double vp = 0;
    planner::Ramp accel;
    planner::Ramp decel;
  };
  // Reads speed (words 4-5), accel (6), decel (7) and the S-curve bits; nullopt after raising
  // CE + IP for an out-of-range value (CE-04/IP-02) or Vp < Vs (CE-05/IP-01) when `ramped`.
  std::optional<Profile> read_profile(const ImageWords& out, bool ramped);
  bool start_move_steps(std::int64_t steps, const Profile& p);
  void start_abs_rel(std::int64_t steps, const Profile& p);
  // A15: no move starts while the E-stop is active or toward an active end limit. True (with
  // Input Error set) when the move must not start.
  bool inputs_block_start(planner::Direction dir);
  // A new move clears the previous move's outcome (3601-MC-03, HLD-C1, IE-C1, STP-C1, AH-01).
  void clear_move_outcome() noexcept;
  // Whether output words first..last are all 0 (the "must be 0" rules of the command table).
  static bool words_zero(const ImageWords& out, unsigned first, unsigned last) noexcept;
  std::optional<std::int32_t> preset_value(const ImageWords& out);
  void immediate_stop(StopCause cause);
  void fault_stop();  // limit/E-stop: immediate stop, IE, PI (digest 7.7)
  bool moving() const noexcept { return activity_ != Activity::kIdle; }
  std::int64_t position() const noexcept { return motion_.steps() - origin_; }
  void set_position(std::int64_t p) noexcept { origin_ = motion_.steps() - p; }
  void reject() noexcept { status_.command_error = true; }
  void reject_profile() noexcept {
    status_.command_error = true;
    status_.invalid_profile = true;
  }

  gpio::Backend& backend_;
  planner::MotionPort& motion_;
  InputBank inputs_;
  QuadratureDecoder quadrature_;

  bool config_mode_ = false;
  bool configured_ = false;              // a valid configuration is in force
  bool config_after_motion_ = false;     // CE-01: mode bit seen while moving
  std::optional<Config3601> pending_;    // last configuration accepted in configuration mode
  ImageWords last_config_words_{};
  bool config_words_seen_ = false;
  Config3601 cfg_;
  std::uint16_t mirror_[4] = {};         // configuration mirror (A26: only accepted data)

  Status status_;
  Activity activity_ = Activity::kIdle;
  StopCause stop_cause_ = StopCause::kNone;
  planner::Direction dir_ = planner::Direction::kCw;
  planner::Ramp move_decel_;             // the running motion's decel (controlled stops)
  HeldMove held_;
  std::int64_t move_target_ = 0;         // absolute target of the running abs/rel move

  std::int64_t origin_ = 0;              // pulse count at which the reported position is 0
  std::int64_t encoder_ = 0;             // encoder register (X4 counts)
  std::int64_t capture_ = 0;             // captured value
  std::uint16_t prev_msw_ = 0;           // last scan's command word MSW (edge detection)
  std::uint16_t lsw_ = 0;                // this scan's command word LSW (proximity echo)
  std::uint16_t prev_lsw_ = 0;           // last scan's command word LSW (edge detection)

  // ==== State of the features in their own files: each block belongs to its file. ==========
  // -- manual_3601.cpp --
  std::int32_t min_registration_ = 0;  // minimum registration distance; 0 = off (LSW bit 10)
  enum class ManualKind : std::uint8_t { kPlain, kOneShot, kRegistration };
  struct ManualRun {
    ManualKind kind = ManualKind::kPlain;
    bool ramped = false;                  // initial Vp > Vs: the speed may change on the fly
    std::uint16_t bit = 0;                // the command MSW bit that keeps it running
    std::array<std::int32_t, 8> words{};  // words 0..7 at the start (4..7: after a change)
    std::int32_t vp = 0;                  // programmed speed in force
    // Registration only:
    std::int32_t count = 0;          // steps output after the trigger (R)
    std::int32_t dmin = 0;           // minimum distance in force at the start
    std::int64_t start_steps = 0;    // pulse count at the start
    bool triggered = false;          // the trigger has been acted on (stop_after sent)
    Nanos released_since = -1;       // scan that first saw the bit reset
    Nanos external_since = -1;       // time the External input became active
    Nanos checked_until = -1;        // the count is known <= Dmin up to this time
  };
  ManualRun manual_;
  bool one_shot_held_ = false;  // a one-shot's bit still held: direction bit stays on (DIR-01)
  // -- homing_3601.cpp --
  // The homing sequence under way (digest 7.11; A12: the step lists are tables in the .cpp).
  enum class HomingStep : std::uint8_t {
    kSearch,       // Vp toward the commanded direction, looking for home / proximity
    kApproach,     // proximity seen: slowing to (or at) Vs, looking for the final edge
    kFoundStop,    // H-A: home found, controlled stop to Vs
    kPause1,       // 2 s before reversing (after the found-stop or an end limit)
    kReverse,      // Vp opposite, until the home (proximity) signal is passed
    kReverseStop,  // controlled stop after passing it
    kPause2,       // 2 s before the creep
    kCreep,        // Vs (no ramp) toward the commanded direction
    kLimitStop,    // immediate stop at the end limit ahead (H-C)
    kFinishing,    // immediate stop at the home event; completes when the motion has ended
  };
  enum class HomingEvent : std::uint8_t {
    kHomeRise, kHomeFall, kProxRise, kProxFall, kMarker, kMotionEnd, kPauseOver
  };
  struct Homing {
    planner::Direction dir = planner::Direction::kCw;  // commanded direction
    HomingStep step = HomingStep::kSearch;
    std::uint8_t variant = 0;       // index of the step table (homing option 1..4, minus 1)
    bool segment = false;           // a motion of the sequence is in progress
    bool limit_reversed = false;    // reversed from the end limit ahead (H-C) or started at it
    bool limit_error = false;       // ended by a limit error (no Stopped, 3601-STP-04)
    bool prox = false;              // backplane proximity bit as last seen
    Nanos pause_end = -1;           // end of the running pause; -1: starts at the next scan
    double vp = 0;
    planner::Ramp accel;
    planner::Ramp decel;
  };
  Homing homing_;
  // -- blend_3601.cpp --
  planner::BlendSpec blend_profile_{};   // stored profile (dir and vs are set by Run Blend)
  bool blend_stored_ = false;            // a complete, valid profile is stored
  planner::BlendSpec blend_pending_{};   // the profile of the programming cycle under way
  bool blend_cycle_ = false;             // program bit (LSW 8) held: a cycle is under way
  bool blend_spoiled_ = false;           // this cycle had an error or was refused: store nothing
  unsigned blend_blocks_ = 0;            // blocks read in this cycle (first block included)
  std::int64_t blend_total_ = 0;         // sum of the segment lengths read so far
  bool blend_ack_ = false;               // status LSW bit 9
  bool blend_hold_error_ = false;        // CE was set by a Hold during the running blend
  // -- encoder_3601.cpp --
  std::int64_t encoder_target_ = 0;   // encoder move: the count at which deceleration starts
  bool encoder_watch_ = false;        // encoder move: the target is still being watched
  bool encoder_stop_pending_ = false; // encoder move: its stop could not be queued yet
  std::int64_t diag_steps_ = 0;       // diagnostic feedback: pulse count already counted
  struct Follower {
    std::uint16_t dir_bit = 0;        // MSW bit in force: 7 same sense, 8 reverse; 0 = no output
    int sense = 0;                    // +1 same, -1 reverse, 0 no output
    std::int32_t mul = 1;             // word 2
    std::int32_t div = 1;             // word 3
    std::int32_t accel = 0;           // word 6, steps/ms/s (0 = jump)
    std::int32_t decel = 0;           // word 7
    std::int64_t rem = 0;             // fraction of a step owed, in 1/div steps (0 <= rem < div)
    std::int64_t last_encoder = 0;    // encoder count already turned into steps
    std::int64_t target = 0;          // pulse count (motion_.steps()) the axis must reach
    std::int64_t base = 0;            // pulse count at the running follow motion's start
    bool running = false;             // our follow motion takes new targets (not told to stop)
    bool motion = false;              // our follow motion may still be busy
    bool leaving = false;             // LSW bit 7 cleared: leave once the owed steps are out
    bool dirty = false;               // target or parameters not yet sent to the planner
    Nanos sent_t = 0;                 // time of the last update sent from an encoder edge
    Nanos count_t = 0;                // time of the last encoder count
    double speed = 0.0;               // master's rate x ratio (steps/s); 0 = not known yet
  };
  Follower follow_;
};

}  // namespace stepmod::module::m3601
