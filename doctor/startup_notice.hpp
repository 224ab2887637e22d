#pragma once
// What the daemon says at start about its pulse CPU, from the doctor's probes: whether the CPU is
// shared with other threads, real-time throttled, or the kernel not PREEMPT_RT. One call:
//   if (auto n = doctor::pulse_cpu_notice(config.rt_cpu); !n.empty()) spdlog::warn("{}", n);
#include <string>

#include "doctor/board_facts.hpp"
#include "doctor/sys_root.hpp"

namespace stepmod::doctor {

// "" when the pulse CPU is a CPU of its own on a PREEMPT_RT kernel with throttling off. The
// caller's own threads do not count as sharing (they start before the pulse thread moves).
std::string pulse_cpu_notice(int pulse_cpu, const SysRoot& root = SysRoot{});
// The same from facts already read (tests).
std::string pulse_cpu_notice(const BoardFacts& facts);

}  // namespace stepmod::doctor
