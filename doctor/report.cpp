#include "doctor/report.hpp"

#include <cstring>
#include <iomanip>
#include <sstream>

#include "doctor/cpu_list.hpp"

namespace stepmod::doctor {

namespace {

std::string list_or_none(const std::vector<int>& cpus) {
  return cpus.empty() ? "none" : format_cpu_list(cpus);
}

std::string us(Nanos ns) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(ns < 10 * kNsPerUs ? 1 : 0)
    << static_cast<double>(ns) / 1e3 << " us";
  return s.str();
}

void print_tenants(const BoardFacts& f, std::ostream& out) {
  out << "pulse cpu: ";
  if (f.pulse_cpu < 0) {
    out << "not pinned ([rt] cpu = -1): the pulse thread shares every CPU with everything else\n";
    return;
  }
  const CpuTenants& t = f.tenants;
  out << "CPU " << f.pulse_cpu << (contains(f.cpus.online, f.pulse_cpu) ? "" : " (NOT ONLINE)")
      << ": " << t.user_tasks << " other user threads may run there, " << t.ran_there
      << " last ran there";
  for (std::size_t i = 0; i < t.names.size(); ++i) out << (i == 0 ? " (" : ", ") << t.names[i];
  out << (t.names.empty() ? "" : ")") << "; " << t.kernel_tasks << " kernel threads"
      << (pulse_cpu_alone(f) ? ": a CPU of its own\n" : ": shared\n");
}

}  // namespace

void print_board(const BoardFacts& f, int priority, std::ostream& out) {
  out << "kernel: " << f.preempt.model
      << (f.preempt.dynamic_mode.empty() ? "" : " (mode " + f.preempt.dynamic_mode + ")")
      << (f.preempt.rt ? "" : ", not PREEMPT_RT") << " [" << f.preempt.version << "]\n";
  out << "cpus: online " << list_or_none(f.cpus.online) << "; isolated "
      << list_or_none(f.cpus.isolated) << "; nohz_full " << list_or_none(f.cpus.nohz_full) << "\n";
  print_tenants(f, out);
  out << "rt throttling: ";
  if (!f.throttle.runtime_us) {
    out << "unread\n";
  } else if (f.throttle.off()) {
    out << "off (sched_rt_runtime_us -1)\n";
  } else {
    out << "on: sched_rt_runtime_us " << *f.throttle.runtime_us << " of "
        << f.throttle.period_us.value_or(0) << ", " << f.throttle.withheld_us_per_s() / 1000
        << " ms of each second go to normal threads\n";
  }
  out << "cpu governor: "
      << (f.governor.empty() ? "none (no cpufreq: a fixed clock or a VM)" : f.governor) << "\n";
  out << "rtprio: " << f.rtprio.user << ": RLIMIT_RTPRIO "
      << (f.rtprio.soft ? std::to_string(*f.rtprio.soft) : std::string("unknown")) << " ("
      << f.rtprio.source << ")" << (f.rtprio.root ? "; the caller is root (CAP_SYS_NICE)" : "")
      << "; [rt] priority " << priority << "\n";
}

void print_gpio(const std::vector<gpio::GpioChipInfo>& chips, const std::string& lines_note,
                const std::vector<LineCheck>& lines, std::ostream& out) {
  out << "gpio chips:" << (chips.empty() ? " none found" : "") << "\n";
  for (const auto& c : chips) {
    out << "  " << c.name << " [" << c.label << "] " << c.lines << " lines (" << c.path << ")\n";
  }
  out << "gpio lines: " << lines_note << "\n";
  for (const auto& l : lines) {
    out << "  " << l.key << " offset " << l.offset << ": "
        << (!l.use.exists ? "NOT ON THE CHIP"
            : l.use.used  ? "BUSY (used by '" + l.use.consumer + "')"
                          : std::string("free"))
        << "\n";
  }
}

void print_wake(const WakeProbeResult& r, const WakeProbeOptions& o, std::ostream& out) {
  const auto& st = r.status;
  out << "wake-up: " << static_cast<double>(o.duration) / 1e9 << " s, a wake-up every "
      << us(o.interval) << ", "
      << (st.fifo ? "SCHED_FIFO " + std::to_string(o.thread.priority)
                  : std::string("SCHED_OTHER (FIFO refused: ") + std::strerror(st.sched_errno) + ")")
      << ", " << (o.thread.cpu < 0 ? std::string("not pinned")
                  : st.pinned      ? "on CPU " + std::to_string(o.thread.cpu)
                                   : "pinning to CPU " + std::to_string(o.thread.cpu) + " refused")
      << ": " << r.late.count() << " wake-ups, late p50 " << us(r.late.percentile(0.5)) << ", p99 "
      << us(r.late.percentile(0.99)) << ", p99.9 " << us(r.late.percentile(0.999))
      << ", worst pause " << us(r.late.worst()) << "\n";
}

void print_fitness(const Fitness& f, const std::vector<std::string>& advice, std::ostream& out) {
  out << "safe rate: under the configured guard (late_limit_us " << f.late_limit / kNsPerUs
      << "), worst pause " << us(f.worst_pause) << ":\n";
  for (const AxisRate& a : f.axes) {
    out << "  axis " << a.axis << ": lag_limit_steps " << a.lag_limit_steps << " -> safe up to "
        << static_cast<long long>(a.safe_rate) << " steps/s\n";
  }
  out << "verdict: " << (f.fit ? "FIT" : "NOT FIT");
  if (!f.within_late_limit) {
    out << ": the worst pause exceeds late_limit_us (a fault at any speed)";
  } else if (f.needed_rate > 0) {
    out << " for " << static_cast<long long>(f.needed_rate) << " steps/s";
  } else {
    out << " (no --speed given: judged by late_limit_us alone)";
  }
  out << "\nto raise it:\n";
  for (const std::string& a : advice) out << "  - " << a << "\n";
}

}  // namespace stepmod::doctor
