#pragma once
// The config files of the end-to-end tests: modules on the simulated machine, named {NAME}
// (DaemonProcess fills in a unique name); a 3601 with every input wired in one call.
#include <cstdint>
#include <initializer_list>
#include <string>

#include "config/config_keys.hpp"

namespace stepmod::testing {

namespace sim_config_detail {
// "late_limit_us = 200000\n": `key` = `value`, a line of its table.
inline std::string key_line(const tools::ConfigKey& key, std::int64_t value) {
  return std::string(key.key) + " = " + std::to_string(value) + "\n";
}
inline const tools::ConfigKey& kLateLimit = tools::config_key("rt", "late_limit_us");
inline const tools::ConfigKey& kLagLimit = tools::config_key("axis", "lag_limit_steps");
inline const std::string kRelaxedLate = key_line(kLateLimit, kLateLimit.max);
inline const std::string kRelaxedLag = key_line(kLagLimit, kLagLimit.max);
inline const std::string kDefaultLate = key_line(kLateLimit, kLateLimit.def);
}  // namespace sim_config_detail

// The late-edge guard's limits of the end-to-end tests that are not about it: the longest pause
// and the largest lag the keys allow (config/config_keys.hpp), no lag limit in practice. A test
// of the module's behaviour must not fail because this shared machine (a loaded two-core VM with
// six developers' builds, the sanitizers, qemu) stalled the pulse thread, which the product's
// guard rightly turns into a fault: above the starting speed, a pause of more than the default
// lag limit's steps (0.8 ms at 10,000 steps/s) is one, and such pauses happen here in ordinary
// release builds too. The guard's own tests pass kDefaultLateLimit and no axis key (the
// product's defaults). Under TSan, with two daemon tests' SCHED_FIFO pulse threads on two CPUs,
// stalls longer than the default pause limit are on record.
inline const char* const kRelaxedLateLimit = sim_config_detail::kRelaxedLate.c_str();
inline const char* const kRelaxedLagLimit = sim_config_detail::kRelaxedLag.c_str();
inline const char* const kDefaultLateLimit = sim_config_detail::kDefaultLate.c_str();

// The [module], [gpio] and [rt] tables of every end-to-end test: a module of `type` on the
// simulated machine, named {NAME}, scanning every 1 ms, its pulse thread at SCHED_FIFO 80.
// `module_extra`: more [module] keys; `rt_extra`: more [rt] keys.
inline std::string sim_module_tables(const std::string& type, const std::string& module_extra = "",
                                     const std::string& rt_extra = kRelaxedLateLimit) {
  return "\n[module]\ntype = \"" + type + "\"\nname = \"{NAME}\"\nscan_us = 1000\n" + module_extra +
         "\n[gpio]\nbackend = \"sim\"\n\n[rt]\npriority = 80\n" + rt_extra;
}

// "key = n" lines: `keys` numbered from `first` up.
inline std::string numbered_lines(unsigned first, std::initializer_list<const char*> keys) {
  std::string out;
  for (const char* key : keys) out += std::string(key) + " = " + std::to_string(first++) + "\n";
  return out;
}

// Every line a 3601/3202 axis has, numbered from `first` up in the order the tests use.
inline std::string every_axis_line(unsigned first) {
  return numbered_lines(first, {"step", "dir", "capture", "external", "home", "estop", "cw_limit",
                                "ccw_limit", "enc_a", "enc_b", "enc_z"});
}

// One [[axis]] table: its `lines` ("step = 1\n..."), `axis_extra` (more [[axis]] keys), then its
// [axis.sim] table with the keys `sim`.
inline std::string sim_axis(const std::string& lines, const std::string& sim,
                            const std::string& axis_extra = kRelaxedLagLimit) {
  return "\n[[axis]]\n" + lines + axis_extra + "\n[axis.sim]\n" + sim;
}

// `module_extra`: more [module] keys (e.g. "plc_timeout_ms = 300"); `sim`: the [axis.sim] keys;
// `rt_extra`: more [rt] keys; `axis_extra`: more [[axis]] keys.
inline std::string sim_3601_config(const std::string& module_extra, const std::string& sim,
                                   const std::string& rt_extra = kRelaxedLateLimit,
                                   const std::string& axis_extra = kRelaxedLagLimit) {
  return sim_module_tables("3601", module_extra, rt_extra) +
         sim_axis(every_axis_line(1), sim, axis_extra);
}

}  // namespace stepmod::testing
