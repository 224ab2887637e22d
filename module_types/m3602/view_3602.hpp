#pragma once
// The 3602's console functions (view_3602.cpp), declared for every translation unit that uses
// its row kViewOf<ModuleType::k3602> (web/module_view_of.hpp says why).
#include "web/module_view_of.hpp"

namespace stepmod::web {
STEPMOD_DECLARE_VIEW_OF(ModuleType::k3602);
}  // namespace stepmod::web
