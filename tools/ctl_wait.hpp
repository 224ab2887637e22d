#pragma once
// stepmodctl's waiting: wait-idle and --wait (the end of a motion and why), and whether the daemon
// scans at all. The commissioning lease a --wait command holds is tools/ctl_lease.hpp's.
#include <chrono>
#include <iosfwd>
#include <vector>

#include "ipc/client.hpp"
#include "tools/ctl_summary.hpp"

namespace stepmod::tools::ctl {

// Whether the scan counter advances within `limit` (a SIGSTOPped or hung daemon does not).
bool daemon_scanning(const ipc::Client& client, std::chrono::milliseconds limit);

// Waits until none of `units` (0-based) moves, at most `limit`; then judges how each motion
// ended (judge_end) and prints a line per unit that did not end well to `err`. Returns the exit
// status: 0 every unit ended well, 1 one did not (or still moves at `limit`), 3 the daemon
// stopped scanning.
int wait_motion_end(ipc::Client& client, const std::vector<unsigned>& units, Motion kind,
                    std::chrono::nanoseconds limit, std::ostream& out, std::ostream& err);

// A motion started without --wait: if the daemon watches the PLC heartbeat and no PLC keeps it
// alive (health bit 1 now), say that [module] plc_timeout_ms will stop the motion.
void warn_heartbeat_timeout(const ipc::Client& client, std::ostream& err);

}  // namespace stepmod::tools::ctl
