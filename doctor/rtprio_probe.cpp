#include "doctor/rtprio_probe.hpp"

#include <cstdlib>
#include <sstream>

#include "doctor/tenants_probe.hpp"

namespace stepmod::doctor {

namespace {

constexpr long kUnlimited = 1L << 30;
constexpr const char* kServiceUser = "stepmod";
constexpr const char* kUnitDirs[] = {"/etc/systemd/system", "/usr/local/lib/systemd/system",
                                     "/lib/systemd/system", "/usr/lib/systemd/system"};

std::optional<long> limit_value(const std::string& word) {
  if (word == "unlimited") return kUnlimited;
  char* end = nullptr;
  const long v = std::strtol(word.c_str(), &end, 10);
  if (end == word.c_str() || *end != '\0') return std::nullopt;
  return v;
}

// A running stepmodd of `uid`: its pid, or "".
std::string stepmodd_of(const SysRoot& root, int uid) {
  for (const std::string& pid : root.list("/proc")) {
    const auto status = root.read("/proc/" + pid + "/status");
    if (!status) continue;
    const auto name = status_field(*status, "Name");
    const auto uids = status_field(*status, "Uid");
    if (name && *name == "stepmodd" && uids && std::strtol(uids->c_str(), nullptr, 10) == uid) {
      return pid;
    }
  }
  return "";
}

void read_service_user(const SysRoot& root, int uid, RtprioLimit& out) {
  out.user = kServiceUser;
  if (const std::string pid = stepmodd_of(root, uid); !pid.empty()) {
    out.source = "stepmodd pid " + pid;
    if (const auto l = root.read("/proc/" + pid + "/limits")) out.soft = parse_limits_rtprio(*l);
    return;
  }
  for (const char* dir : kUnitDirs) {
    const std::string unit = std::string(dir) + "/stepmodd@.service";
    const auto text = root.read(unit);
    if (!text) continue;
    out.source = unit;
    if (const auto v = unit_setting(*text, "LimitRTPRIO")) out.soft = limit_value(*v);
    return;
  }
  out.source = "no stepmodd running and no unit installed";
}

}  // namespace

std::optional<long> parse_limits_rtprio(std::string_view limits) {
  std::istringstream in{std::string(limits)};
  std::string line;
  const std::string key = "Max realtime priority";
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) != 0) continue;
    std::istringstream fields(line.substr(key.size()));
    std::string soft;
    fields >> soft;
    return limit_value(soft);
  }
  return std::nullopt;
}

std::optional<int> uid_in_passwd(std::string_view passwd, std::string_view user) {
  std::istringstream in{std::string(passwd)};
  std::string line;
  while (std::getline(in, line)) {
    // name:password:uid:...
    const auto a = line.find(':');
    if (a == std::string::npos || line.compare(0, a, user) != 0 || a != user.size()) continue;
    const auto b = line.find(':', a + 1);
    if (b == std::string::npos) return std::nullopt;
    return static_cast<int>(std::strtol(line.c_str() + b + 1, nullptr, 10));
  }
  return std::nullopt;
}

std::optional<std::string> unit_setting(std::string_view unit, std::string_view key) {
  std::istringstream in{std::string(unit)};
  std::string line;
  std::optional<std::string> value;  // the last one counts, as for systemd
  while (std::getline(in, line)) {
    if (line.size() > key.size() && line.compare(0, key.size(), key) == 0 &&
        line[key.size()] == '=') {
      value = line.substr(key.size() + 1);
    }
  }
  return value;
}

RtprioLimit probe_rtprio(const SysRoot& root, int self_pid, int self_uid) {
  RtprioLimit out;
  out.root = self_uid == 0;
  const auto passwd = root.read("/etc/passwd");
  if (const auto uid = passwd ? uid_in_passwd(*passwd, kServiceUser) : std::nullopt) {
    read_service_user(root, *uid, out);
    return out;
  }
  out.user = "uid " + std::to_string(self_uid) + " (no user '" + kServiceUser + "')";
  out.source = "this process";
  if (const auto l = root.read("/proc/" + std::to_string(self_pid) + "/limits")) {
    out.soft = parse_limits_rtprio(*l);
  }
  return out;
}

}  // namespace stepmod::doctor
