#include "ipc/health.hpp"

namespace stepmod::ipc {

std::vector<std::string> health_flag_list(std::uint32_t flags) {
  static constexpr struct {
    std::uint32_t bit;
    const char* name;
  } kNames[] = {
      {STEPMOD_HEALTH_LATE_EDGE, "late-edge fault"},
      {STEPMOD_HEALTH_PLC_STALE, "PLC heartbeat stale"},
      {STEPMOD_HEALTH_SEQ_STUCK, "output sequence left odd"},
      {STEPMOD_HEALTH_SEQ_BYPASS, "seqlock bypassed"},
      {STEPMOD_HEALTH_TRACE_LOST, "trace records lost"},
      {STEPMOD_HEALTH_INPUT_LOST, "input events lost"},
      {STEPMOD_HEALTH_LEASE_EXPIRED, "commissioning lease expired"},
      {STEPMOD_HEALTH_LEASE_CONFLICT, "PLC heartbeat during a commissioning lease"},
  };
  std::vector<std::string> names;
  for (const auto& n : kNames) {
    if (flags & n.bit) names.emplace_back(n.name);
  }
  return names;
}

std::string health_flag_names(std::uint32_t flags) {
  std::string s;
  for (const std::string& n : health_flag_list(flags)) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "ok" : s;
}

}  // namespace stepmod::ipc
