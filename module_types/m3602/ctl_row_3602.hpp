#pragma once
// The 3602's row of stepmodctl (tools/ctl_dialects.hpp): its dialect (ctl_3602.cpp), its status
// display and summary (ctl_status_3602.cpp).
#include <chrono>
#include <sstream>
#include <vector>

#include "tools/ctl_dialects.hpp"

namespace stepmod::tools::ctl {

plc::Outcome run_3602(const CtlRequest& c, plc::Port& port, std::chrono::milliseconds timeout);
void format_status_3602(std::ostringstream& o, const ImageWords& in);
std::vector<AxisSummary> summarize_3602(const ImageWords& in);

inline constexpr CtlRow kCtlRow3602{
    .type = ModuleType::k3602,
    .run_command = [](const CtlRequest& c, plc::Port& p, ipc::Client&,
                      std::chrono::milliseconds t) { return run_3602(c, p, t); },
    .format_status = format_status_3602,
    .summarize = summarize_3602,
};

}  // namespace stepmod::tools::ctl
