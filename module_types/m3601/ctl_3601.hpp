#pragma once
// The 3601's stepmodctl functions (ctl_3601.cpp, ctl_status_3601.cpp), declared for every
// translation unit that uses its row kCtlRowOf<ModuleType::k3601> (tools/ctl_row_of.hpp says why).
#include "tools/ctl_row_of.hpp"

namespace stepmod::tools::ctl {
STEPMOD_DECLARE_CTL_OF(ModuleType::k3601);
}  // namespace stepmod::tools::ctl
