#pragma once
// The config file of the end-to-end tests: a 3601 on the simulated machine with every input
// wired, named {NAME} (DaemonProcess fills in a unique name).
#include <string>

namespace stepmod::testing {

// The late-edge guard's limit of the end-to-end tests that are not about it: its maximum, 1 s.
// A test of the module's behaviour must not fail because this shared machine (a loaded two-core
// VM, the sanitizers, qemu) stalled the pulse thread, which the default 1 ms limit rightly turns
// into a fault; the guard's own tests pass kDefaultLateLimit. 200 ms was not enough: under TSan,
// with two daemon tests' SCHED_FIFO pulse threads on two CPUs (equal FIFO priorities do not
// share a CPU), stalls of more than 200 ms cut moves (a trace test; a stepmodctl hold/resume).
inline constexpr const char* kRelaxedLateLimit = "late_limit_us = 1000000\n";
inline constexpr const char* kDefaultLateLimit = "late_limit_us = 1000\n";

// `module_extra`: more [module] keys (e.g. "plc_timeout_ms = 300"); `sim`: the [axis.sim] keys;
// `rt_extra`: more [rt] keys.
inline std::string sim_3601_config(const std::string& module_extra, const std::string& sim,
                                   const std::string& rt_extra = kRelaxedLateLimit) {
  return R"(
[module]
type = "3601"
name = "{NAME}"
scan_us = 1000
)" + module_extra +
         R"(
[gpio]
backend = "sim"

[rt]
priority = 80
)" + rt_extra +
         R"(

[[axis]]
step = 1
dir = 2
capture = 3
external = 4
home = 5
estop = 6
cw_limit = 7
ccw_limit = 8
enc_a = 9
enc_b = 10
enc_z = 11

[axis.sim]
)" + sim;
}

}  // namespace stepmod::testing
