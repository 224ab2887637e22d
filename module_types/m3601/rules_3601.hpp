#pragma once
// The 3601's rules value: what the shared axis code (module/axis/) does differently for this
// module, as data (the fields are explained in module/axis/rules.hpp). Written down here, with its
// module; Module3601 (module_3601.hpp) names it as its kRules, which the registry's row reads.
#include "module/axis/rules.hpp"

namespace stepmod::module::m3601 {

inline constexpr axis::ModuleRules kRules3601{
    .type = ModuleType::k3601,
    .target_min = -8'388'608,
    .target_max = 8'388'607,
    .speed_max = 1'000'000,
    .starting_speed_min = 1,
    .starting_speed_max = 1'000'000,
    .accel_min = 1'000,  // 1 ... 2000 steps/ms/s
    .accel_max = 2'000'000,
    .accel_word_unit = 1'000,
    .blend_length_max = 8'388'607,  // 3601 manual ch. 5 (3601-IP-20)
    .blend_segment_max = 8'388'607,
    .registration_max = 8'388'607,
    .has_encoder = true,
    .has_follower = true,
    .has_registration = true,
    .has_marker_homing = true,
    .has_homing_timeout = false,
    .homing_timeout_max_s = 0,
    .has_estop_input = true,
    .cw_ccw_inputs_configurable = false,
    .has_disable = false,
    .preset_clears_move_complete = false,
    .stopped_means_idle = false,
    .homing_needs_limit_ahead = true,
    .homing_s_curve_sets_home_invalid = false,
    .homing_home_with_limit_is_error = false,
    .registration_external_always_error = true,
    .powers_up_with_configuration_error = true,
};

}  // namespace stepmod::module::m3601
