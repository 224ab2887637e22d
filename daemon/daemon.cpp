#include "daemon/daemon.hpp"

#include <spdlog/spdlog.h>

#include "daemon/backend_factory.hpp"
#include "daemon/control_loop.hpp"
#include "daemon/daemon_trace.hpp"
#include "daemon/realtime_setup.hpp"
#include "daemon/sim_panel_link.hpp"
#include "daemon/stack.hpp"
#include "doctor/startup_notice.hpp"
#include "ipc/modbus_server.hpp"
#include "ipc/shm_image.hpp"
#include "planner/planner_thread.hpp"
#include "systemd/notify.hpp"

namespace stepmod::tools {

// Declared in the order they are built; destroyed in reverse (the control loop before what it
// works on, the stack before the trace rings its step output writes, the backend last).
struct Daemon::Impl {
  Config config;
  Nanos start = monotonic_now();  // the VCD's #0
  BuiltBackend io;
  std::unique_ptr<DaemonTrace> trace;  // --trace
  std::unique_ptr<Stack> stack;
  std::unique_ptr<ipc::ShmImage> image;
  std::unique_ptr<SimPanelLink> panel;        // the "sim" backend only
  std::unique_ptr<ipc::ModbusServer> modbus;  // [modbus] enabled; its own thread
  std::unique_ptr<ControlLoop> control;

  void build_stack();
  void open_servers();
  void stop_threads(planner::PlannerThread& planner);
  void log_thread_stats(const planner::PlannerThread& planner) const;
};

Daemon::Daemon(const Config& config, const std::optional<std::string>& trace_path)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.config = config;
  d.io = make_backend(config);
  // Outputs start idle, as they will end.
  d.io.backend->idle_outputs();
  if (trace_path) d.trace = std::make_unique<DaemonTrace>();
  d.build_stack();
  d.open_servers();
  if (trace_path) d.trace->open(*trace_path, d.start, config, *d.stack);
  d.control = std::make_unique<ControlLoop>(
      ControlLoop::Parts{d.config, *d.stack, *d.image, d.trace.get(), d.panel.get()});
}

Daemon::~Daemon() = default;

void Daemon::Impl::build_stack() {
  StackOptions so;
  so.type = config.type;
  for (const AxisSection& a : config.axes) {
    so.timing.push_back({a.step_pulse_ns, a.dir_setup_ns});
    so.lag_limit_steps.push_back(a.lag_limit_steps);
  }
  // A new motion's time 0 is this long after the planner takes its command. The pulse thread,
  // rung when the command is submitted (PulseDoorbell), polls every max_sleep_ns (50 us) and
  // wakes ~15-20 us late: 100 us covers it and is 50 us off the command latency (issue 5).
  so.planner.start_delay_ns = 100 * kNsPerUs;
  so.late_limit_ns = config.late_limit_ns;
  stack = std::make_unique<Stack>(so, *io.backend, trace ? trace->output_ring() : nullptr);
}

// The shared-memory image, the simulator panel and the Modbus server.
void Daemon::Impl::open_servers() {
  image = std::make_unique<ipc::ShmImage>(config.name, stack->shape());
  // A crashed daemon's image is replaced silently by ShmImage; say what was there (a PLC still
  // attached to it would have been talking to nobody).
  if (const std::string old = image->replaced_description(); !old.empty()) {
    spdlog::warn("replaced {}", old);
  }
  if (io.sim != nullptr) {
    panel = std::make_unique<SimPanelLink>(config.name, *io.sim, stack->shape().axes);
  }
  if (config.modbus.enabled) {
    modbus = std::make_unique<ipc::ModbusServer>(config.name, config.modbus);
    spdlog::info("modbus: serving on {} (unit {}, writes {})", modbus->endpoint(),
                 config.modbus.unit_id, config.modbus.writes ? "accepted" : "refused");
  }
}

// The wiring of the threads: trace, pulse, planner, then this thread as the control thread
// until `stop`; then the orderly shutdown in the reverse order.
bool Daemon::run(const std::atomic<bool>& stop) {
  Impl& d = *impl_;
  const rt::StepOutput::Options po = pulse_options(d.config);
  rt::StepOutput& pulse = d.stack->output();
  if (d.trace) d.trace->start_thread();
  if (!pulse.start(po)) throw std::runtime_error("cannot start the pulse thread");
  warn_pulse_setup(po, pulse.status());
  planner::PlannerThread planner(d.stack->planner());
  planner.start();
  raise_planner_thread(planner, po.priority);

  spdlog::info("module {} '{}' running: /dev/shm/stepmod.{}, {} backend, scan {} us",
               static_cast<unsigned>(d.config.type), d.config.name, d.config.name,
               d.io.sim != nullptr ? "sim" : "gpiod", d.config.scan_ns / kNsPerUs);
  // The VCD's times are relative to this instant; an outside tool (bench/daemon_bench) needs it
  // to compare trace times with its own CLOCK_MONOTONIC readings.
  if (d.trace) spdlog::info("trace: #0 is CLOCK_MONOTONIC {} ns", d.start);
  // Whether the pulse CPU is shared, throttled or without PREEMPT_RT (the doctor's probes:
  // stepmodctl doctor measures what that costs).
  if (auto n = doctor::pulse_cpu_notice(d.config.rt_cpu); !n.empty()) spdlog::info("{}", n);
  systemd::notify_ready("running");
  if (d.io.sim == nullptr) raise_control_thread(d.config.rt_priority);
  d.control->run(stop);

  systemd::notify_stopping();
  d.stop_threads(planner);
  d.log_thread_stats(planner);
  const bool trace_complete = d.trace ? d.trace->finish() : true;
  if (d.io.backend->lost_events() > 0) {
    spdlog::warn("{} input events were lost in all", d.io.backend->lost_events());
  }
  return trace_complete;
}

// Every axis stopped, the planner and pulse threads joined, then the outputs to their idle
// level, recorded in the trace like every other write (this thread may now produce into the
// pulse thread's ring too).
void Daemon::Impl::stop_threads(planner::PlannerThread& planner) {
  control->stop_motion();
  planner.stop();
  stack->output().stop();
  io.backend->idle_outputs();
  const Nanos now = monotonic_now();
  control->trace_enable_release(now);
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
  spdlog::info("control thread: {} scans published, longest {} us between two",
               image->scan_counter(), control->longest_scan_gap() / kNsPerUs);
}

}  // namespace stepmod::tools
