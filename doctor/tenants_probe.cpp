#include "doctor/tenants_probe.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "doctor/cpu_list.hpp"

namespace stepmod::doctor {

namespace {

constexpr std::size_t kNamesShown = 8;

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

void count_task(const SysRoot& root, const std::string& task_dir, int cpu, CpuTenants& out) {
  const auto stat = root.read_line(task_dir + "/stat");
  const auto status = root.read(task_dir + "/status");
  if (!stat || !status) return;  // ended meanwhile
  const auto t = parse_task_stat(*stat);
  const auto allowed_text = status_field(*status, "Cpus_allowed_list");
  if (!t || !allowed_text) return;
  const auto allowed = parse_cpu_list(*allowed_text);
  if (!allowed || !contains(*allowed, cpu)) return;
  if (t->kernel_thread()) {
    ++out.kernel_tasks;
    return;
  }
  ++out.user_tasks;
  if (t->processor != cpu) return;
  ++out.ran_there;
  if (out.names.size() < kNamesShown &&
      std::find(out.names.begin(), out.names.end(), t->comm) == out.names.end()) {
    out.names.push_back(t->comm);
  }
}

}  // namespace

std::optional<TaskStat> parse_task_stat(std::string_view line) {
  const auto open = line.find('(');
  const auto close = line.rfind(')');
  if (open == std::string_view::npos || close == std::string_view::npos || close < open) {
    return std::nullopt;
  }
  TaskStat t;
  t.comm = std::string(line.substr(open + 1, close - open - 1));
  // After the name: field 3 (state) onwards; flags is field 9, processor field 39.
  std::istringstream rest{std::string(line.substr(close + 1))};
  std::string field;
  for (int n = 3; n <= 39 && rest >> field; ++n) {
    if (n == 9) t.flags = std::strtoul(field.c_str(), nullptr, 10);
    if (n == 39) t.processor = static_cast<int>(std::strtol(field.c_str(), nullptr, 10));
  }
  if (t.processor < 0) return std::nullopt;
  return t;
}

std::optional<std::string> status_field(std::string_view status, std::string_view key) {
  std::size_t at = 0;
  while (at < status.size()) {
    const auto nl = status.find('\n', at);
    const std::string_view line = status.substr(at, nl == std::string_view::npos ? nl : nl - at);
    if (line.size() > key.size() && line.substr(0, key.size()) == key &&
        line[key.size()] == ':') {
      std::string_view v = line.substr(key.size() + 1);
      while (!v.empty() && (v.front() == ' ' || v.front() == '\t')) v.remove_prefix(1);
      return std::string(v);
    }
    if (nl == std::string_view::npos) break;
    at = nl + 1;
  }
  return std::nullopt;
}

CpuTenants probe_tenants(const SysRoot& root, int cpu, int self_pid) {
  CpuTenants out;
  out.cpu = cpu;
  for (const std::string& pid : root.list("/proc")) {
    if (!all_digits(pid) || std::strtol(pid.c_str(), nullptr, 10) == self_pid) continue;
    for (const std::string& tid : root.list("/proc/" + pid + "/task")) {
      count_task(root, "/proc/" + pid + "/task/" + tid, cpu, out);
    }
  }
  return out;
}

}  // namespace stepmod::doctor
