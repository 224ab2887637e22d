#pragma once
// Runs the real stepmodd as a child process for end-to-end tests, on a config file written to a
// private temporary directory, with a unique module name so tests never share an image.
#include <sys/types.h>

#include <string>

namespace stepmod::testing {

// How a DaemonProcess starts stepmodd.
struct DaemonOptions {
  bool trace = true;  // run with --trace
  // The module name to use instead of a fresh unique one (a test of what a daemon finds left
  // behind by another of the same name).
  std::string name{};
  std::string trace_path{};  // the --trace file instead of one in the private directory
  // The stepmodd to run instead of this build's (the benchmarks' --stepmodd).
  std::string exe{};
};

class DaemonProcess {
 public:
  // `config_toml_with_name_placeholder`: the config file; "{NAME}" where the module name goes.
  DaemonProcess(const std::string& config_toml_with_name_placeholder, const DaemonOptions& options);
  explicit DaemonProcess(const std::string& config_toml_with_name_placeholder, bool trace = true,
                         const std::string& name = "", const std::string& trace_path = "")
      : DaemonProcess(config_toml_with_name_placeholder,
                      DaemonOptions{trace, name, trace_path, ""}) {}
  ~DaemonProcess();  // kills the daemon if still running and removes the temporary directory
  DaemonProcess(const DaemonProcess&) = delete;
  DaemonProcess& operator=(const DaemonProcess&) = delete;

  const std::string& name() const { return name_; }
  const std::string& trace_path() const { return trace_; }
  const std::string& config_path() const { return config_; }
  // Waits until the daemon is up: its shared-memory image names it as the owner and has been
  // scanned once. False on timeout or exit.
  bool wait_ready(int timeout_ms = 10'000);
  // SIGTERM and wait; returns the exit status (or -1 if it did not exit in time).
  int terminate(int timeout_ms = 10'000);
  // Sends `sig` to the daemon (SIGSTOP/SIGCONT: a stalled machine; SIGKILL: a crash).
  void signal(int sig);
  // Waits for the daemon to exit; its exit status, or -1 on timeout.
  int wait_exit(int timeout_ms = 10'000);
  pid_t pid() const { return pid_; }
  // The daemon's stderr so far (for failure messages).
  std::string log() const;

  // Runs stepmodd with `args` to completion; returns its exit status and stderr.
  static int run_to_exit(const std::string& args, std::string* stderr_text = nullptr);
  static std::string daemon_path();

 private:
  std::string dir_;
  std::string name_;
  std::string config_;
  std::string trace_;
  std::string log_;
  pid_t pid_ = -1;      // -1 once the daemon has been waited for
  pid_t spawned_ = -1;  // the daemon's pid, kept: the owner of the files it may leave
};

}  // namespace stepmod::testing
