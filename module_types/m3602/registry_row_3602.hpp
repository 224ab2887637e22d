#pragma once
// The 3602's row of the module registry (registry/module_registry.hpp): the daemon's side of it.
#include <memory>
#include <span>

#include "module_types/m3602/interpolated_items.hpp"
#include "module_types/m3602/module_3602.hpp"
#include "module_types/m3602/rules_3602.hpp"
#include "registry/module_registry.hpp"

namespace stepmod::registry {

inline constexpr ModuleTypeRow kRow3602{
    .type = ModuleType::k3602,
    .name = "3602",
    .shape = shape_of(ModuleType::k3602),
    .rules = &module::m3602::kRules3602,
    .make_personality = [](module::AxisIo& b, std::span<planner::MotionPort* const> a)
        -> std::unique_ptr<module::Personality> {
      return std::make_unique<module::m3602::Module3602>(b, *a[0], *a[1]);
    },
    .own_items = module::m3602::items::kAll,
};

}  // namespace stepmod::registry
