#pragma once
// What the daemon benchmarks (bench/daemon_bench.cpp, bench/path_slip.cpp) share beyond the test
// support library: their command-line lookup and what they read from stepmodd's log.
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>

#include "core/clock.hpp"

namespace stepmod::bench {

// The value after `name` among the arguments after the subcommand (argv[1]), or `def`.
inline const char* arg(int argc, char** argv, const char* name, const char* def) {
  for (int i = 2; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], name) == 0) return argv[i + 1];
  }
  return def;
}

// The VCD's #0 as a CLOCK_MONOTONIC time (stepmodd logs it when it traces), or -1.
inline Nanos trace_origin(const std::string& log) {
  const std::string key = "#0 is CLOCK_MONOTONIC ";
  const auto at = log.find(key);
  return at == std::string::npos ? -1 : std::stoll(log.substr(at + key.size()));
}

// The daemon's own account of each late-edge fault (axis, step, speed, pause, lag).
inline void print_fault_lines(const std::string& log) {
  std::istringstream s(log);
  for (std::string line; std::getline(s, line);) {
    if (line.find("late-edge fault") != std::string::npos) std::printf("  %s\n", line.c_str());
  }
}

}  // namespace stepmod::bench
