#pragma once
// What differs between the modules is data: one ModuleRules value per module type, read by the
// shared axis code (module/axis/) wherever the manuals disagree. The values are the manuals'
// (each manual's specifications and the checklist items named at each field: genuine
// differences between the modules, not to be harmonised). Only numbers and yes/no facts live
// here; how a module writes them into its words is its dialect's business (module/m3601/...).
// The values themselves live with their modules: module/m3601/rules_3601.hpp, ...
//
// Shared by all three (so no field here): commands fire on a 0->1 edge (7.16); while Command
// Error is set every command but Reset Errors is ignored, Immediate Stop included (3601-CE-L1,
// the 3602 and 3202 lists say "as 3601"); a configuration request while moving is CE, the move
// finishes, then the mode changes (7.15); 2..16 blend segments; homing pauses of 2 s.
#include <cstdint>

#include "core/clock.hpp"
#include "core/module_shape.hpp"

namespace stepmod::module::axis {

struct ModuleRules {
  ModuleType type{};

  // ---- Ranges (each manual's Ch.1 specifications) ----------------------------------------------
  std::int32_t target_min{};  // absolute/relative target, preset values, registration counts
  std::int32_t target_max{};
  std::int32_t speed_max{};  // programmed speed Vp (steps/s)
  std::int32_t starting_speed_min{};
  std::int32_t starting_speed_max{};
  // Accel/decel in steps/s^2 (the shared code never sees a module's own unit).
  std::int64_t accel_min{};
  std::int64_t accel_max{};
  // One unit of the module's accel/decel words in steps/s^2: 1,000 where the words are in
  // steps/ms/s (3601, 3602), 1 where they are in steps/s^2 (3202). Used by the dialects only.
  std::int64_t accel_word_unit{};
  std::int64_t blend_length_max{};   // sum of the segment lengths
  std::int64_t blend_segment_max{};  // one segment's length (3602: 1 ... 1,073,741,822)
  std::int64_t registration_max{};   // registration count and minimum registration distance

  // ---- Features that exist on some modules only -----------------------------------------------
  bool has_encoder{};         // quadrature encoder input, encoder move, Preset Encoder
  bool has_follower{};        // encoder follower (3601 firmware >= 4.1)
  bool has_registration{};    // manual/jog move with a registration count
  bool has_marker_homing{};   // homing options 3 and 4 (marker pulse)
  bool has_homing_timeout{};  // 3602: 0 ... 300 s, expiry -> Home Invalid (A16)
  std::int32_t homing_timeout_max_s{};
  bool has_estop_input{};             // a separate E-stop terminal (3601, 3202)
  bool cw_ccw_inputs_configurable{};  // 3602: CW/CCW inputs are unused, limits or E-stops
  bool has_disable{};                 // axis/channel disable bit (3602 inferred, 3202 bit 28)

  // ---- Genuine differences of behaviour (the checklist items named per field) -----------------
  // Preset Position clears Move Complete on the 3602 only (3602-MC-02 vs 3601-MC-03).
  bool preset_clears_move_complete{};
  // Stopped: an event bit set after certain stops (3601, 3202) or "idle in command mode" (3602,
  // 3602-STP-01).
  bool stopped_means_idle{};
  // A home command needs the end limit in its own direction configured (3601/3202, 3601-CE-13);
  // the 3602 needs only the home input.
  bool homing_needs_limit_ahead{};
  // Find Home with S-curve: Command Error on every module (3601-CE-10, 3602-CE-11); Home Invalid
  // too on the 3602 only (3602-HI-02; the 3601 HI list has no such item).
  bool homing_s_curve_sets_home_invalid{};
  // The home input active together with an end limit during homing is a homing error on the 3602
  // (3602-HI-06); the 3601 and 3202 lists have no such item.
  bool homing_home_with_limit_is_error{};
  // External input active when a registration move starts: always an error on the 3601, only
  // with a minimum registration distance of 0 on the 3602 (3601-CE-27).
  bool registration_external_always_error{};
  // Power-up: 3601/3602 in command mode with Configuration Error; 3202 disabled without it.
  bool powers_up_with_configuration_error{};
  // Hold during the deceleration of an absolute/relative move is ignored, no CE (3202 manual
  // Ch.4 "Hold Move" note 2, 3202-CE-07); the 3601 and 3602 manuals say nothing: they hold.
  bool hold_ignored_while_decelerating = false;
  // Input Error is cleared by the next move command only if no E-stop or end-limit input is active
  // at that moment (3602-IE-C1, manual Ch.9 bit 11); 3601-IE-C1 clears it whenever a move starts.
  bool input_error_kept_while_inputs_active = false;
};

// Homing pauses (3601 Ch.4 "Find Home": every pause of the homing sequences is 2 s, on every
// module).
inline constexpr Nanos kHomingPause = 2 * kNsPerSec;

}  // namespace stepmod::module::axis
