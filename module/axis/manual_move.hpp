#pragma once
// Manual (jog) moves of one axis, plain, one-shot and registration, and the minimum
// registration distance (3601 Ch.4 "Manual Move", "Registration Move"): the start checks, the level
// the move runs on, the runtime changes of speed/accel/decel/target, and the registration trigger.
// It owns the run's state; the axis hands it the command, the scans and the External input's edges.
#include <cstdint>
#include <optional>

#include "module/axis/axis_state.hpp"

namespace stepmod::module::axis {

class ManualMove {
 public:
  explicit ManualMove(AxisState& ax) noexcept : ax_(ax) {}

  // A rising Manual + / - (without the follower flag).
  void command(const AxisCommand& c, planner::Direction dir, Nanos now);
  // Every command-mode scan, first: a released command is a controlled stop (3601-STP-01).
  void levels(const AxisCommand& c);
  // Every command-mode scan of a configured axis: runtime changes (3601-CE-17/19/30..33), the
  // release of a one-shot or registration move, the registration trigger at `now`.
  void scan(const AxisCommand& c, const CommandSet& rising, Nanos now);
  // The store-minimum-distance flag rising with no command set (3601 Ch.4 "New Command Bit").
  void store_min_registration(const AxisCommand& c);
  // An input edge during a manual/registration move; true if it was fully handled here.
  bool on_input(const InputEvent& e, bool now_active);

  // 3601-DIR-01: the direction of a one-shot whose command is still held (`held`: this scan's
  // commands), shown as "moving" whether the pulse is out or not.
  std::optional<planner::Direction> one_shot_direction(const CommandSet& held) const noexcept;
  bool min_registration_set() const noexcept { return min_registration_ != 0; }
  // Every configuration resets the minimum distance (3601 Ch.4 "Registration Move").
  void reset_min_registration() noexcept { min_registration_ = 0; }

 private:
  bool owns_release() const noexcept;
  void begin_run(const AxisCommand& c, planner::Direction dir, const Profile& p, Nanos now);
  std::uint32_t start_motion(planner::Direction dir, const Profile& p, bool external);
  void registration_scan(const AxisCommand& c, const CommandSet& rising, bool held, Nanos now);
  bool hold_before_trigger(const CommandSet& rising);
  bool registration_start_allowed(std::int32_t count, double vp, const planner::Ramp& decel);
  void runtime_checks(const AxisCommand& c);
  void error_stop(const Item& why);
  void registration_check(Nanos now, Nanos present_since, StopCause cause);
  std::int64_t registration_steps_at(Nanos t) const noexcept;

  enum class Kind : std::uint8_t { kPlain, kOneShot, kRegistration };
  struct Run {
    Kind kind = Kind::kPlain;
    bool ramped = false;                       // initial Vp > Vs: the speed may change on the fly
    CommandKind key = CommandKind::kManualCw;  // the command that keeps it running
    // The parameters at the start (speed, accel, decel: after the last accepted change).
    std::optional<std::int32_t> target;
    std::optional<std::int32_t> speed;
    std::int64_t accel = 0;
    std::int64_t decel = 0;
    std::int32_t vp = 0;  // programmed speed in force
    // Registration only:
    std::int32_t count = 0;        // steps output after the trigger (R)
    std::int32_t dmin = 0;         // minimum distance in force at the start
    std::int64_t start_steps = 0;  // pulse count at the start
    Nanos start_t = 0;             // the scan that started it: none of its steps before
    bool triggered = false;        // the trigger has been acted on (stop_after sent)
    Nanos released_since = -1;     // scan that first saw the command reset
    Nanos external_since = -1;     // time the External input became active
    Nanos checked_until = -1;      // the count is known <= Dmin up to this time
  };

  AxisState& ax_;
  Run run_;
  bool one_shot_held_ = false;         // a one-shot's command still held (DIR-01)
  std::int32_t min_registration_ = 0;  // minimum registration distance; 0 = off
};

}  // namespace stepmod::module::axis
