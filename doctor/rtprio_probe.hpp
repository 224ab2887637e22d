#pragma once
// RLIMIT_RTPRIO of the service user: the highest SCHED_FIFO priority it may take without
// CAP_SYS_NICE. The stepmod user (the unit's User=) when it exists: a running stepmodd of that
// user's own limit (/proc/PID/limits), else the installed unit's LimitRTPRIO=; without that user,
// the caller's own limit.
#include <optional>
#include <string>
#include <string_view>

#include "doctor/sys_root.hpp"

namespace stepmod::doctor {

struct RtprioLimit {
  std::string user;    // "stepmod" or the caller ("uid 0")
  std::string source;  // where the value was read: "stepmodd pid 812", "unit file ...", ...
  std::optional<long> soft;  // nullopt: unread; "unlimited" is a large number
  bool root = false;         // the caller is root (CAP_SYS_NICE: any priority)
};

// The soft limit of "Max realtime priority" in a /proc/PID/limits text; nullopt if absent.
std::optional<long> parse_limits_rtprio(std::string_view limits);
// The uid of `user` in an /etc/passwd text.
std::optional<int> uid_in_passwd(std::string_view passwd, std::string_view user);
// The value of a "Key=value" line of a unit file ("LimitRTPRIO").
std::optional<std::string> unit_setting(std::string_view unit, std::string_view key);

// `self_pid`, `self_uid`: the caller's.
RtprioLimit probe_rtprio(const SysRoot& root, int self_pid, int self_uid);

}  // namespace stepmod::doctor
