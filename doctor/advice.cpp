#include "doctor/advice.hpp"

#include "doctor/cpu_list.hpp"

namespace stepmod::doctor {

namespace {

// The CPU to give the pulse thread: the configured one, else the last online CPU.
int cpu_to_isolate(const BoardFacts& f) {
  if (f.pulse_cpu >= 0) return f.pulse_cpu;
  return f.cpus.online.empty() ? -1 : f.cpus.online.back();
}

void advise_cpu(const BoardFacts& f, std::vector<std::string>& out) {
  const int cpu = cpu_to_isolate(f);
  if (f.cpus.online.size() < 2) {
    out.push_back("this board has one CPU: a CPU of its own for the pulse thread needs a board "
                  "with two or more");
    return;
  }
  const std::string n = std::to_string(cpu);
  if (f.pulse_cpu < 0 || !pulse_cpu_alone(f)) {
    out.push_back("give the pulse thread CPU " + n + " of its own: `stepmodctl isolate --cpu " + n +
                  " --config FILE` (sets [rt] cpu = " + n +
                  ", the systemd drop-ins and the sysctl), or boot with isolcpus=" + n +
                  " nohz_full=" + n + " rcu_nocbs=" + n);
  }
  if (!contains(f.cpus.nohz_full, cpu)) {
    out.push_back("stop the periodic tick on CPU " + n + ": kernel command line nohz_full=" + n);
  }
}

}  // namespace

std::vector<std::string> advise(const AdviceInput& in) {
  const BoardFacts& f = in.facts;
  std::vector<std::string> out;
  if (!in.wake.fifo) {
    out.push_back("the probe ran without SCHED_FIFO (run it as root or as the service user with "
                  "LimitRTPRIO): the daemon's pulse thread will do better or worse than measured");
  }
  if (!f.preempt.rt) {
    out.push_back("boot a PREEMPT_RT kernel (Raspberry Pi OS: its RT kernel; Debian: apt install "
                  "linux-image-rt-arm64, -rt-amd64 on x86): the wake-up tail drops from hundreds "
                  "of us to tens");
  }
  advise_cpu(f, out);
  if (!f.throttle.off()) {
    out.push_back("with the CPU isolated, turn real-time throttling off: "
                  "kernel.sched_rt_runtime_us = -1 (stepmodctl isolate writes it)");
  }
  if (!f.governor.empty() && f.governor != "performance") {
    out.push_back("set the CPU frequency governor to performance (now " + f.governor +
                  "): echo performance > /sys/devices/system/cpu/cpu*/cpufreq/scaling_governor");
  }
  if (!f.rtprio.root && f.rtprio.soft.value_or(0) < in.priority) {
    out.push_back("let " + f.rtprio.user + " take SCHED_FIFO priority " +
                  std::to_string(in.priority) + ": LimitRTPRIO=99 in the unit (or limits.conf)");
  }
  if (in.late_limit_exceeded) {
    out.push_back("the worst pause exceeds [rt] late_limit_us: every motion may fault; find what "
                  "holds the CPU (the tenants above) or raise late_limit_us");
  }
  out.push_back("a larger [axis] lag_limit_steps raises an axis' safe rate in proportion (at the "
                "cost of a larger lag a pause may leave)");
  return out;
}

}  // namespace stepmod::doctor
