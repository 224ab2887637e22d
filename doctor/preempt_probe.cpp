#include "doctor/preempt_probe.hpp"

namespace stepmod::doctor {

std::string model_of_version(std::string_view version) {
  for (const char* m : {"PREEMPT_RT", "PREEMPT_DYNAMIC"}) {
    if (version.find(m) != std::string_view::npos) return m;
  }
  // " PREEMPT " as a word (older kernels print "SMP PREEMPT"); otherwise no full preemption.
  if (version.find("PREEMPT") != std::string_view::npos) return "PREEMPT";
  return "voluntary or none";
}

std::string chosen_preempt_mode(std::string_view text) {
  const auto open = text.find('(');
  const auto close = text.find(')', open);
  if (open == std::string_view::npos || close == std::string_view::npos) return "";
  return std::string(text.substr(open + 1, close - open - 1));
}

PreemptModel probe_preempt(const SysRoot& root) {
  PreemptModel m;
  m.version = root.read_line("/proc/sys/kernel/version").value_or("");
  m.model = model_of_version(m.version);
  m.rt = root.read_line("/sys/kernel/realtime").value_or("") == "1" || m.model == "PREEMPT_RT";
  if (m.rt) m.model = "PREEMPT_RT";
  if (const auto mode = root.read_line("/sys/kernel/debug/sched/preempt")) {
    m.dynamic_mode = chosen_preempt_mode(*mode);
  }
  return m;
}

}  // namespace stepmod::doctor
