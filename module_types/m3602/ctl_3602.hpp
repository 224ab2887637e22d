#pragma once
// The 3602's stepmodctl functions (ctl_3602.cpp, ctl_status_3602.cpp), declared for every
// translation unit that uses its row kCtlRowOf<ModuleType::k3602> (tools/ctl_row_of.hpp says why).
#include "tools/ctl_row_of.hpp"

namespace stepmod::tools::ctl {
STEPMOD_DECLARE_CTL_OF(ModuleType::k3602);
}  // namespace stepmod::tools::ctl
