#pragma once
// The config file of the end-to-end tests: a 3601 on the simulated machine with every input
// wired, named {NAME} (DaemonProcess fills in a unique name).
#include <string>

namespace stepmod::testing {

// The late-edge guard's limits of the end-to-end tests that are not about it: the longest pause
// 1 s, and no lag limit in practice. A test of the module's behaviour must not fail because this
// shared machine (a loaded two-core VM with six developers' builds, the sanitizers, qemu)
// stalled the pulse thread, which the product's guard rightly turns into a fault: above the
// starting speed, a pause of more than 8 steps (0.8 ms at 10,000 steps/s) is one, and such
// pauses happen here in ordinary release builds too. The guard's own tests pass
// kDefaultLateLimit and no axis key (the product's defaults). Under TSan, with two daemon tests'
// SCHED_FIFO pulse threads on two CPUs, stalls of more than 200 ms are on record.
inline constexpr const char* kRelaxedLateLimit = "late_limit_us = 1000000\n";
inline constexpr const char* kRelaxedLagLimit = "lag_limit_steps = 1000000\n";
inline constexpr const char* kDefaultLateLimit = "late_limit_us = 200000\n";

// `module_extra`: more [module] keys (e.g. "plc_timeout_ms = 300"); `sim`: the [axis.sim] keys;
// `rt_extra`: more [rt] keys; `axis_extra`: more [[axis]] keys.
inline std::string sim_3601_config(const std::string& module_extra, const std::string& sim,
                                   const std::string& rt_extra = kRelaxedLateLimit,
                                   const std::string& axis_extra = kRelaxedLagLimit) {
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
)" + axis_extra +
         R"(
[axis.sim]
)" + sim;
}

}  // namespace stepmod::testing
