#pragma once
// What every per-module-type table shares: the registry's rows (registry/module_registry.cpp),
// stepmodctl's (tools/ctl_dialects.cpp) and the console's views (web/module_views.cpp) are each a
// generated std::array of pointers to rows with a `type` member, one per module type in
// kModuleShapes' order (module_types/CMakeLists.txt, stepmod_collect). Each table is checked
// against the ground list where it is collected and looked up by type here.
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "core/module_shape.hpp"

namespace stepmod {

// Whether `rows` has one row per module type, in kModuleShapes' order (for a static_assert).
template <class Row, std::size_t N>
constexpr bool rows_follow_shapes(const std::array<const Row*, N>& rows) noexcept {
  if (N != kModuleShapes.size()) return false;
  for (std::size_t i = 0; i < N; ++i) {
    if (rows[i]->type != kModuleShapes[i].type) return false;
  }
  return true;
}

// The row of `type`. Throws std::invalid_argument "<missing><number>" for a number that is no
// module type (a ModuleType made from an unchecked number).
template <class Row, std::size_t N>
const Row& row_of_type(const std::array<const Row*, N>& rows, ModuleType type,
                       const char* missing) {
  for (const Row* r : rows) {
    if (r->type == type) return *r;
  }
  throw std::invalid_argument(missing + std::to_string(static_cast<unsigned>(type)));
}

}  // namespace stepmod
