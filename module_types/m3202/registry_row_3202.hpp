#pragma once
// The 3202's row of the module registry (registry/module_registry.hpp): the daemon's side of it.
#include <memory>
#include <span>

#include "module_types/m3202/module_3202.hpp"
#include "module_types/m3202/rules_3202.hpp"
#include "registry/module_registry.hpp"

namespace stepmod::registry {

inline constexpr ModuleTypeRow kRow3202{
    .type = ModuleType::k3202,
    .name = "3202",
    .shape = shape_of(ModuleType::k3202),
    .rules = &module::m3202::kRules3202,
    .make_personality = [](module::AxisIo& b, std::span<planner::MotionPort* const> a)
        -> std::unique_ptr<module::Personality> {
      return std::make_unique<module::m3202::Module3202>(b, *a[0], *a[1]);
    },
};

}  // namespace stepmod::registry
