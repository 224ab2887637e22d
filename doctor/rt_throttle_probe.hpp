#pragma once
// Real-time throttling: of every sched_rt_period_us, real-time threads may use
// sched_rt_runtime_us (-1: unlimited). Default 950000 of 1000000: a SCHED_FIFO thread that keeps
// its CPU busy loses it for 50 ms each second (docs/performance.md, "A CPU of its own").
#include <cstdint>
#include <optional>

#include "doctor/sys_root.hpp"

namespace stepmod::doctor {

struct RtThrottle {
  std::optional<std::int64_t> runtime_us;  // nullopt: unread
  std::optional<std::int64_t> period_us;
  bool off() const { return runtime_us && *runtime_us < 0; }
  // Microseconds of each second real-time threads give up (0 when off or unread).
  std::int64_t withheld_us_per_s() const;
};

std::optional<std::int64_t> parse_integer(std::string_view text);
RtThrottle probe_rt_throttle(const SysRoot& root);

}  // namespace stepmod::doctor
