#include "web/module_views.hpp"

#include "core/module_rows.hpp"
#include "module_types/view_rows.hpp"  // generated: kViewRows, one per module type

namespace stepmod::web {

static_assert(rows_follow_shapes(module_types::kViewRows),
              "a module type needs one console row, in kModuleShapes' order");

const ModuleView& view_of(ModuleType type) {
  return row_of_type(module_types::kViewRows, type, "no console view for module type ");
}

}  // namespace stepmod::web
