#pragma once
// The 3202's console functions (view_3202.cpp), declared for every translation unit that uses
// its row kViewOf<ModuleType::k3202> (web/module_view_of.hpp says why).
#include "web/module_view_of.hpp"

namespace stepmod::web {
STEPMOD_DECLARE_VIEW_OF(ModuleType::k3202);
}  // namespace stepmod::web
