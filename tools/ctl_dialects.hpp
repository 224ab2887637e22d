#pragma once
// stepmodctl's module dialects: a parsed command (ctl_command.hpp) → the PLC library's calls
// for the module the image belongs to. Each checks every option against its module's words
// first and throws UsageError before anything is written; then it runs the command over `port`
// and returns its outcome. One file per module: ctl_3601.cpp, ctl_3602.cpp, ctl_3202.cpp. The
// registry row of each module type (registry/module_registry.cpp) points at its functions here.
#include <chrono>
#include <sstream>
#include <vector>

#include "ipc/client.hpp"
#include "plc/port.hpp"
#include "plc/profile.hpp"
#include "tools/ctl_command.hpp"
#include "tools/ctl_summary.hpp"

namespace stepmod::tools::ctl {

plc::Outcome run_3601(const Command& c, plc::Port& port, std::chrono::milliseconds timeout);
plc::Outcome run_3602(const Command& c, plc::Port& port, std::chrono::milliseconds timeout);
// The 3202's blend profile travels as a message through the image's mailbox (`client`).
plc::Outcome run_3202(const Command& c, plc::Port& port, ipc::Client& client,
                      std::chrono::milliseconds timeout);

// The status display (stepmodctl status) and the per-axis summary of each module's input image:
// module_types/m3601/ctl_status_3601.cpp, ctl_status_3602.cpp, ctl_status_3202.cpp.
void format_status_3601(std::ostringstream& o, const ImageWords& in);
void format_status_3602(std::ostringstream& o, const ImageWords& in);
void format_status_3202(std::ostringstream& o, const ImageWords& in);
std::vector<AxisSummary> summarize_3601(const ImageWords& in);
std::vector<AxisSummary> summarize_3602(const ImageWords& in);
std::vector<AxisSummary> summarize_3202(const ImageWords& in);

// The seconds of jog --for / wait-idle --max as a duration.
inline std::chrono::milliseconds millis(double seconds) {
  return std::chrono::milliseconds(static_cast<long>(seconds * 1000));
}

}  // namespace stepmod::tools::ctl
