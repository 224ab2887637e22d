#include "doctor/board_facts.hpp"

#include "doctor/cpu_list.hpp"
#include "doctor/governor_probe.hpp"

namespace stepmod::doctor {

BoardFacts probe_board(const SysRoot& root, int pulse_cpu, int self_pid, int self_uid) {
  BoardFacts f;
  f.pulse_cpu = pulse_cpu;
  f.preempt = probe_preempt(root);
  f.cpus = probe_cpu_isolation(root);
  if (pulse_cpu >= 0) f.tenants = probe_tenants(root, pulse_cpu, self_pid);
  f.throttle = probe_rt_throttle(root);
  f.governor = probe_governor(root, pulse_cpu);
  f.rtprio = probe_rtprio(root, self_pid, self_uid);
  return f;
}

bool pulse_cpu_alone(const BoardFacts& f) {
  return f.pulse_cpu >= 0 && contains(f.cpus.online, f.pulse_cpu) && f.tenants.user_tasks == 0;
}

}  // namespace stepmod::doctor
