#pragma once
// The 3202's stepmodctl functions (ctl_3202.cpp, ctl_status_3202.cpp), declared for every
// translation unit that uses its row kCtlRowOf<ModuleType::k3202> (tools/ctl_row_of.hpp says why).
#include "tools/ctl_row_of.hpp"

namespace stepmod::tools::ctl {
STEPMOD_DECLARE_CTL_OF(ModuleType::k3202);
}  // namespace stepmod::tools::ctl
