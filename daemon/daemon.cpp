#include "daemon/daemon.hpp"

#include <spdlog/spdlog.h>

#include <exception>
#include <thread>

#include "daemon/backend_factory.hpp"
#include "daemon/daemon_log.hpp"
#include "daemon/daemon_trace.hpp"
#include "daemon/enip_adapters.hpp"
#include "daemon/modbus_servers.hpp"
#include "daemon/module_runtime.hpp"
#include "daemon/realtime_setup.hpp"
#include "daemon/stack.hpp"
#include "doctor/startup_notice.hpp"
#include "planner/planner_thread.hpp"
#include "systemd/notify.hpp"

namespace stepmod::tools {

namespace {
// A failure while building module `m`, said with its name (the rack starts whole or not at all).
[[noreturn]] void module_failed(const Config& m, const std::exception& e) {
  throw std::runtime_error("module '" + m.name + "' (" + m.file + "): " + e.what());
}
}  // namespace

// Declared in the order they are built; destroyed in reverse (the modules' control loops before
// what they work on, the stack before the trace rings its step output writes and the planners'
// wake counter, the backends last).
struct Daemon::Impl {
  RackConfig rack;
  Nanos start = monotonic_now();               // the VCD's #0
  std::vector<BuiltBackend> io;                // per module
  std::unique_ptr<DaemonTrace> trace;          // --trace
  std::atomic<std::uint32_t> planner_wake{0};  // the planners' shared wake counter
  std::unique_ptr<Stack> stack;
  std::vector<std::unique_ptr<ModuleRuntime>> modules;
  std::vector<std::unique_ptr<ipc::ModbusServer>> modbus;  // after the images they map
  std::vector<std::unique_ptr<enip::Adapter>> enip;        // the same

  const Config& first() const { return rack.modules.front(); }
  void build_backends();
  void build_stack();
  void build_modules();
  void log_start() const;
  void run_control_threads(const std::atomic<bool>& stop);
  void stop_threads(planner::PlannerThread& planner);
  void log_thread_stats(const planner::PlannerThread& planner) const;
};

Daemon::Daemon(const RackConfig& rack, const std::optional<std::string>& trace_path)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.rack = rack;
  d.build_backends();
  if (trace_path) d.trace = std::make_unique<DaemonTrace>();
  d.build_stack();
  d.build_modules();
  d.modbus = start_modbus_servers(d.rack.modules);
  d.enip = start_enip_adapters(d.modules);
  if (trace_path) d.trace->open(*trace_path, d.start, d.rack.modules, d.rack.rack_file, *d.stack);
}

Daemon::~Daemon() = default;

void Daemon::Impl::build_backends() {
  for (const Config& m : rack.modules) {
    try {
      io.push_back(make_backend(m));
    } catch (const std::exception& e) {
      module_failed(m, e);
    }
    // Outputs start idle, as they will end.
    io.back().backend->idle_outputs();
  }
}

void Daemon::Impl::build_stack() {
  std::vector<StackModule> parts;
  for (std::size_t k = 0; k < rack.modules.size(); ++k) {
    const Config& m = rack.modules[k];
    StackOptions so;
    so.type = m.type;
    for (const AxisSection& a : m.axes) {
      so.timing.push_back({a.step_pulse_ns, a.dir_setup_ns});
      so.lag_limit_steps.push_back(a.lag_limit_steps);
    }
    // A new motion's time 0 is this long after the planner takes its command. The pulse thread,
    // rung when the command is submitted (PulseDoorbell), polls every max_sleep_ns (50 us) and
    // wakes ~15-20 us late: 100 us covers it and is 50 us off the command latency (issue 5).
    so.planner.start_delay_ns = 100 * kNsPerUs;
    // One planner thread serves every module's planner (planner/planner_thread.hpp).
    so.planner.wake_counter = &planner_wake;
    so.planner.group_domain = static_cast<std::uint8_t>(k);
    so.late_limit_ns = m.late_limit_ns;
    parts.push_back({so, io[k].backend.get()});
  }
  stack = std::make_unique<Stack>(parts, trace ? trace->output_ring() : nullptr);
}

// Each module's image, panel, Modbus server and control loop.
void Daemon::Impl::build_modules() {
  for (unsigned k = 0; k < rack.modules.size(); ++k) {
    const Config& m = rack.modules[k];
    try {
      modules.push_back(std::make_unique<ModuleRuntime>(ModuleRuntime::Parts{
          m, stack->module(k), stack->output(), io[k].sim, trace.get(), stack->first_axis(k)}));
    } catch (const std::exception& e) {
      module_failed(m, e);
    }
  }
}

// The wiring of the threads: trace, pulse, planner, then the modules' control threads (this one
// the first's) until `stop`; then the orderly shutdown in the reverse order.
bool Daemon::run(const std::atomic<bool>& stop) {
  Impl& d = *impl_;
  const rt::StepOutput::Options po = pulse_options(d.first());
  rt::StepOutput& pulse = d.stack->output();
  if (d.trace) d.trace->start_thread();
  if (!pulse.start(po)) throw std::runtime_error("cannot start the pulse thread");
  warn_pulse_setup(po, pulse.status());
  std::vector<planner::Planner*> planners;
  for (unsigned k = 0; k < d.stack->modules(); ++k)
    planners.push_back(&d.stack->module(k).planner());
  planner::PlannerThread planner(planners);
  planner.start();
  raise_planner_thread(planner, po.priority);
  d.log_start();
  systemd::notify_ready("running");
  std::exception_ptr failure;
  try {
    d.run_control_threads(stop);
  } catch (...) {
    failure = std::current_exception();  // stopped like a signal's stop, then reported
  }
  systemd::notify_stopping();
  d.stop_threads(planner);
  d.log_thread_stats(planner);
  const bool trace_complete = d.trace ? d.trace->finish() : true;
  for (const BuiltBackend& b : d.io) {
    if (b.backend->lost_events() > 0) {
      spdlog::warn("{} input events were lost in all", b.backend->lost_events());
    }
  }
  if (failure) std::rethrow_exception(failure);
  return trace_complete;
}

void Daemon::Impl::log_start() const {
  for (std::size_t k = 0; k < rack.modules.size(); ++k) {
    const Config& m = rack.modules[k];
    spdlog::info("module {} '{}' running: /dev/shm/stepmod.{}, {} backend, scan {} us",
                 static_cast<unsigned>(m.type), m.name, m.name,
                 io[k].sim != nullptr ? "sim" : "gpiod", m.scan_ns / kNsPerUs);
  }
  if (rack.rack_file) {
    spdlog::info("rack {}: {} modules, one pulse thread and one planner thread", rack.file,
                 rack.modules.size());
  }
  // The VCD's times are relative to this instant; an outside tool (bench/daemon_bench) needs it
  // to compare trace times with its own CLOCK_MONOTONIC readings.
  if (trace) spdlog::info("trace: #0 is CLOCK_MONOTONIC {} ns", start);
  // Whether the pulse CPU is shared, throttled or without PREEMPT_RT (the doctor's probes:
  // stepmodctl doctor measures what that costs).
  if (auto n = doctor::pulse_cpu_notice(first().rt_cpu); !n.empty()) spdlog::info("{}", n);
}

// A control thread per module, this thread the first's, until `stop`. A module's loop that
// fails halts the others; the first failure is rethrown once all have ended.
void Daemon::Impl::run_control_threads(const std::atomic<bool>& stop) {
  std::atomic<bool> halt{false};
  std::vector<std::exception_ptr> failures(modules.size());
  const auto control = [&](unsigned k) {
    try {
      // In a rack every line a module's thread logs names the module.
      if (rack.rack_file) set_log_scope("[" + rack.modules[k].name + "] ");
      if (io[k].sim == nullptr) raise_control_thread(rack.modules[k].rt_priority);
      modules[k]->control().run(stop, &halt);
    } catch (...) {
      failures[k] = std::current_exception();
    }
    halt.store(true, std::memory_order_release);
  };
  std::vector<std::thread> others;
  for (unsigned k = 1; k < modules.size(); ++k) {
    others.emplace_back(control, k);
    pthread_setname_np(others.back().native_handle(), "stepmod-ctl");
  }
  control(0);
  set_log_scope("");
  for (std::thread& t : others) t.join();
  for (const std::exception_ptr& f : failures) {
    if (f) std::rethrow_exception(f);
  }
}

// Every axis stopped, the planner and pulse threads joined, then the outputs to their idle
// level, recorded in the trace like every other write (this thread may now produce into the
// pulse thread's ring too).
void Daemon::Impl::stop_threads(planner::PlannerThread& planner) {
  for (auto& m : modules) m->control().stop_motion();
  planner.stop();
  stack->output().stop();
  for (BuiltBackend& b : io) b.backend->idle_outputs();
  const Nanos now = monotonic_now();
  for (auto& m : modules) m->control().trace_enable_release(now);
  if (trace) trace->record_idle_outputs(*stack, now);
}

void Daemon::Impl::log_thread_stats(const planner::PlannerThread& planner) const {
  rt::StepOutput& pulse = stack->output();
  const auto stats = pulse.stats().snapshot();
  spdlog::info("pulse thread: {} edges written, lateness p50 {} ns, p99.9 {} ns, max {} ns",
               stats.count, stats.percentile(0.5), stats.percentile(0.999), stats.max);
  // How often each real-time thread woke: the cost of a motion on a slow CPU is mostly there.
  spdlog::info(
      "wake-ups: pulse thread {} loops, {} sleeps ({} starved polls); planner thread {} passes",
      pulse.loops(), pulse.sleeps(), pulse.starved_polls(), planner.loops());
  for (const auto& m : modules) {
    const std::string who = rack.rack_file ? "module '" + m->config().name + "' " : "";
    spdlog::info("{}control thread: {} scans published, longest {} us between two", who,
                 m->image().scan_counter(), m->control().longest_scan_gap() / kNsPerUs);
  }
}

}  // namespace stepmod::tools
