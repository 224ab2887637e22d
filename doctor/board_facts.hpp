#pragma once
// Everything the doctor reads about the board before it measures (each probe is its own file):
// what the start-up notice, the report and the advice are made from.
#include <string>
#include <vector>

#include "doctor/cpu_isolation_probe.hpp"
#include "doctor/preempt_probe.hpp"
#include "doctor/rt_throttle_probe.hpp"
#include "doctor/rtprio_probe.hpp"
#include "doctor/sys_root.hpp"
#include "doctor/tenants_probe.hpp"

namespace stepmod::doctor {

struct BoardFacts {
  int pulse_cpu = -1;  // [rt] cpu (-1: not pinned)
  PreemptModel preempt;
  CpuIsolation cpus;
  CpuTenants tenants;    // of pulse_cpu (when pinned)
  RtThrottle throttle;
  std::string governor;  // of pulse_cpu (CPU 0 when not pinned); "" none
  RtprioLimit rtprio;
};

// `self_pid`, `self_uid`: the caller's (left out of the tenants; the limit's fallback user).
BoardFacts probe_board(const SysRoot& root, int pulse_cpu, int self_pid, int self_uid);

// Whether the pulse CPU is one nothing else is scheduled on: pinned, online, and no other user
// thread may run there.
bool pulse_cpu_alone(const BoardFacts& f);

}  // namespace stepmod::doctor
