#include "tools/ctl_dialects.hpp"

#include "core/module_rows.hpp"
#include "module_types/ctl_rows.hpp"  // generated: kCtlRows, one per module type

namespace stepmod::tools::ctl {

static_assert(rows_follow_shapes(module_types::kCtlRows),
              "a module type needs one stepmodctl row, in kModuleShapes' order");

const CtlRow& ctl_row_of(ModuleType type) {
  return row_of_type(module_types::kCtlRows, type, "unknown module type ");
}

}  // namespace stepmod::tools::ctl
