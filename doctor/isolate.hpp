#pragma once
// `stepmodctl isolate --cpu N` / `--off`: gives the pulse thread a CPU of its own at run time, as
// docs/performance.md ("A CPU of its own") and systemd/cpu-of-its-own/ describe: systemd drop-ins
// that keep every other slice and PID 1 off CPU N and put stepmodd in stepmod.slice, the sysctl
// that turns real-time throttling off, and `[rt] cpu = N` in the module's config (--config).
// Every file it writes says so in its first line; --off removes exactly those (and the [rt] cpu
// line it set). Idempotent. It does not reload systemd: it prints the commands.
#include <ostream>
#include <string>
#include <vector>

namespace stepmod::doctor {

struct IsolateOptions {
  int cpu = -1;        // --cpu N
  bool off = false;    // --off
  std::string config;  // a module's config to pin ([rt] cpu); "" = say what to set
  std::string root;    // write under this directory instead of / (tests)
};

struct IsolateFile {
  std::string path;  // absolute, as on the board
  std::string text;
};

// The first line of every file isolate writes.
inline constexpr const char* kIsolateMarker = "# Written by stepmodctl isolate";

// The files for CPU `cpu` of the online CPUs `online` (the others keep everything else).
std::vector<IsolateFile> isolation_files(int cpu, const std::vector<int>& online);
// The config text with `[rt] cpu = N` set (marked), or with isolate's own lines removed (cpu < 0).
std::string pin_in_config(const std::string& toml, int cpu);

// Exit status 0 done, 2 refused (no such CPU, a one-CPU board, a bad config) with the reason on
// `err`.
int run_isolate(const IsolateOptions& options, std::ostream& out, std::ostream& err);

}  // namespace stepmod::doctor
