#include "web/module_views.hpp"

#include <array>
#include <stdexcept>
#include <string>

namespace stepmod::web {
namespace {

// ---- one row per module type, in kModuleShapes' order --------------------------------------

constexpr std::array kViews = {
    ModuleView{ModuleType::k3601, view3601::registers, view3601::status_words,
               view3601::config_bits, view3601::make_controls},
    ModuleView{ModuleType::k3602, view3602::registers, view3602::status_words,
               view3602::config_bits, view3602::make_controls},
    ModuleView{ModuleType::k3202, view3202::registers, view3202::status_words,
               view3202::config_bits, view3202::make_controls},
};

constexpr bool views_match_shapes() {
  if (kViews.size() != kModuleShapes.size()) return false;
  for (std::size_t i = 0; i < kViews.size(); ++i) {
    if (kViews[i].type != kModuleShapes[i].type) return false;
  }
  return true;
}
static_assert(views_match_shapes(), "a module type needs one console row, in kModuleShapes' order");

}  // namespace

const ModuleView& view_of(ModuleType type) {
  for (const ModuleView& v : kViews) {
    if (v.type == type) return v;
  }
  throw std::invalid_argument("no console view for module type " +
                              std::to_string(static_cast<unsigned>(type)));
}

}  // namespace stepmod::web
