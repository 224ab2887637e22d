#pragma once
// A real stepmodd on the simulated 3601 (examples/3601-sim.toml) with stepmodctl beside it, for
// the commissioning-lease tests (tests/integration/lease_deadman_test.cpp,
// tests/web/web_lease_test.cpp). Header-only: the test's target defines STEPMODCTL_PATH and
// STEPMOD_SOURCE_DIR (as for tests/support/ctl_run.hpp).
#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "ipc/client.hpp"
#include "tests/support/ctl_run.hpp"
#include "tests/support/daemon_process.hpp"

namespace stepmod::testing {

using Clock = std::chrono::steady_clock;

// examples/3601-sim.toml with the harness' name, a late-edge limit for a loaded machine and
// optionally a PLC heartbeat timeout.
inline std::string lease_test_config(int plc_timeout_ms) {
  std::string t = slurp_file(std::string(STEPMOD_SOURCE_DIR) + "/examples/3601-sim.toml");
  const auto line = [&t](const std::string& from, const std::string& to) {
    const auto at = t.find(from);
    if (at != std::string::npos) t.replace(at, t.find('\n', at) - at, to);
  };
  line("name = \"stepmod\"", "name = \"{NAME}\"");
  line("[rt]", "[rt]\nlate_limit_us = 1000000");
  line("lag_limit_steps = ", "lag_limit_steps = 1000000");  // not about timing
  if (plc_timeout_ms > 0) {
    line("scan_us = 1000", "scan_us = 1000\nplc_timeout_ms = " + std::to_string(plc_timeout_ms));
  }
  return t;
}

// Polls `f` every 5 ms until true or `limit`; the last answer.
inline bool eventually(const std::function<bool()>& f, std::chrono::milliseconds limit) {
  const auto end = Clock::now() + limit;
  while (Clock::now() < end) {
    if (f()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return f();
}

class CommissioningDaemon {
 public:
  explicit CommissioningDaemon(int plc_timeout_ms = 0)
      : daemon_(std::make_unique<DaemonProcess>(lease_test_config(plc_timeout_ms), false)) {}
  bool ready() { return daemon_->wait_ready(); }
  const std::string& name() const { return daemon_->name(); }
  std::string log() const { return daemon_->log(); }

  CtlRun ctl(const std::string& args) const { return stepmodctl("-n " + name() + " " + args); }
  // stepmodctl in the background, output discarded; killed if this process dies.
  pid_t ctl_background(const std::string& args) const {
    const std::string cmd = std::string("exec ") + STEPMODCTL_PATH + " -n " + name() + " " + args;
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid == 0) {
      if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || ::getppid() != parent) ::_exit(127);
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, 1);
      ::dup2(null, 2);
      ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    return pid;
  }
  // The module's state column says so (stepmodctl status --brief).
  bool moving() const { return ctl("status --brief").out.find(": moving") != std::string::npos; }
  std::int64_t position() const {
    const CtlRun r = ctl("status --json");
    const auto at = r.out.find("\"position\":");
    return at == std::string::npos ? -1 : std::stoll(r.out.substr(at + 11));
  }
  ipc::Client client() const { return ipc::Client(name()); }
  std::uint32_t health() const { return client().read_health().flags; }
  std::uint32_t holder() const {
    return __atomic_load_n(&client().raw().lease_holder, __ATOMIC_ACQUIRE);
  }
  // Milliseconds until the axis no longer moves, polled; -1 if it still moves after `limit`.
  long long ms_until_stopped(std::chrono::milliseconds limit) const {
    const auto from = Clock::now();
    if (!eventually([&] { return !moving(); }, limit)) return -1;
    return std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - from).count();
  }

 private:
  std::unique_ptr<DaemonProcess> daemon_;
};

// Waits up to `limit` for a background process to exit by itself; its exit status, or -1 if it
// still runs (then it is the caller's to kill).
inline int reap_within(pid_t pid, std::chrono::milliseconds limit) {
  const auto end = Clock::now() + limit;
  do {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  } while (Clock::now() < end);
  return -1;
}

// Kills and reaps a background process; its exit status (128 + signal if killed).
inline int kill_and_reap(pid_t pid, int sig = SIGKILL) {
  ::kill(pid, sig);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace stepmod::testing
