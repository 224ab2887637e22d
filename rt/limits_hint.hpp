#pragma once
// What fixes a refused SCHED_FIFO or mlockall for the daemon's threads: the resource limits
// RLIMIT_RTPRIO and RLIMIT_MEMLOCK (or CAP_SYS_NICE / CAP_IPC_LOCK), which the package sets in
// two places: the unit (LimitRTPRIO=99, LimitMEMLOCK=infinity) and, for a daemon run by hand,
// /etc/security/limits.d/stepmod.conf for the group 'stepmod' (rtprio 95, memlock unlimited).
#include <cerrno>
#include <string>

namespace stepmod::rt {

// Appended to "SCHED_FIFO priority P refused (errno)": empty unless the refusal is a limit's.
inline std::string rtprio_fix(int err) {
  if (err != EPERM) return "";
  return "; the fix: run it as the service (systemctl start stepmodd@NAME: LimitRTPRIO=99), or "
         "by hand as a member of the group 'stepmod' (/etc/security/limits.d/stepmod.conf gives "
         "it rtprio 95: `sudo usermod -aG stepmod $USER`, log in again; `ulimit -r` shows it)";
}

// Appended to "mlockall refused (errno)".
inline std::string memlock_fix(int err) {
  if (err != EPERM && err != ENOMEM && err != EAGAIN) return "";
  return "; the fix: LimitMEMLOCK=infinity (the service has it) or the group 'stepmod''s memlock "
         "in /etc/security/limits.d/stepmod.conf (`ulimit -l` shows it)";
}

}  // namespace stepmod::rt
