#pragma once
// The 3601's row of stepmodctl (tools/ctl_dialects.hpp): its dialect (ctl_3601.cpp), its status
// display and summary (ctl_status_3601.cpp).
#include <chrono>
#include <sstream>
#include <vector>

#include "tools/ctl_dialects.hpp"

namespace stepmod::tools::ctl {

plc::Outcome run_3601(const CtlRequest& c, plc::Port& port, std::chrono::milliseconds timeout);
void format_status_3601(std::ostringstream& o, const ImageWords& in);
std::vector<AxisSummary> summarize_3601(const ImageWords& in);

inline constexpr CtlRow kCtlRow3601{
    .type = ModuleType::k3601,
    .run_command = [](const CtlRequest& c, plc::Port& p, ipc::Client&,
                      std::chrono::milliseconds t) { return run_3601(c, p, t); },
    .format_status = format_status_3601,
    .summarize = summarize_3601,
};

}  // namespace stepmod::tools::ctl
