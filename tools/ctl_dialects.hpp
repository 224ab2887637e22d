#pragma once
// stepmodctl's side of each module type, one row each (the client counterpart of the daemon's
// registry row, registry/module_registry.hpp): its dialect, a parsed command (ctl_command.hpp) ->
// the PLC library's calls for the module the image belongs to, which checks every option against
// its module's words first and throws UsageError before anything is written, then runs the
// command over `port` and returns its outcome; its status display; its per-axis summary. Each row
// is kCtlRowOf<T> (tools/ctl_row_of.hpp), pointing at the functions of its type's ctl_XXXX.cpp and
// ctl_status_XXXX.cpp, and is collected by the generated module_types/ctl_rows.hpp.
#include <chrono>
#include <sstream>
#include <vector>

#include "core/module_shape.hpp"
#include "ipc/client.hpp"
#include "plc/move_profile.hpp"
#include "plc/port.hpp"
#include "tools/ctl_command.hpp"
#include "tools/ctl_summary.hpp"

namespace stepmod::tools::ctl {

// The dialect: a parsed command -> the plc/ calls (messages, such as the 3202's blend profile,
// travel through the image's mailbox, `client`).
using RunCommand = plc::Outcome(const CtlRequest& c, plc::Port& port, ipc::Client& client,
                                std::chrono::milliseconds timeout);
// stepmodctl status: the decoded input image, multi-line.
using FormatStatus = void(std::ostringstream& o, const ImageWords& in);
// Every axis/channel in a few words (stepmodctl --brief, --json, wait-idle, --wait).
using Summarize = std::vector<AxisSummary>(const ImageWords& in);

struct CtlRow {
  ModuleType type;
  RunCommand* run_command;      // module_types/mXXXX/ctl_XXXX.cpp
  FormatStatus* format_status;  // module_types/mXXXX/ctl_status_XXXX.cpp
  Summarize* summarize;         // module_types/mXXXX/ctl_status_XXXX.cpp
};

// The row of `type`. Throws std::invalid_argument for a number that is no module type.
const CtlRow& ctl_row_of(ModuleType type);

// The seconds of jog --for / wait-idle --max as a duration.
inline std::chrono::milliseconds millis(double seconds) {
  return std::chrono::milliseconds(static_cast<long>(seconds * 1000));
}

}  // namespace stepmod::tools::ctl
