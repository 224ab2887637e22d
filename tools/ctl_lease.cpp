#include "tools/ctl_lease.hpp"

#include <syslog.h>
#include <unistd.h>

#include <ostream>
#include <string>
#include <thread>

#include "ipc/lease.hpp"

namespace stepmod::tools::ctl {
namespace {

using Clock = std::chrono::steady_clock;
using Take = ipc::LeaseClient::Take;

std::uint32_t holder_now(const ipc::Client& client) {
  return ipc::Lease::holder_of(client.raw());
}

// A holder that no longer runs (killed, crashed): the daemon frees its lease at most
// kLeaseMaxAheadNs after its last renewal. Waits that long and as much again for it; returns the
// holder then (0: free).
std::uint32_t outwait_dead_holder(const ipc::Client& client, std::uint32_t holder,
                                  std::ostream& err) {
  if (holder == 0 || ipc::Lease::process_running(holder)) return holder;
  err << "stepmodctl: the commissioning lease is held by pid " << holder
      << ", which is not running: waiting for stepmodd to free it\n";
  const auto end = Clock::now() + std::chrono::nanoseconds(2 * ipc::kLeaseMaxAheadNs);
  while (Clock::now() < end) {
    const std::uint32_t now = holder_now(client);
    if (now != holder) return now;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return holder_now(client);
}

LeasePlan refused(std::uint32_t holder, std::ostream& err) {
  err << "stepmodctl: the commissioning lease is held by pid " << holder
      << (ipc::Lease::process_running(holder)
              ? " (running)"
              : " (not running here, yet not freed: does stepmodd scan? another PID namespace?)")
      << ": another tool commands this module; refused, nothing written ('stepmodctl stop' "
         "works without the lease; --steal takes it over, logged)\n";
  LeasePlan p;
  p.refused = true;
  return p;
}

// --steal is the operator overriding another tool's deadman: said here, in the system log, and
// (from the image) in stepmodd's log.
void log_steal(const ipc::Client& client, std::uint32_t from, std::ostream& err) {
  err << "stepmodctl: --steal: the commissioning lease of module '" << client.name()
      << "' taken over from pid " << from << " (logged)\n";
  ::openlog("stepmodctl", LOG_PID, LOG_USER);
  ::syslog(LOG_WARNING,
           "--steal: commissioning lease of module '%s' taken over from pid %u (uid %u)",
           client.name().c_str(), from, static_cast<unsigned>(::getuid()));
  ::closelog();
}

// Takes the lease (over from `from`, if not 0) for the command.
LeasePlan take(ipc::Client& client, const LeaseRequest& r, std::uint32_t from, std::ostream& err) {
  auto lease = std::make_unique<ipc::LeaseClient>(client);
  switch (lease->take_over(from)) {
    case Take::kTaken:
      break;
    case Take::kPlcInControl:
      if (from != 0) {
        err << "stepmodctl: a PLC heartbeat is live while pid " << from
            << " holds the commissioning lease (two writers): not taken over\n";
        return LeasePlan{nullptr, true, false};
      }
      err << "stepmodctl: a PLC heartbeat is live: no commissioning lease taken (the PLC is the "
             "deadman)\n";
      return LeasePlan{};
    case Take::kHeldByOther:
      return refused(holder_now(client), err);
  }
  if (from != 0) log_steal(client, from, err);
  // The daemon has seen the take (and acts on the words again), and the take still stands.
  client.wait_scans(3, r.timeout);
  if (!lease->held()) {
    err << "stepmodctl: the commissioning lease was lost right after its take (holder now: pid "
        << holder_now(client) << "); nothing written\n";
    return LeasePlan{nullptr, true, false};
  }
  return LeasePlan{std::move(lease), false, false};
}

}  // namespace

LeasePlan plan_lease(ipc::Client& client, const LeaseRequest& r, std::ostream& err) {
  std::uint32_t holder = holder_now(client);
  if (r.never_refused) {
    // Under another tool's lease a stop is no PLC: no heartbeat (health bit 7 would report two
    // writers), and the module acts on the words anyway while a lease stands.
    return LeasePlan{nullptr, false, holder == 0};
  }
  if (!r.steal) holder = outwait_dead_holder(client, holder, err);
  if (holder != 0 && !r.steal) return refused(holder, err);
  if (holder != 0 || r.hold) return take(client, r, holder, err);
  return LeasePlan{};
}

}  // namespace stepmod::tools::ctl
