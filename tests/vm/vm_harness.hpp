#pragma once
// What the VM's daemon cases share (tests/vm/daemon_vm_test.cpp for the 3601,
// tests/vm/modules_vm_test.cpp for the 3202 and 3602): reporting, the board's lines through the
// gpio-sim sysfs, stepmodd as a child process, sampling outputs, and reading the VCD against
// the samples. Header-only: each VM test program is one translation unit.
#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "ipc/client.hpp"
#include "tests/support/vcd_reader.hpp"

extern char** environ;

namespace stepmod::vmtest {

using std::chrono::milliseconds;
using stepmod::testing::Vcd;
using stepmod::testing::VcdChange;

// ---- reporting ------------------------------------------------------------------------------

struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct Skip : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline std::string fmt(const char* f, ...) __attribute__((format(printf, 1, 2)));
inline std::string fmt(const char* f, ...) {
  char buf[1024];
  va_list ap;
  va_start(ap, f);
  std::vsnprintf(buf, sizeof buf, f, ap);
  va_end(ap);
  return buf;
}
inline void info(const std::string& s) {
  std::printf("%s\n", s.c_str());
}
[[noreturn]] inline void fail(const std::string& s) {
  throw Failure(s);
}
inline void check(bool cond, const std::string& what) {
  if (!cond) fail(what);
}

// A daemon of this case logged a late-edge fault: the guest stalled its pulse thread beyond
// [rt] late_limit_us (1 s) and the daemon cut the motion, so what the case checks next (counts,
// end positions, the reaction to an input) was not the kernel path's doing. run_case() then
// asks scripts/vm/guest/init to run the case again (exit 75) instead of failing it.
inline std::string& guest_too_slow() {
  static std::string line;
  return line;
}
inline void note_late_fault(const std::string& log) {
  const auto p = log.find("late-edge fault");
  if (p == std::string::npos || !guest_too_slow().empty()) return;
  const auto b = log.rfind('\n', p);
  const auto e = log.find('\n', p);
  guest_too_slow() = log.substr(b == std::string::npos ? 0 : b + 1,
                                e == std::string::npos ? std::string::npos : e - b - 1);
}

inline std::int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}
inline void sleep_ms(int ms) {
  std::this_thread::sleep_for(milliseconds(ms));
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// ---- the board (environment of the VM case) -------------------------------------------------

inline std::string env(const char* name) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == '\0')
    fail(fmt("%s not set (run inside the test VM, . /vm/lib.sh)", name));
  return v;
}
// The [rt] lines of a case's config: the late-edge guard at its maximum. Under qemu (TCG) on a
// loaded host the guest stalls for hundreds of ms, and the cases are about the kernel path's
// levels, counts, order and timestamps, not about this machine's latency. (One emulated CPU: with
// two, gpio-sim's edge events came out of order and were lost even for 16 edges 1 ms apart.)
inline std::string rt_section(int priority = 80) {
  return "[rt]\npriority = " + std::to_string(priority) + "\nlate_limit_us = 1000000\n";
}
// The lag guard relaxed likewise, as the first key of an [[axis]] table: the VM cases judge the
// kernel path (levels, counts, order, timestamps), not an emulated CPU's timing.
inline std::string axis_guard() {
  return "lag_limit_steps = 1000000\n";
}
// Line offset of `key` of axis `axis` on the board: AX1_STEP, AX2_GPO, ...
inline unsigned line(const std::string& key, unsigned axis = 1) {
  std::string var = "AX" + std::to_string(axis) + "_";
  for (char c : key) var.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  return static_cast<unsigned>(std::stoul(env(var.c_str())));
}

// sim_gpioN/value and /pull of the gpio-sim chip.
class SimLine {
 public:
  explicit SimLine(unsigned offset) : offset_(offset) {
    const std::string dir = env("GPIO_SIM_DIR") + "/sim_gpio" + std::to_string(offset);
    value_fd_ = ::open((dir + "/value").c_str(), O_RDONLY | O_CLOEXEC);
    pull_fd_ = ::open((dir + "/pull").c_str(), O_WRONLY | O_CLOEXEC);
    if (value_fd_ < 0 || pull_fd_ < 0) fail("cannot open " + dir + "/{value,pull}");
  }
  ~SimLine() {
    ::close(value_fd_);
    ::close(pull_fd_);
  }
  SimLine(const SimLine&) = delete;
  SimLine& operator=(const SimLine&) = delete;
  int value() const {
    char c = 0;
    if (::pread(value_fd_, &c, 1, 0) != 1) fail(fmt("reading sim_gpio%u/value", offset_));
    return c == '1' ? 1 : 0;
  }
  void pull(bool up) const {
    const char* s = up ? "pull-up" : "pull-down";
    if (::pwrite(pull_fd_, s, std::strlen(s), 0) < 0) {
      fail(fmt("writing sim_gpio%u/pull: %s", offset_, std::strerror(errno)));
    }
  }
  unsigned offset() const { return offset_; }

 private:
  unsigned offset_;
  int value_fd_ = -1;
  int pull_fd_ = -1;
};

// ---- stepmodd as a child process ---------------------------------------------------------------

class Daemon {
 public:
  // stepmodd on the config file `config` of the module named `name`; its trace and log are
  // /tmp/<tag>.vcd and /tmp/<tag>.log.
  Daemon(const std::string& name, const std::string& config, const std::string& tag,
         bool trace = true)
      : name_(name), config_(config), trace_("/tmp/" + tag + ".vcd"), log_("/tmp/" + tag + ".log") {
    ::unlink(trace_.c_str());
    ::unlink(log_.c_str());
    remove_image();  // of a daemon killed by an earlier case
    std::vector<std::string> args{"stepmodd", "--config", config_};
    if (trace) {
      args.push_back("--trace");
      args.push_back(trace_);
    }
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, log_.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const int rc = posix_spawnp(&pid_, "stepmodd", &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) fail(fmt("cannot start stepmodd: %s", std::strerror(rc)));
    started_ = now_ns();
  }
  ~Daemon() {
    if (pid_ > 0) {
      // The case failed with the daemon still running (a check threw): its log says why (a
      // late-edge fault, a refused command, ...), so it goes into the case's output first.
      if (std::uncaught_exceptions() > 0) {
        signal(SIGTERM);
        wait_exit(5'000);
        info("the daemon's log (the case failed while it ran):");
        print_log();
      }
    }
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
      remove_image();  // a killed daemon cannot remove it
    }
  }
  void remove_image() const {
    ::unlink(("/dev/shm/stepmod." + name_).c_str());
    ::unlink(("/dev/shm/stepmod." + name_ + ".sim").c_str());
  }
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  // Waits for the image and the first scans; fails with the daemon's log if it exits.
  void wait_ready(int timeout_ms = 20'000) {
    const std::string shm = "/dev/shm/stepmod." + name_;
    const std::int64_t end = now_ns() + std::int64_t{timeout_ms} * 1'000'000;
    while (now_ns() < end) {
      struct stat s {};
      if (::stat(shm.c_str(), &s) == 0 && s.st_size == 4096) {
        try {
          stepmod::ipc::Client c(name_);
          if (c.wait_scans(3, milliseconds(5'000))) {
            info(fmt("stepmodd up after %lld ms",
                     static_cast<long long>((now_ns() - started_) / 1'000'000)));
            return;
          }
        } catch (const std::exception&) {
          // created but not yet published (magic written last): try again
        }
      }
      if (exited())
        fail(fmt("stepmodd exited with status %d before it was ready: %s", status_,
                 last_log_line().c_str()));
      sleep_ms(10);
    }
    fail("stepmodd not ready in time: " + last_log_line());
  }
  bool exited() {
    if (pid_ <= 0) return true;
    int s = 0;
    if (::waitpid(pid_, &s, WNOHANG) == pid_) {
      status_ = WIFEXITED(s) ? WEXITSTATUS(s) : 128 + WTERMSIG(s);
      pid_ = -1;
      exit_time_ = now_ns();
      return true;
    }
    return false;
  }
  // Waits for the exit (after a signal or on its own); the exit status, -1 on timeout.
  int wait_exit(int timeout_ms = 10'000) {
    const std::int64_t end = now_ns() + std::int64_t{timeout_ms} * 1'000'000;
    while (now_ns() < end) {
      if (exited()) return status_;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    return -1;
  }
  void signal(int sig) {
    if (pid_ > 0) ::kill(pid_, sig);
  }
  int terminate(int timeout_ms = 10'000) {
    signal(SIGTERM);
    return wait_exit(timeout_ms);
  }
  std::string log() const { return read_text(log_); }
  std::string last_log_line() const {
    std::string l = log();
    while (!l.empty() && l.back() == '\n') l.pop_back();
    const auto p = l.rfind('\n');
    return p == std::string::npos ? l : l.substr(p + 1);
  }
  void print_log() const {
    note_late_fault(log());
    std::istringstream in(log());
    for (std::string l; std::getline(in, l);) info("  stepmodd: " + l);
  }
  Vcd trace() const { return stepmod::testing::read_vcd(trace_); }
  // SIGTERM, the daemon's log into the case output, exit status 0 required, then its trace.
  Vcd stop_and_trace() {
    const int rc = terminate();
    print_log();
    check(rc == 0, fmt("stepmodd exit status %d", rc));
    return trace();
  }
  const std::string& name() const { return name_; }
  std::int64_t exit_time() const { return exit_time_; }

 private:
  std::string name_, config_, trace_, log_;
  pid_t pid_ = -1;
  int status_ = -1;
  std::int64_t started_ = 0;
  std::int64_t exit_time_ = 0;
};

// ---- sampling the outputs through sysfs
// ----------------------------------------------------------

struct Sample {
  std::int64_t t0, t1;  // CLOCK_MONOTONIC before and after reading the values
  std::uint8_t step, dir;
};

class Sampler {
 public:
  // Samples every `period_ns` (sleeping in between, so that it does not take the one emulated
  // CPU away from the daemon's threads); period 0: as fast as it can.
  Sampler(unsigned step, unsigned dir, std::int64_t period_ns = 100'000) : step_(step), dir_(dir) {
    samples_.reserve(2'000'000);
    th_ = std::thread([this, period_ns] {
      // Real-time, below the pulse thread (80): a woken sampler runs at once instead of waiting
      // for a time slice; it sleeps most of the time, so the daemon's other threads still run.
      sched_param sp{};
      sp.sched_priority = 10;
      pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
      while (!stop_.load(std::memory_order_relaxed) && samples_.size() < samples_.capacity()) {
        Sample s{};
        s.t0 = now_ns();
        s.step = static_cast<std::uint8_t>(step_.value());
        s.dir = static_cast<std::uint8_t>(dir_.value());
        s.t1 = now_ns();
        samples_.push_back(s);
        if (period_ns > 0) {
          const timespec ts{0, static_cast<long>(period_ns)};
          clock_nanosleep(CLOCK_MONOTONIC, 0, &ts, nullptr);
        }
      }
    });
  }
  ~Sampler() { stop(); }
  Sampler(const Sampler&) = delete;
  Sampler& operator=(const Sampler&) = delete;
  const std::vector<Sample>& stop() {
    stop_ = true;
    if (th_.joinable()) th_.join();
    return samples_;
  }

 private:
  SimLine step_, dir_;
  std::atomic<bool> stop_{false};
  std::vector<Sample> samples_;
  std::thread th_;
};

// ---- VCD helpers --------------------------------------------------------------------------------

// The changes of a wire after its initial value (the $dumpvars entry at #0, which read_vcd lists
// as the first change). stepmodd writes only real changes, so these alternate.
inline std::vector<VcdChange> wire(const Vcd& v, const std::string& name) {
  const auto it = v.wires.find(name);
  if (it == v.wires.end() || it->second.empty()) return {};
  return {it->second.begin() + 1, it->second.end()};
}
// Level of a wire at VCD time t (changes at exactly t count), given its initial level.
inline int level_at(const std::vector<VcdChange>& w, std::int64_t t, int initial = 0) {
  int l = initial;
  for (const VcdChange& c : w) {
    if (c.t > t) break;
    l = c.level;
  }
  return l;
}
// Number of rising edges of `steps` at or before t.
inline std::int64_t count_until(const std::vector<std::int64_t>& rising, std::int64_t t) {
  return std::upper_bound(rising.begin(), rising.end(), t) - rising.begin();
}

// The VCD's time 0 is the daemon's start (CLOCK_MONOTONIC). A pull change on an input is stamped
// by the kernel while the sysfs write runs: [before, after] of our clock brackets its VCD time,
// which gives the VCD's origin within that bracket.
struct Alignment {
  std::int64_t lo = 0, hi = 0;  // monotonic = vcd + offset, offset in [lo, hi]
};
struct PullMark {
  std::int64_t before, after;
  bool up;
};
inline PullMark pull_marked(const SimLine& l, bool up) {
  PullMark p{now_ns(), 0, up};
  l.pull(up);
  p.after = now_ns();
  return p;
}
// Several marks: the origin lies in every bracket, so in their intersection.
inline Alignment align_all(const Vcd& v, const std::string& wire_name,
                           const std::vector<PullMark>& marks) {
  const auto w = wire(v, wire_name);
  check(w.size() >= marks.size(),
        fmt("VCD: %s has %zu changes, drove %zu", wire_name.c_str(), w.size(), marks.size()));
  Alignment a{INT64_MIN, INT64_MAX};
  for (std::size_t i = 0; i < marks.size(); ++i) {
    check(w[i].level == (marks[i].up ? 1 : 0), "VCD: mark edges of the wrong polarity");
    a.lo = std::max(a.lo, marks[i].before - w[i].t);
    a.hi = std::min(a.hi, marks[i].after - w[i].t);
  }
  check(a.lo <= a.hi, fmt("VCD: the %zu mark edges' times are not all inside their sysfs writes "
                          "(not the kernel's timestamps?)",
                          marks.size()));
  return a;
}
inline Alignment align(const Vcd& v, const std::string& wire_name, const PullMark& p,
                       std::size_t index) {
  const auto w = wire(v, wire_name);
  check(index < w.size(), fmt("VCD: %s has %zu changes, no change #%zu to align with",
                              wire_name.c_str(), w.size(), index));
  check(w[index].level == (p.up ? 1 : 0), "VCD: alignment edge of the wrong polarity");
  return {p.before - w[index].t, p.after - w[index].t};
}

// Sampled levels against the VCD: every sample whose VCD-time window [t0, t1] (widened by the
// alignment uncertainty and `slack`) holds no change of the wire must show the VCD's level.
struct Agreement {
  std::size_t compared = 0, ambiguous = 0, mismatched = 0;
  std::string first_mismatch;
};
inline Agreement compare(const std::vector<Sample>& samples, const Vcd& v, const Alignment& a,
                         std::int64_t slack, bool dir, unsigned axis = 1) {
  const std::string ax = "axis" + std::to_string(axis);
  const auto w = wire(v, ax + (dir ? ".dir" : ".step"));
  Agreement r;
  std::size_t i = 0;  // first change after the window start
  for (const Sample& s : samples) {
    const std::int64_t from = s.t0 - a.hi - slack;
    const std::int64_t to = s.t1 - a.lo + slack;
    while (i < w.size() && w[i].t < from) ++i;
    if (i < w.size() && w[i].t <= to) {
      ++r.ambiguous;
      continue;
    }
    const int expect = i == 0 ? 0 : w[i - 1].level;
    const int got = dir ? s.dir : s.step;
    ++r.compared;
    if (got != expect) {
      if (r.mismatched++ == 0) {
        r.first_mismatch = fmt("sample at vcd %lld..%lld ns reads %d, VCD says %d",
                               static_cast<long long>(s.t0 - a.hi),
                               static_cast<long long>(s.t1 - a.lo), got, expect);
      }
    }
  }
  return r;
}

// VCD pulses the sampler cannot have missed: a sample lies wholly inside the pulse's high phase
// and another wholly inside the low phase before it (in monotonic time, given the alignment and
// `slack`). Each of them gives one sampled rising edge; pulses made shorter than the sampling
// interval (a late leading edge pulls the trailing one in) can be missed.
inline std::size_t observable_pulses(const std::vector<Sample>& samples, const Vcd& v,
                                     const Alignment& a, std::int64_t slack, unsigned axis = 1) {
  const auto w = wire(v, "axis" + std::to_string(axis) + ".step");
  // Is there a sample with [t0, t1] inside (from, to) (monotonic)?
  const auto inside = [&](std::int64_t from, std::int64_t to) {
    auto it = std::lower_bound(samples.begin(), samples.end(), from,
                               [](const Sample& x, std::int64_t t) { return x.t0 <= t; });
    for (; it != samples.end() && it->t0 < to; ++it) {
      if (it->t1 < to) return true;
    }
    return false;
  };
  std::size_t n = 0;
  std::int64_t prev_fall = INT64_MIN / 2;
  for (std::size_t i = 0; i + 1 < w.size(); ++i) {
    if (w[i].level != 1 || w[i + 1].level != 0) continue;
    const std::int64_t r = w[i].t, f = w[i + 1].t;
    const bool low = inside(prev_fall + a.hi + slack, r + a.lo - slack);
    const bool high = inside(r + a.hi + slack, f + a.lo - slack);
    if (low && high) ++n;
    prev_fall = f;
  }
  return n;
}

inline std::size_t sampled_rising(const std::vector<Sample>& samples) {
  std::size_t n = 0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if (samples[i - 1].step == 0 && samples[i].step == 1) ++n;
  }
  return n;
}

// Longest gap between consecutive samples (to know sampling could not miss a pulse).
inline std::int64_t max_sample_gap(const std::vector<Sample>& s, std::int64_t from,
                                   std::int64_t to) {
  std::int64_t g = 0;
  for (std::size_t i = 1; i < s.size(); ++i) {
    if (s[i].t0 < from || s[i - 1].t1 > to) continue;
    g = std::max(g, s[i].t1 - s[i - 1].t0);
  }
  return g;
}

// "pulse thread: N edges written, lateness p50 X ns, p99.9 Y ns, max Z ns" from the log.
inline std::string lateness_line(const std::string& log) {
  const auto p = log.find("lateness p50");
  if (p == std::string::npos) return "(no lateness line)";
  const auto e = log.find('\n', p);
  return log.substr(p, e == std::string::npos ? std::string::npos : e - p);
}
long long lateness_max_ns(const std::string& log) {
  const auto p = log.find("lateness p50");
  if (p == std::string::npos) return -1;
  const auto q = log.find("max ", p);
  if (q == std::string::npos) return -1;
  return std::atoll(log.c_str() + q + 4);
}

// A VM case program's main: runs the case named by the one argument and prints its last line
// as cases/README.md wants it: "ok: ..." (exit 0), "skip: ..." (77) or "FAIL: ..." (1); a
// usage error exits 2. A failure after a late-edge fault (guest_too_slow) exits 75: run again.
inline int run_case(int argc, char** argv, const char* program,
                    const std::map<std::string, std::string (*)()>& cases) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const auto it = argc == 2 ? cases.find(argv[1]) : cases.end();
  if (it == cases.end()) {
    std::string names;
    for (const auto& [name, run] : cases) names += (names.empty() ? "" : "|") + name;
    std::fprintf(stderr, "usage: %s %s\n", program, names.c_str());
    return 2;
  }
  try {
    std::printf("ok: %s\n", it->second().c_str());
    return 0;
  } catch (const Skip& e) {
    std::printf("skip: %s\n", e.what());
    return 77;
  } catch (const std::exception& e) {
    if (!guest_too_slow().empty()) {
      std::printf("too slow: %s; then: %s\n", guest_too_slow().c_str(), e.what());
      return 75;
    }
    std::printf("FAIL: %s\n", e.what());
    return 1;
  }
}

}  // namespace stepmod::vmtest
