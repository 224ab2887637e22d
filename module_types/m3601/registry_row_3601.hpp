#pragma once
// The 3601's row of the module registry (registry/module_registry.hpp): the daemon's side of it.
#include <memory>
#include <span>

#include "module_types/m3601/module_3601.hpp"
#include "module_types/m3601/rules_3601.hpp"
#include "registry/module_registry.hpp"

namespace stepmod::registry {

inline constexpr ModuleTypeRow kRow3601{
    .type = ModuleType::k3601,
    .name = "3601",
    .shape = shape_of(ModuleType::k3601),
    .rules = &module::m3601::kRules3601,
    .make_personality = [](module::AxisIo& b, std::span<planner::MotionPort* const> a)
        -> std::unique_ptr<module::Personality> {
      return std::make_unique<module::m3601::Module3601>(b, *a[0]);
    },
};

}  // namespace stepmod::registry
