#include "web/module_views.hpp"

#include <stdexcept>
#include <string>

#include "module_types/view_rows.hpp"  // generated: kViewRows, one per module type

namespace stepmod::web {
namespace {

using module_types::kViewRows;

constexpr bool views_match_shapes() {
  if (kViewRows.size() != kModuleShapes.size()) return false;
  for (std::size_t i = 0; i < kViewRows.size(); ++i) {
    if (kViewRows[i]->type != kModuleShapes[i].type) return false;
  }
  return true;
}
static_assert(views_match_shapes(), "a module type needs one console row, in kModuleShapes' order");

}  // namespace

const ModuleView& view_of(ModuleType type) {
  for (const ModuleView* v : kViewRows) {
    if (v->type == type) return *v;
  }
  throw std::invalid_argument("no console view for module type " +
                              std::to_string(static_cast<unsigned>(type)));
}

}  // namespace stepmod::web
