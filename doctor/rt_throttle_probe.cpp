#include "doctor/rt_throttle_probe.hpp"

#include <charconv>

namespace stepmod::doctor {

std::optional<std::int64_t> parse_integer(std::string_view text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.remove_suffix(1);
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc{} || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return v;
}

std::int64_t RtThrottle::withheld_us_per_s() const {
  if (!runtime_us || !period_us || *runtime_us < 0 || *period_us <= 0) return 0;
  return (*period_us - *runtime_us) * 1'000'000 / *period_us;
}

RtThrottle probe_rt_throttle(const SysRoot& root) {
  RtThrottle t;
  if (const auto s = root.read("/proc/sys/kernel/sched_rt_runtime_us")) t.runtime_us = parse_integer(*s);
  if (const auto s = root.read("/proc/sys/kernel/sched_rt_period_us")) t.period_us = parse_integer(*s);
  return t;
}

}  // namespace stepmod::doctor
