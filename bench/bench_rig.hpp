#pragma once
// What the daemon benchmarks share (bench/daemon_bench.cpp, bench/path_slip.cpp): argument
// lookup, a stepmodd child process on a private configuration, the VCD's rising edges, a
// percentile.
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/clock.hpp"

namespace stepmod::bench {

inline const char* arg(int argc, char** argv, const char* name, const char* def) {
  for (int i = 2; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], name) == 0) return argv[i + 1];
  }
  return def;
}

inline std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// A stepmodd child process on a private config; SIGTERM on destruction.
class Daemon {
 public:
  // The configuration's text for the module name the daemon is given.
  using ConfigText = std::function<std::string(const std::string& name)>;

  // A 3601 on the simulated machine. `late_limit_us`: the late-edge guard's pause limit, with
  // the lag limit at its maximum; the default is the pause limit's maximum, so that a fault does
  // not end a measured move early (the guard has its own benchmarks: `guard`, `slip`); <= 0: the
  // product's defaults (no key written).
  Daemon(const std::string& exe, unsigned scan_us, bool trace, long late_limit_us = 1'000'000)
      : Daemon(exe, config_3601(scan_us, late_limit_us), trace) {}

  Daemon(const std::string& exe, const ConfigText& config, bool trace) {
    char tmpl[] = "/tmp/stepmod-bench-XXXXXX";
    dir_ = mkdtemp(tmpl);
    name_ = "bench" + std::to_string(getpid());
    config_ = dir_ + "/module.toml";
    log_ = dir_ + "/stepmodd.log";
    if (trace) trace_ = dir_ + "/trace.vcd";
    std::ofstream(config_) << config(name_);
    start(exe);
  }
  ~Daemon() {
    stop();
    std::error_code ignored;  // a bench leaves at worst a temp dir behind
    std::filesystem::remove_all(dir_, ignored);
  }
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  int stop() {
    if (pid_ <= 0) return 0;
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    return status;
  }
  pid_t pid() const { return pid_; }
  const std::string& name() const { return name_; }
  const std::string& trace() const { return trace_; }
  std::string log() const { return slurp(log_); }
  // The VCD's #0 as a CLOCK_MONOTONIC time (stepmodd logs it), or -1.
  Nanos trace_origin() const {
    const std::string l = log();
    const auto at = l.find("#0 is CLOCK_MONOTONIC ");
    return at == std::string::npos ? -1 : std::stoll(l.substr(at + 22));
  }

 private:
  static ConfigText config_3601(unsigned scan_us, long late_limit_us) {
    return [=](const std::string& name) {
      return "[module]\ntype = \"3601\"\nname = \"" + name +
             "\"\nscan_us = " + std::to_string(scan_us) +
             "\n[gpio]\nbackend = \"sim\"\n[rt]\npriority = 80\n" +
             (late_limit_us > 0 ? "late_limit_us = " + std::to_string(late_limit_us) + "\n"
                                : std::string()) +
             "[[axis]]\nstep = 1\ndir = 2\nhome = 3\ncw_limit = 4\nccw_limit = 5\n" +
             // With the pause limit raised, the lag limit too (its maximum).
             (late_limit_us > 0 ? "lag_limit_steps = 1000000\n" : "") +
             "[axis.sim]\ncw_limit_at = 100000000\nccw_limit_at = -100000000\n"
             "home_from = -200\nhome_to = -100\n";
    };
  }
  void start(const std::string& exe) {
    pid_ = fork();
    if (pid_ == 0) {
      if (std::freopen(log_.c_str(), "w", stderr) == nullptr) _exit(126);  // no log, no run
      std::vector<std::string> a{exe, "--config", config_};
      if (!trace_.empty()) {
        a.push_back("--trace");
        a.push_back(trace_);
      }
      std::vector<char*> av;
      for (auto& s : a) av.push_back(s.data());
      av.push_back(nullptr);
      execv(av[0], av.data());
      _exit(127);
    }
    const std::string shm = "/dev/shm/stepmod." + name_;
    for (int i = 0; i < 1000; ++i) {
      struct stat st {};
      if (stat(shm.c_str(), &st) == 0) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));  // let it start scanning
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    throw std::runtime_error("stepmodd did not start: " + slurp(log_));
  }

  std::string dir_, name_, config_, log_, trace_;
  pid_t pid_ = -1;
};

// Rising-edge times (ns from #0) of one VCD wire.
inline std::vector<Nanos> vcd_rising(const std::string& path, const std::string& wire) {
  std::ifstream f(path);
  std::string line, id;
  Nanos t = 0;
  int level = 0;
  std::vector<Nanos> out;
  while (std::getline(f, line)) {
    if (line.rfind("$var", 0) == 0) {
      std::istringstream s(line);
      std::string var, type, width, ident, name;
      s >> var >> type >> width >> ident >> name;
      if (name == wire) id = ident;
    } else if (!line.empty() && line[0] == '#') {
      t = std::stoll(line.substr(1));
    } else if (!id.empty() && line.size() >= 2 && (line[0] == '0' || line[0] == '1') &&
               line.substr(1) == id) {
      const int l = line[0] - '0';
      if (l == 1 && level == 0) out.push_back(t);
      level = l;
    }
  }
  return out;
}

// The daemon's own account of each late-edge fault (axis, step, speed, pause, lag).
inline void print_fault_lines(const std::string& log) {
  std::istringstream s(log);
  for (std::string line; std::getline(s, line);) {
    if (line.find("late-edge fault") != std::string::npos) std::printf("  %s\n", line.c_str());
  }
}

inline double pct(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size()))) - 1;
  return v[std::min(i, v.size() - 1)];
}

}  // namespace stepmod::bench
