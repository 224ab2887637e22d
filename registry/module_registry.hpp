#pragma once
// The module types as the daemon sees them, one row each (model: LinuxCNC stepgen.c's
// master_lut, where a variant is a table row): its number and name, its image shape, its rules
// value (what the shared axis does differently) and the factory of its personality. Each row is
// made from its module type's personality class (registry/module_type_row_of.hpp) and collected by
// the generated module_types/registry_rows.hpp; stepmodctl's side of a type is its CtlRow
// (tools/ctl_dialects.hpp), the console's its ModuleView (web/module_views.hpp). Code that needs
// one of these for a type looks the row up here: nothing else switches on the module type.
//
// The image shapes themselves are written in core/module_shape.hpp (kModuleShapes), because
// ipc/, plc/ and the config checker sit below this library; the row repeats nothing, it reads the
// shape from there, and module_registry.cpp checks at compile time that the two lists agree.
#include <memory>
#include <span>
#include <string_view>

#include "core/module_shape.hpp"
#include "module/axis/axis_io.hpp"
#include "module/axis/error_reason.hpp"
#include "module/axis/rules.hpp"
#include "module/personality.hpp"
#include "planner/motion_port.hpp"

namespace stepmod::registry {

// The personality over one motion port per axis (the row's shape.axes of them).
using MakePersonality = std::unique_ptr<module::Personality>(
    module::AxisIo& io, std::span<planner::MotionPort* const> axes);

struct ModuleTypeRow {
  ModuleType type;                         // its number, as the image header carries it
  std::string_view name;                   // as the config file ([module] type) writes it
  ModuleShape shape;                       // core/module_shape.hpp
  const module::axis::ModuleRules* rules;  // module_types/mXXXX/rules_XXXX.hpp
  MakePersonality* make_personality;       // module_types/mXXXX/module_XXXX.hpp
  // The error conditions only this type has, beside the shared ones of module/axis/
  // error_items.hpp (the console's help on reasons lists both); none by default.
  std::span<const module::axis::Item* const> own_items{};
};

// Every row, in kModuleShapes' order.
std::span<const ModuleTypeRow* const> module_type_rows() noexcept;

// The row of `type`. Throws std::invalid_argument for a number that is no module type (a
// ModuleType made from an unchecked number).
const ModuleTypeRow& row_of(ModuleType type);

// The personality for `type` over `axes` (one MotionPort per axis of the module); throws
// std::invalid_argument when the count is not the module's.
std::unique_ptr<module::Personality> make_personality(ModuleType type, module::AxisIo& io,
                                                      std::span<planner::MotionPort* const> axes);

}  // namespace stepmod::registry
