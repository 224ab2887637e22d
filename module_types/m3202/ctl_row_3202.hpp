#pragma once
// The 3202's row of stepmodctl (tools/ctl_dialects.hpp): its dialect (ctl_3202.cpp), its status
// display and summary (ctl_status_3202.cpp).
#include <chrono>
#include <sstream>
#include <vector>

#include "tools/ctl_dialects.hpp"

namespace stepmod::tools::ctl {

// The 3202's blend profile travels as a message through the image's mailbox (`client`).
plc::Outcome run_3202(const CtlRequest& c, plc::Port& port, ipc::Client& client,
                      std::chrono::milliseconds timeout);
void format_status_3202(std::ostringstream& o, const ImageWords& in);
std::vector<AxisSummary> summarize_3202(const ImageWords& in);

inline constexpr CtlRow kCtlRow3202{
    .type = ModuleType::k3202,
    .run_command = run_3202,
    .format_status = format_status_3202,
    .summarize = summarize_3202,
};

}  // namespace stepmod::tools::ctl
