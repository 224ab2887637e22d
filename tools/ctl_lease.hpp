#pragma once
// stepmodctl and the commissioning lease (docs/interface.md 3.5, docs/commissioning.md): the lease
// excludes. A command finds it held by another running process: refused (exit 1, the holder's pid,
// nothing written), unless the operator takes it over with --steal (logged by stepmodctl and by
// the daemon). A dead holder's lease is waited out (the daemon frees it within 500 ms). An
// Immediate Stop is never refused and never takes the lease, nor does `path wait`; status, watch,
// raw get and wait-idle command nothing and do not come here.
#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <memory>

#include "ipc/client.hpp"
#include "ipc/lease_client.hpp"

namespace stepmod::tools::ctl {

struct LeaseRequest {
  bool hold = false;   // --wait of a motion: hold the lease (when no PLC is in control) to its end
  bool steal = false;  // --steal: take it over from another holder (logged)
  // An Immediate Stop, or a wait that commands nothing (path wait): never refused, no lease.
  bool never_refused = false;
  std::chrono::milliseconds timeout{2000};  // for the daemon to see the take
};

struct LeasePlan {
  std::unique_ptr<ipc::LeaseClient> lease;  // held for the command (and its wait)
  bool refused = false;                     // another process holds it: exit 1, nothing written
  bool heartbeat = true;  // the command may bump the PLC heartbeat (no lease held by anyone)
};

// What a module command does about the lease; the messages go to `err`.
LeasePlan plan_lease(ipc::Client& client, const LeaseRequest& r, std::ostream& err);

}  // namespace stepmod::tools::ctl
