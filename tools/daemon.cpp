#include "tools/daemon.hpp"

#include <spdlog/spdlog.h>

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <thread>
#include <vector>

#include "gpio/sim_backend.hpp"
#include "gpio/vcd_trace.hpp"
#include "ipc/shm_image.hpp"
#include "ipc/sim_panel.hpp"
#include "planner/planner_thread.hpp"
#include "rt/pulse_thread.hpp"
#include "systemd/notify.hpp"
#include "tools/backend_factory.hpp"
#include "tools/stack.hpp"

namespace stepmod::tools {

namespace {
constexpr std::size_t kTraceRing = 1u << 18;  // records: ~130 ms of two axes at 1 MHz
// How long the shutdown waits for the pulse thread to acknowledge the immediate stops.
constexpr Nanos kStopAckTimeout = 200 * kNsPerMs;
}  // namespace

struct Daemon::Impl {
  Config config;
  Nanos start = monotonic_now();
  std::unique_ptr<gpio::Backend> backend;
  gpio::SimBackend* sim = nullptr;  // the same object when backend = "sim"
  std::unique_ptr<SpscRing<TraceRecord>> output_trace;
  std::unique_ptr<SpscRing<TraceRecord>> input_trace;
  std::unique_ptr<gpio::TraceWriter> trace;
  std::unique_ptr<Stack> stack;
  std::unique_ptr<ipc::ShmImage> image;
  std::unique_ptr<ipc::SimPanelServer> panel;
  std::uint64_t input_trace_dropped = 0;
  rt::PulseThread* pulse = nullptr;  // while run() runs
  std::uint32_t planner_wakes = 0;   // the planner's wake counter as last seen by kick()

  // After the control thread may have submitted commands (or set an immediate stop, which is
  // also submitted): ring the pulse thread's doorbell so that it polls for the new edges. It
  // otherwise sleeps until its next edge (PulseThreadOptions::quiet_sleep_ns).
  void kick() noexcept {
    const std::uint32_t w = stack->planner().wake_counter().load(std::memory_order_acquire);
    if (w == planner_wakes) return;
    planner_wakes = w;
    if (pulse != nullptr) pulse->ring();
  }
  bool axes_at_rest() noexcept {
    for (unsigned a = 0; a < stack->shape().axes; ++a) {
      if (stack->motion(a).busy()) return false;
    }
    return true;
  }

  void control_loop(const std::atomic<bool>& stop);
  void sync_panel();
  void shutdown_motion();
  void idle_outputs();
};

Daemon::Daemon(const Config& config, const std::optional<std::string>& trace_path)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.config = config;
  d.backend = make_backend(config);
  d.sim = dynamic_cast<gpio::SimBackend*>(d.backend.get());
  // Outputs start idle, as they will end.
  d.backend->idle_outputs();

  StackOptions so;
  so.type = config.type;
  for (const AxisConfig& a : config.axes) so.timing.push_back({a.step_pulse_ns, a.dir_setup_ns});
  // A new motion's time 0 is this long after the planner takes its command. The pulse thread,
  // rung when the command is submitted (kick()), polls every max_sleep_ns (50 us) and wakes
  // ~15-20 us late: 100 us covers it and is 50 us off the command latency (issue 5).
  so.planner.start_delay_ns = 100 * kNsPerUs;
  if (trace_path) {
    d.output_trace = std::make_unique<SpscRing<TraceRecord>>(kTraceRing);
    d.input_trace = std::make_unique<SpscRing<TraceRecord>>(kTraceRing);
  }
  d.stack = std::make_unique<Stack>(so, *d.backend, d.output_trace.get());
  d.image = std::make_unique<ipc::ShmImage>(config.name, d.stack->shape());
  if (d.sim != nullptr) {
    d.panel = std::make_unique<ipc::SimPanelServer>(config.name, d.stack->shape().axes);
  }
  if (trace_path) {
    const auto wires = gpio::trace_wires(*d.backend);
    d.trace = std::make_unique<gpio::TraceWriter>(*trace_path, wires, d.start, *d.output_trace,
                                                  *d.input_trace);
  }
}

Daemon::~Daemon() = default;

void Daemon::run(const std::atomic<bool>& stop) {
  Impl& d = *impl_;
  rt::PulseThread::Options po;
  po.priority = d.config.rt_priority;
  po.cpu = d.config.rt_cpu;
#ifdef STEPMOD_SANITIZED
  po.lock_memory = false;  // the sanitizers' shadow memory cannot be locked
#endif
  // Every command reaches the pulse thread through kick(): between commands it need not poll
  // (issue 5: an idle daemon polling every 50 us used a fifth of a core).
  po.quiet_sleep_ns = 100 * kNsPerMs;
  rt::PulseThread pulse(d.stack->engine(), po);
  d.pulse = &pulse;
  d.planner_wakes = d.stack->planner().wake_counter().load();
  if (d.trace) d.trace->start();
  if (!pulse.start()) throw std::runtime_error("cannot start the pulse thread");
  const auto& st = pulse.status();
  if (!st.fifo) {
    spdlog::warn(
        "pulse thread: SCHED_FIFO priority {} refused ({}); running without real-time "
        "priority: pulse timing will suffer under load",
        po.priority, std::strerror(st.sched_errno));
  }
  if (!st.memory_locked) {
    spdlog::warn("mlockall refused ({}); memory is not locked", std::strerror(st.mlock_errno));
  }
  if (po.cpu >= 0 && !st.pinned) {
    spdlog::warn("cannot pin the pulse thread to CPU {} ({})", po.cpu,
                 std::strerror(st.affinity_errno));
  }
  planner::PlannerThread planner(d.stack->planner());
  planner.start();

  spdlog::info("module {} '{}' running: /dev/shm/stepmod.{}, {} backend, scan {} us",
               static_cast<unsigned>(d.config.type), d.config.name, d.config.name,
               d.sim != nullptr ? "sim" : "gpiod", d.config.scan_ns / kNsPerUs);
  // The VCD's times are relative to this instant; an outside tool (bench/daemon_bench) needs it
  // to compare trace times with its own CLOCK_MONOTONIC readings.
  if (d.trace) spdlog::info("trace: #0 is CLOCK_MONOTONIC {} ns", d.start);
  systemd::notify_ready("running");

  // The control thread reads the input edges. The v1 GPIO uAPI keeps only 16 unread edges per
  // line and drops further ones silently, so this thread must run as soon as an edge arrives,
  // not when the scheduler next gives it a time slice (on a single-core board a busy process,
  // the soft PLC for one, otherwise makes it lose edges; an E-stop edge would wait as well).
  // Real-time, below the pulse thread; set after the other threads have been started so that
  // they do not inherit it. The simulated machine has no such buffer: left as it is.
  if (d.sim == nullptr) {
    sched_param sp{};
    sp.sched_priority = std::max(1, d.config.rt_priority - 10);
    const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
    if (rc != 0) {
      spdlog::warn(
          "control thread: SCHED_FIFO priority {} refused ({}); input edges may be lost "
          "under load",
          sp.sched_priority, std::strerror(rc));
    }
  }
  d.control_loop(stop);

  systemd::notify_stopping();
  d.shutdown_motion();
  planner.stop();
  pulse.stop();
  pulse.join();
  d.idle_outputs();
  const auto stats = d.stack->engine().stats().snapshot();
  spdlog::info("pulse thread: {} edges written, lateness p50 {} ns, p99.9 {} ns, max {} ns",
               stats.count, stats.percentile(0.5), stats.percentile(0.999), stats.max);
  if (d.trace) {
    d.trace->stop(d.stack->engine().trace_dropped(), d.input_trace_dropped);
    if (d.stack->engine().trace_dropped() + d.input_trace_dropped > 0) {
      spdlog::warn("trace: {} output and {} input records dropped (ring full)",
                   d.stack->engine().trace_dropped(), d.input_trace_dropped);
    }
  }
  if (d.backend->lost_events() > 0) {
    spdlog::warn("{} input events were lost", d.backend->lost_events());
  }
}

// The control thread: input events as they come, the PLC image once per scan.
void Daemon::Impl::control_loop(const std::atomic<bool>& stop) {
  module::Personality& personality = stack->personality();
  std::array<gpio::InputEvent, 64> events{};
  ImageWords out{};
  ImageWords in{};
  Nanos next_scan = monotonic_now();
  std::uint64_t last_heartbeat = image->heartbeat();
  Nanos heartbeat_changed = next_scan;
  bool plc_stopped = false;

  while (!stop.load(std::memory_order_acquire)) {
    std::size_t n = 0;
    if (sim != nullptr && axes_at_rest()) {
      // The simulated machine has no file descriptor to block on: its wait_events polls in
      // 50 us steps. With every axis at rest only the panel, applied by this thread, changes an
      // input: sleep to the scan in one go, then drain (issue 5: idle CPU).
      if (monotonic_now() < next_scan) sleep_until(next_scan);
      n = backend->wait_events(events, 0);
    } else {
      n = backend->wait_events(events, next_scan);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const gpio::InputEvent& e = events[i];
      if (input_trace) {
        const TraceRecord r{e.t, e.axis, static_cast<std::uint8_t>(e.line),
                            static_cast<std::uint8_t>(e.level), 1};
        if (!input_trace->try_push(r)) ++input_trace_dropped;
      }
      personality.on_input(e);
    }
    kick();
    if (panel) sync_panel();
    const Nanos now = monotonic_now();
    if (now < next_scan) continue;

    // One consistent snapshot per scan; a PLC caught mid-write keeps the previous snapshot.
    image->read_outputs(out);
    if (config.plc_timeout_ns > 0) {
      const std::uint64_t hb = image->heartbeat();
      if (hb != last_heartbeat) {
        last_heartbeat = hb;
        heartbeat_changed = now;
        plc_stopped = false;
      } else if (!plc_stopped && now - heartbeat_changed >= config.plc_timeout_ns) {
        spdlog::warn("PLC heartbeat unchanged for {} ms: treating the PLC as out of Run mode",
                     config.plc_timeout_ns / kNsPerMs);
        personality.plc_stopped(now);
        plc_stopped = true;
      }
    }
    // The 3202's blend message (INTERFACE.md 3): handed over before the scan that reports it.
    if (const auto msg = image->pending_message()) {
      image->finish_message(msg->seq, personality.on_message(msg->data, now));
    }
    personality.scan(out, in, now);
    kick();
    image->publish_inputs(in);
    next_scan += config.scan_ns;
    if (next_scan <= now) next_scan = now + config.scan_ns;  // overrun: skip, never burst
  }
}

void Daemon::Impl::sync_panel() {
  for (unsigned a = 0; a < stack->shape().axes; ++a) {
    sim->force(a, panel->force_mask(a), panel->force_levels(a));
    panel->publish_position(a, sim->position(a));
    panel->publish_encoder(a, sim->encoder(a));
    panel->publish_outputs(a, sim->output_levels(a));
  }
}

// Outputs to their idle level, recorded in the trace like every other write. The pulse thread
// has been joined, so this thread may now be the producer of its trace ring.
void Daemon::Impl::idle_outputs() {
  backend->idle_outputs();
  const Nanos now = monotonic_now();
  for (unsigned a = 0; a < stack->shape().axes; ++a) {
    const std::uint8_t levels = stack->feedback(a).output_levels.load(std::memory_order_acquire);
    for (unsigned l = 0; l < kOutputLinesPerAxis; ++l) {
      if (output_trace && (levels >> l) & 1u) {
        output_trace->try_push(
            {now, static_cast<std::uint8_t>(a), static_cast<std::uint8_t>(l), 0, 0});
      }
    }
  }
}

// Immediate stop of every axis, and wait (bounded) until the pulse thread has acknowledged it.
void Daemon::Impl::shutdown_motion() {
  stack->personality().shutdown();
  kick();
  const Nanos deadline = monotonic_now() + kStopAckTimeout;
  for (unsigned a = 0; a < stack->shape().axes; ++a) {
    while (stack->motion(a).busy() && monotonic_now() < deadline) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
  if (panel) sync_panel();
}

}  // namespace stepmod::tools
