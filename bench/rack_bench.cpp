// Issue 31's benchmark: eight axes (four 3601s and two 3602s on the simulated machine) each
// moving --steps at --rate, started together, served either by one stepmodd as a rack (one pulse
// thread, one planner thread) or by six stepmodds (one per module, six pulse threads at the same
// SCHED_FIFO priority), with the product's default late-edge guard. scripts/bench runs both,
// unloaded and beside `stress-ng --cpu 1`, in one run.
//
//   rack_bench rack|daemons --stepmodd PATH [--steps 20000] [--rate 20000] [--runs 3]
//
// Reported over the runs: completed moves (every planned step on the wire, no late-edge fault),
// late-edge faults (the modules' health words), compressed intervals (a step interval shorter
// than 0.9 x its planned one - 2 us, judged from the VCD against the planner's own plan; must be
// 0), the worst pause (an interval's excess over its plan) and the daemons' CPU during the moves.
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <latch>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench/daemon_log.hpp"
#include "bench/path_plan.hpp"
#include "bench/proc_cpu.hpp"
#include "bench/slip_judge.hpp"
#include "ipc/client.hpp"
#include "module_types/m3601/plc_3601.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "module_types/m3602/plc_3602.hpp"
#include "module_types/m3602/words_3602.hpp"
#include "plc/shm_port.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/sim_config.hpp"
#include "tests/support/vcd_reader.hpp"

namespace {

using namespace stepmod;
using namespace stepmod::bench;
namespace fs = std::filesystem;
using std::chrono::milliseconds;

constexpr std::int32_t kStartSpeed = 1'000;
constexpr plc::Sequencing kSeq{.hold_scans = 3, .release_scans = 2, .config_scans = 3};

struct ModuleSpec {
  std::string name;  // unique per bench process
  bool is_3602;
  unsigned axes() const { return is_3602 ? 2u : 1u; }
};

// The module file: the product's defaults but for the simulated machine and SCHED_FIFO 80 (no
// late_limit_us, no lag_limit_steps: the default guard). `own_rt`: a daemon of its own has an
// [rt] table; a rack's module file must not (the rack file has it).
std::string module_text(const ModuleSpec& m, bool own_rt) {
  const std::string far = "cw_limit_at = 100000000\nccw_limit_at = -100000000\n";
  std::string text = "[module]\ntype = \"" + std::string(m.is_3602 ? "3602" : "3601") +
                     "\"\nname = \"" + m.name + "\"\nscan_us = 1000\n\n[gpio]\nbackend = \"sim\"\n";
  if (own_rt) text += "\n[rt]\npriority = 80\n";
  if (m.is_3602) {
    for (const unsigned first : {1u, 11u}) {
      text += testing::sim_axis(
          testing::numbered_lines(first, {"step", "dir", "cw_limit", "ccw_limit"}), far, "");
    }
  } else {
    text += testing::sim_axis(
        testing::numbered_lines(1, {"step", "dir", "home", "cw_limit", "ccw_limit"}),
        far + "home_from = -200\nhome_to = -100\n", "");
  }
  return text;
}

// The module files in a private directory, and the daemons serving them.
class Bench {
 public:
  Bench(const std::string& exe, bool rack) {
    std::string tmpl = (fs::temp_directory_path() / "stepmod-rack-bench-XXXXXX").string();
    if (::mkdtemp(tmpl.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    dir_ = tmpl;
    const std::string prefix = "rb" + std::to_string(::getpid()) + "-";
    for (const char* n : {"m1", "m2", "m3", "m4"}) modules_.push_back({prefix + n, false});
    for (const char* n : {"p1", "p2"}) modules_.push_back({prefix + n, true});
    rack ? start_rack(exe) : start_daemons(exe);
  }
  ~Bench() {
    daemons_.clear();
    fs::remove_all(dir_);
  }
  Bench(const Bench&) = delete;
  Bench& operator=(const Bench&) = delete;

  const std::vector<ModuleSpec>& modules() const { return modules_; }
  double cpu_ns() const {
    double ns = 0;
    for (const auto& d : daemons_) ns += total(thread_cpu(d->pid()));
    return ns;
  }
  // Stops every daemon (their traces complete) and returns each axis' rising step edges, in
  // module order.
  std::vector<std::vector<Nanos>> stop_and_read_steps() {
    std::vector<std::vector<Nanos>> steps;
    for (auto& d : daemons_) {
      if (d->terminate(60'000) != 0) std::fprintf(stderr, "%s\n", d->log().c_str());
    }
    const bool rack = daemons_.size() == 1;
    for (std::size_t i = 0; i < modules_.size(); ++i) {
      const testing::Vcd vcd = testing::read_vcd(daemons_[rack ? 0 : i]->trace_path());
      for (unsigned a = 1; a <= modules_[i].axes(); ++a) {
        const std::string wire = "axis" + std::to_string(a) + ".step";
        steps.push_back(vcd.rising(rack ? modules_[i].name + "." + wire : wire));
      }
    }
    return steps;
  }
  std::string logs() const {
    std::string out;
    for (const auto& d : daemons_) out += d->log();
    return out;
  }

 private:
  void start_rack(const std::string& exe) {
    std::string list;
    for (const ModuleSpec& m : modules_) {
      const fs::path file = dir_ / (m.name + ".toml");
      std::ofstream(file) << module_text(m, false);
      list += (list.empty() ? "\"" : ", \"") + file.string() + "\"";
    }
    const std::string rack = "[rack]\nmodules = [" + list + "]\n\n[rt]\npriority = 80\n";
    start(rack, modules_.front().name, exe);
  }
  void start_daemons(const std::string& exe) {
    for (const ModuleSpec& m : modules_) start(module_text(m, true), m.name, exe);
  }
  void start(const std::string& text, const std::string& name, const std::string& exe) {
    daemons_.push_back(std::make_unique<testing::DaemonProcess>(
        text, testing::DaemonOptions{.trace = true, .name = name, .exe = exe}));
    if (!daemons_.back()->wait_ready(20'000)) {
      throw std::runtime_error("stepmodd did not start: " + daemons_.back()->log());
    }
  }

  fs::path dir_;
  std::vector<ModuleSpec> modules_;
  std::vector<std::unique_ptr<testing::DaemonProcess>> daemons_;
};

// One module's PLC over its shared-memory image: configures its axes, then moves each by `steps`
// when told to, and waits for them to rest.
class ModulePlc {
 public:
  explicit ModulePlc(const ModuleSpec& m)
      : spec_(m), client_(m.name), port_(client_, milliseconds(2000)) {
    if (!client_.wait_scans(2, milliseconds(5000))) throw std::runtime_error(m.name + " idle");
    if (m.is_3602) {
      p3602_ = std::make_unique<plc::Plc3602>(port_, milliseconds(2000), kSeq);
    } else {
      p3601_ = std::make_unique<plc::Plc3601>(port_, milliseconds(2000), kSeq);
    }
  }
  void configure() {
    namespace c1 = words::m3601::cfg_msw;
    namespace c2 = words::m3602::cfg_msw;
    constexpr std::uint16_t kCfg3601 =
        c1::kHomeUsed | c1::kCwLimitUsed | c1::kCcwLimitUsed | c1::kStepDirOutput;
    constexpr std::uint16_t kCfg3602 = (c2::kFunctionLimit << c2::kCwFunctionShift) |
                                       (c2::kFunctionLimit << c2::kCcwFunctionShift) |
                                       c2::kStepDirOutput;
    plc::Outcome o;
    for (unsigned a = 0; a < spec_.axes() && (a == 0 || o.ok); ++a) {
      o = p3602_ ? p3602_->configure(a, kCfg3602, 0x1F, kStartSpeed)
                 : p3601_->configure(kCfg3601, 0x3F, kStartSpeed);
    }
    if (!o.ok) throw std::runtime_error(spec_.name + " config: " + o.message);
  }
  void move(std::int32_t steps, const plc::Profile& p) {
    for (unsigned a = 0; a < spec_.axes(); ++a) {
      const plc::Outcome o =
          p3602_ ? p3602_->move(a, false, steps, p) : p3601_->move(false, steps, p);
      if (o.timed_out) throw std::runtime_error(spec_.name + " not scanning");
    }
  }
  void wait_idle(std::chrono::seconds limit) {
    for (unsigned a = 0; a < spec_.axes(); ++a) {
      if (p3602_) p3602_->wait_idle(a, limit);
      if (p3601_) p3601_->wait_idle(limit);
    }
  }
  std::uint32_t late_faults() const { return client_.read_health().late_faults; }
  std::uint32_t worst_late_us() const { return client_.read_health().worst_late_us; }

 private:
  ModuleSpec spec_;
  ipc::Client client_;
  plc::ShmPort port_;
  std::unique_ptr<plc::Plc3601> p3601_;
  std::unique_ptr<plc::Plc3602> p3602_;
};

struct Totals {
  int moves = 0;
  int completed = 0;
  std::uint32_t faults = 0;
  std::uint32_t worst_late_us = 0;
  std::size_t compressed = 0;
  Nanos worst_pause = 0;
  double cpu_ns = 0;
  double wall_ns = 0;
};

// Runs `fn` on every PLC at once, each in a thread of its own, released together.
void on_every_module(std::vector<std::unique_ptr<ModulePlc>>& plcs,
                     const std::function<void(ModulePlc&)>& fn) {
  std::latch go(static_cast<std::ptrdiff_t>(plcs.size()));
  std::vector<std::thread> threads;
  for (auto& p : plcs) {
    threads.emplace_back([&go, &fn, &p] {
      go.arrive_and_wait();
      fn(*p);
    });
  }
  for (auto& t : threads) t.join();
}

planner::MoveSpec move_spec(std::int32_t steps, int rate, std::int32_t accel_word) {
  planner::MoveSpec s;
  s.steps = steps;
  s.vs = kStartSpeed;
  s.vp = rate;
  s.accel =
      planner::Ramp{static_cast<double>(accel_word) * 1'000.0, planner::AccelShape::kConstant};
  s.decel = s.accel;
  return s;
}

// Judges each axis' moves (split where its line rested) against the plan.
void judge(const std::vector<std::vector<Nanos>>& axes, const std::vector<Nanos>& plan,
           std::int32_t steps, Totals& t) {
  for (const std::vector<Nanos>& rising : axes) {
    for (const auto& wire : split_moves(rising, 300 * kNsPerMs)) {
      const bool full = wire.size() == static_cast<std::size_t>(steps);
      const SlipVerdict v = judge_move(wire, plan, kStartSpeed, !full);
      t.compressed += v.compressed;
      t.worst_pause = std::max(t.worst_pause, v.worst_pause);
      t.completed += full ? 1 : 0;
    }
  }
}

int run(int argc, char** argv) {
  const std::string exe = arg(argc, argv, "--stepmodd", "build/bench/daemon/stepmodd");
  const std::string mode = argc > 1 ? argv[1] : "";
  const auto steps = static_cast<std::int32_t>(std::atoi(arg(argc, argv, "--steps", "20000")));
  const int rate = std::atoi(arg(argc, argv, "--rate", "20000"));
  const int runs = std::atoi(arg(argc, argv, "--runs", "3"));
  if (mode != "rack" && mode != "daemons") {
    std::fprintf(stderr,
                 "usage: rack_bench rack|daemons --stepmodd PATH [--steps N] [--rate "
                 "STEPS_PER_S] [--runs N]\n");
    return 2;
  }
  const auto accel = static_cast<std::int32_t>(std::max(1, rate / 500));  // ~0.5 s ramps
  const plc::Profile profile{.speed = rate, .accel = accel, .decel = accel};
  Totals t;
  Bench bench(exe, mode == "rack");
  std::vector<std::unique_ptr<ModulePlc>> plcs;
  for (const ModuleSpec& m : bench.modules()) plcs.push_back(std::make_unique<ModulePlc>(m));
  on_every_module(plcs, [](ModulePlc& p) { p.configure(); });
  std::uint32_t faults_before = 0;
  for (const auto& p : plcs) faults_before += p->late_faults();
  for (int r = 0; r < runs; ++r) {
    const std::int32_t dir_steps = r % 2 == 0 ? steps : -steps;
    const double cpu0 = bench.cpu_ns();
    const Nanos t0 = monotonic_now();
    on_every_module(plcs, [&](ModulePlc& p) {
      p.move(dir_steps, profile);
      p.wait_idle(std::chrono::seconds(60 + 5 * steps / rate));
    });
    t.wall_ns += static_cast<double>(monotonic_now() - t0);
    t.cpu_ns += bench.cpu_ns() - cpu0;
    std::this_thread::sleep_for(milliseconds(500));  // a rest the VCD is split at
  }
  for (const auto& p : plcs) {
    t.faults += p->late_faults();
    t.worst_late_us = std::max(t.worst_late_us, p->worst_late_us());
  }
  t.faults -= faults_before;
  plcs.clear();
  const std::vector<std::vector<Nanos>> axes = bench.stop_and_read_steps();
  t.moves = static_cast<int>(axes.size()) * runs;
  judge(axes, plan_move(move_spec(steps, rate, accel)), steps, t);
  print_fault_lines(bench.logs());
  std::printf(
      "rack_bench %s: %d moves of %d steps at %d steps/s: %d completed, %u late-edge faults "
      "(worst %u us), %zu compressed intervals, worst pause %.1f us, CPU %.2f s (%.0f%% of one "
      "CPU over the moves)\n",
      mode.c_str(), t.moves, steps, rate, t.completed, t.faults, t.worst_late_us, t.compressed,
      static_cast<double>(t.worst_pause) / 1e3, t.cpu_ns / 1e9, 100.0 * t.cpu_ns / t.wall_ns);
  std::printf(
      "RESULT bench=rack mode=%s moves=%d completed=%d faults=%u compressed=%zu "
      "worst_pause_us=%.1f cpu_s=%.3f cpu_pct=%.1f\n",
      mode.c_str(), t.moves, t.completed, t.faults, t.compressed,
      static_cast<double>(t.worst_pause) / 1e3, t.cpu_ns / 1e9, 100.0 * t.cpu_ns / t.wall_ns);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  signal(SIGPIPE, SIG_IGN);
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rack_bench: %s\n", e.what());
    return 1;
  }
}
