#include "registry/module_registry.hpp"

#include <stdexcept>

#include "core/module_rows.hpp"
#include "module_types/registry_rows.hpp"  // generated: kRegistryRows, one per module type

namespace stepmod::registry {
namespace {

using module_types::kRegistryRows;

// ---- the rows agree with the ground list of shapes and with themselves ------------------------

static_assert(rows_follow_shapes(kRegistryRows),
              "a module type needs one row, in kModuleShapes' order");

// Each row's shape, rules and name agree with its type.
constexpr bool rows_agree() {
  for (std::size_t i = 0; i < kRegistryRows.size(); ++i) {
    const ModuleTypeRow& r = *kRegistryRows[i];
    if (r.shape.axes != kModuleShapes[i].axes) return false;
    if (r.rules->type != r.type || module_type_from_name(r.name) != r.type) return false;
    // The config checker's terminals (core/) and the axis code's features (rules) agree.
    const AxisTerminals& io = kModuleShapes[i].terminals;
    if (io.encoder != r.rules->has_encoder || io.estop != r.rules->has_estop_input) return false;
    if (kModuleShapes[i].reason_digit == 0) return false;
  }
  return true;
}
static_assert(rows_agree(), "a module type's row disagrees with its shape, rules or name");

}  // namespace

std::span<const ModuleTypeRow* const> module_type_rows() noexcept {
  return kRegistryRows;
}

const ModuleTypeRow& row_of(ModuleType type) {
  return row_of_type(kRegistryRows, type, "unknown module type ");
}

std::unique_ptr<module::Personality> make_personality(ModuleType type, module::AxisIo& io,
                                                      std::span<planner::MotionPort* const> axes) {
  const ModuleTypeRow& row = row_of(type);
  if (axes.size() != row.shape.axes) {
    throw std::invalid_argument("module needs one motion port per axis");
  }
  return row.make_personality(io, axes);
}

}  // namespace stepmod::registry
