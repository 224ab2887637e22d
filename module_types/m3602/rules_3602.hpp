#pragma once
// The 3602's rules value: what the shared axis code (module/axis/) does differently for this
// module, as data (the fields are explained in module/axis/rules.hpp). Written down here, with its
// module; Module3602 (module_3602.hpp) names it as its kRules, which the registry's row reads.
#include "module/axis/rules.hpp"

namespace stepmod::module::m3602 {

inline constexpr axis::ModuleRules kRules3602{
    .type = ModuleType::k3602,
    .target_min = -1'073'741'823,  // 16#C000:0001 ... 16#3FFF:FFFF
    .target_max = 1'073'741'823,
    .speed_max = 1'000'000,
    .starting_speed_min = 1,
    .starting_speed_max = 1'000'000,
    .accel_min = 1'000,  // 1 ... 2000 steps/ms/s
    .accel_max = 2'000'000,
    .accel_word_unit = 1'000,
    .blend_length_max = 1'073'741'823,
    .blend_segment_max = 1'073'741'822,
    .registration_max = 1'073'741'823,
    .has_encoder = false,  // A20: no encoder register exists
    .has_follower = false,
    .has_registration = true,
    .has_marker_homing = false,
    .has_homing_timeout = true,
    .homing_timeout_max_s = 300,
    .has_estop_input = false,  // CW/CCW inputs may be E-stops instead
    .cw_ccw_inputs_configurable = true,
    .has_disable = true,
    .preset_clears_move_complete = true,
    .stopped_means_idle = true,
    .homing_needs_limit_ahead = false,
    .homing_s_curve_sets_home_invalid = true,
    .homing_home_with_limit_is_error = true,
    .registration_external_always_error = false,
    .powers_up_with_configuration_error = true,
    .input_error_kept_while_inputs_active = true,
};

}  // namespace stepmod::module::m3602
