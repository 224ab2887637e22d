#pragma once
// The PLC supervision's verdicts said in the log as they start and end (heartbeat stale,
// output sequence stuck odd, a writer bypassing the seqlock: ipc/plc_supervisor.hpp).
// Control thread, after each scan's supervision.
#include "core/clock.hpp"
#include "ipc/plc_supervisor.hpp"

namespace stepmod::tools {

void log_supervision(const ipc::PlcSupervisor& sup, Nanos now);

}  // namespace stepmod::tools
