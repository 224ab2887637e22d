#include "tools/ctl_dialects.hpp"

#include <stdexcept>
#include <string>

#include "module_types/ctl_rows.hpp"  // generated: kCtlRows, one per module type

namespace stepmod::tools::ctl {
namespace {

using module_types::kCtlRows;

constexpr bool rows_match_shapes() {
  if (kCtlRows.size() != kModuleShapes.size()) return false;
  for (std::size_t i = 0; i < kCtlRows.size(); ++i) {
    if (kCtlRows[i]->type != kModuleShapes[i].type) return false;
  }
  return true;
}
static_assert(rows_match_shapes(),
              "a module type needs one stepmodctl row, in kModuleShapes' order");

}  // namespace

const CtlRow& ctl_row_of(ModuleType type) {
  for (const CtlRow* r : kCtlRows) {
    if (r->type == type) return *r;
  }
  throw std::invalid_argument("unknown module type " + std::to_string(static_cast<unsigned>(type)));
}

}  // namespace stepmod::tools::ctl
