#include "tools/daemon.hpp"

#include <spdlog/spdlog.h>

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <thread>
#include <vector>

#include "gpio/sim_backend.hpp"
#include "gpio/vcd_trace.hpp"
#include "ipc/plc_supervisor.hpp"
#include "ipc/modbus_server.hpp"
#include "ipc/shm_image.hpp"
#include "ipc/sim_panel.hpp"
#include "module/axis/error_items.hpp"
#include "planner/output_doorbell.hpp"
#include "planner/planner_thread.hpp"
#include "rt/limits_hint.hpp"
#include "rt/step_output.hpp"
#include "systemd/notify.hpp"
#include "systemd/watchdog.hpp"
#include "tools/backend_factory.hpp"
#include "tools/drive_enable.hpp"
#include "tools/lease_keeper.hpp"
#include "tools/reason_publisher.hpp"
#include "tools/stack.hpp"

namespace stepmod::tools {

namespace {
// Records per trace ring: 4 MB each, ~130 ms of 2 M records/s. The trace thread spools them as
// fast as a copy (gpio/trace_spool.hpp) and runs at SCHED_FIFO 1 where there is a second CPU,
// so it is not starved for that long; bigger rings cost memory that a small board (or the
// 256 MB VM test) does not have to spare, since they are touched (and locked) up front.
constexpr std::size_t kOutputTraceRing = 1u << 18;
constexpr std::size_t kInputTraceRing = 1u << 18;
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
  std::unique_ptr<DriveEnable> drive_enable;  // the axes' enable outputs (extension)
  std::unique_ptr<ipc::ShmImage> image;
  std::unique_ptr<ipc::SimPanelServer> panel;
  std::unique_ptr<ipc::ModbusServer> modbus;  // [modbus] enabled; its own thread
  systemd::Watchdog watchdog;  // WatchdogSec=: petted per scan while the pulse thread loops
  std::atomic<std::uint64_t> input_trace_dropped{0};  // control thread writes, trace reads
  rt::StepOutput* pulse = nullptr;                    // while run() runs
  std::optional<planner::OutputDoorbell> doorbell;    // kick()'s: when to ring (set by run())
  std::vector<std::uint32_t> late_faults_seen;        // per axis: faults already logged
  // Per axis, for the "needs a CPU of its own" notice: the step count at the last scan and the
  // motion it was last given for.
  std::vector<std::uint32_t> cpu_notice_epoch;
  bool trace_loss_logged = false;
  // The longest time between two published scans (the image counts them): a PLC sees nothing
  // new for that long (the control thread held off the CPU), logged at exit. 0: none yet.
  Nanos longest_scan_gap = 0;
  Nanos last_publish = 0;
  // Input events lost (gpio::Backend::lost_events): the count already acted on, and each axis'
  // motion epoch at the last loss (health bit 5 lasts until one of them has a new motion).
  std::uint64_t lost_inputs_seen = 0;
  std::vector<std::uint32_t> input_loss_epochs;

  // After the control thread may have submitted commands (an immediate stop too): ring the pulse
  // thread so that it polls for the new edges, and again once they are planned (it otherwise
  // sleeps until its next edge, quiet_sleep_ns; planner/output_doorbell.hpp).
  void kick() noexcept {
    if (doorbell && doorbell->due() && pulse != nullptr) pulse->ring();
  }

  void control_loop(const std::atomic<bool>& stop);
  bool finish_trace();  // after the threads: the VCD written; false if incomplete
  // The daemon health words (docs/interface.md 3.3) for this scan, logging new late-edge faults.
  ipc::Health health(std::uint32_t supervisor_flags);
  void log_supervision(const ipc::PlcSupervisor& sup, Nanos now);
  void check_lost_inputs(Nanos now);
  void update_drive_enable(const ipc::PlcSupervisor& sup, Nanos now);
  bool input_loss_lasts() const noexcept;
  void notice_cpu_need(Nanos now);
  std::uint64_t trace_dropped() const noexcept {
    return stack->output().trace_dropped() + input_trace_dropped.load(std::memory_order_relaxed);
  }
  void take_panel_forces();
  void publish_panel();
  void note_scan_published() noexcept;
  void shutdown_motion();
  void idle_outputs();
  void trace_input_record(const TraceRecord& r);
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
  for (const AxisConfig& a : config.axes) {
    so.timing.push_back({a.step_pulse_ns, a.dir_setup_ns});
    so.lag_limit_steps.push_back(a.lag_limit_steps);
  }
  // A new motion's time 0 is this long after the planner takes its command. The pulse thread,
  // rung when the command is submitted (kick()), polls every max_sleep_ns (50 us) and wakes
  // ~15-20 us late: 100 us covers it and is 50 us off the command latency (issue 5).
  so.planner.start_delay_ns = 100 * kNsPerUs;
  so.late_limit_ns = config.late_limit_ns;
  if (trace_path) {
    d.output_trace = std::make_unique<SpscRing<TraceRecord>>(kOutputTraceRing);
    d.input_trace = std::make_unique<SpscRing<TraceRecord>>(kInputTraceRing);
  }
  d.stack = std::make_unique<Stack>(so, *d.backend, d.output_trace.get());
  d.image = std::make_unique<ipc::ShmImage>(config.name, d.stack->shape());
  // A crashed daemon's image is replaced silently by ShmImage; say what was there (a PLC still
  // attached to it would have been talking to nobody).
  if (const std::string old = d.image->replaced_description(); !old.empty()) {
    spdlog::warn("replaced {}", old);
  }
  std::vector<DriveEnable::AxisSetup> enables;
  for (const AxisConfig& a : config.axes) {
    enables.push_back({a.enable.has_value(), a.enable_delay_ns, a.enable_release});
  }
  d.drive_enable = std::make_unique<DriveEnable>(*d.backend, std::move(enables), &monotonic_now);
  d.late_faults_seen.assign(d.stack->shape().axes, 0);
  d.cpu_notice_epoch.assign(d.stack->shape().axes, 0);
  if (d.sim != nullptr) {
    d.panel = std::make_unique<ipc::SimPanelServer>(config.name, d.stack->shape().axes);
  }
  if (config.modbus.enabled) {
    d.modbus = std::make_unique<ipc::ModbusServer>(config.name, config.modbus);
    spdlog::info("modbus: serving on {} (unit {}, writes {})", d.modbus->endpoint(),
                 config.modbus.unit_id, config.modbus.writes ? "accepted" : "refused");
  }
  if (trace_path) {
    auto wires = gpio::trace_wires(*d.backend);
    for (unsigned a = 0; a < config.axes.size(); ++a) {
      if (config.axes[a].enable)
        wires.push_back(gpio::enable_trace_wire(a, config.axes[a].enable_opt.active_low));
    }
    d.trace = std::make_unique<gpio::TraceWriter>(*trace_path, wires, d.start, *d.output_trace,
                                                  *d.input_trace);
    d.trace->watch_losses(&d.stack->output().trace_dropped_counter(), &d.input_trace_dropped);
  }
}

Daemon::~Daemon() = default;

namespace {

// The pulse thread's options from the configuration.
rt::StepOutput::Options pulse_options(const Config& config) {
  rt::StepOutput::Options po;
  po.priority = config.rt_priority;
  po.cpu = config.rt_cpu;
#ifdef STEPMOD_SANITIZED
  po.lock_memory = false;  // the sanitizers' shadow memory cannot be locked
#endif
  // Every command reaches the pulse thread through kick(): between commands it need not poll
  // (issue 5: an idle daemon polling every 50 us used a fifth of a core).
  po.quiet_sleep_ns = 100 * kNsPerMs;
  return po;
}

// What the pulse thread's setup was refused, said once (the thread itself never logs).
void warn_pulse_setup(const rt::StepOutput::Options& po, const rt::StepOutput::Status& st) {
  if (!st.fifo) {
    spdlog::warn(
        "pulse thread: SCHED_FIFO priority {} refused ({}); running without real-time "
        "priority: pulse timing will suffer under load{}",
        po.priority, std::strerror(st.sched_errno), rt::rtprio_fix(st.sched_errno));
  }
  if (!po.lock_memory) {
    // A sanitizer build never asks (its shadow memory cannot be locked): no refusal to report.
    spdlog::info("memory locking is off in this sanitizer build");
  } else if (!st.memory_locked) {
    spdlog::warn("mlockall refused ({}); memory is not locked{}", std::strerror(st.mlock_errno),
                 rt::memlock_fix(st.mlock_errno));
  }
  if (po.cpu >= 0 && !st.pinned) {
    spdlog::warn("cannot pin the pulse thread to CPU {} ({})", po.cpu,
                 std::strerror(st.affinity_errno));
  }
}

// SCHED_FIFO 1: above every normal thread, below the pulse and control threads (gpio/vcd_trace),
// where there is a second CPU for it. On a single CPU it stays a normal thread: its wake-ups
// would otherwise come before everything else there (the PLC, a test's machine model).
void start_trace_thread(gpio::TraceWriter& trace) {
  cpu_set_t cpus;
  CPU_ZERO(&cpus);
  const bool several = sched_getaffinity(0, sizeof cpus, &cpus) == 0 && CPU_COUNT(&cpus) >= 2;
  trace.start(several ? 1 : 0);
}

// Real-time below the control thread (issue 18): under CPU hogs a normal-priority planner was
// held off for milliseconds, the pulse thread's 4 ms of edges ran dry and the steps paused.
void raise_planner_thread(planner::PlannerThread& planner, int rt_priority) {
  if (rt_priority <= 0) return;
  const int prio = std::max(1, rt_priority - 20);
  if (const int rc = planner.set_realtime(prio); rc != 0) {
    spdlog::warn("planner thread: SCHED_FIFO priority {} refused ({}): steps may pause under load",
                 prio, std::strerror(rc));
  }
}

// The control thread reads the input edges. The v1 GPIO uAPI keeps only 16 unread edges per
// line and drops further ones silently, so this thread must run as soon as an edge arrives,
// not when the scheduler next gives it a time slice (on a single-core board a busy process,
// the soft PLC for one, otherwise makes it lose edges; an E-stop edge would wait as well).
// Real-time, below the pulse thread; set after the other threads have been started so that
// they do not inherit it. The simulated machine's FIFO is sized to ride out an ordinary thread's
// stalls instead (gpio::kDefaultSimEventRing): left as it is.
void raise_control_thread(int rt_priority) {
  sched_param sp{};
  sp.sched_priority = std::max(1, rt_priority - 10);
  const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
  if (rc != 0) {
    spdlog::warn(
        "control thread: SCHED_FIFO priority {} refused ({}); input edges may be lost "
        "under load",
        sp.sched_priority, std::strerror(rc));
  }
}

}  // namespace

// The wiring of the threads: pulse, trace, planner, then this thread as the control thread
// (control_loop) until `stop`; then the orderly shutdown in the reverse order.
bool Daemon::run(const std::atomic<bool>& stop) {
  Impl& d = *impl_;
  const rt::StepOutput::Options po = pulse_options(d.config);
  rt::StepOutput& pulse = d.stack->output();
  d.pulse = &pulse;
  d.doorbell.emplace(d.stack->planner());
  if (d.trace) start_trace_thread(*d.trace);
  if (!pulse.start(po)) throw std::runtime_error("cannot start the pulse thread");
  warn_pulse_setup(po, pulse.status());
  planner::PlannerThread planner(d.stack->planner());
  planner.start();
  raise_planner_thread(planner, po.priority);

  spdlog::info("module {} '{}' running: /dev/shm/stepmod.{}, {} backend, scan {} us",
               static_cast<unsigned>(d.config.type), d.config.name, d.config.name,
               d.sim != nullptr ? "sim" : "gpiod", d.config.scan_ns / kNsPerUs);
  // The VCD's times are relative to this instant; an outside tool (bench/daemon_bench) needs it
  // to compare trace times with its own CLOCK_MONOTONIC readings.
  if (d.trace) spdlog::info("trace: #0 is CLOCK_MONOTONIC {} ns", d.start);
  systemd::notify_ready("running");
  if (d.sim == nullptr) raise_control_thread(d.config.rt_priority);
  d.control_loop(stop);

  systemd::notify_stopping();
  d.shutdown_motion();
  planner.stop();
  pulse.stop();
  d.idle_outputs();
  const auto stats = pulse.stats().snapshot();
  spdlog::info("pulse thread: {} edges written, lateness p50 {} ns, p99.9 {} ns, max {} ns",
               stats.count, stats.percentile(0.5), stats.percentile(0.999), stats.max);
  // How often each real-time thread woke: the cost of a motion on a slow CPU is mostly there.
  spdlog::info(
      "wake-ups: pulse thread {} loops, {} sleeps ({} starved polls); planner thread {} passes",
      pulse.loops(), pulse.sleeps(), pulse.starved_polls(), planner.loops());
  spdlog::info("control thread: {} scans published, longest {} us between two",
               d.image->scan_counter(), d.longest_scan_gap / kNsPerUs);
  const bool trace_complete = d.finish_trace();
  if (d.backend->lost_events() > 0) {
    spdlog::warn("{} input events were lost in all", d.backend->lost_events());
  }
  return trace_complete;
}

// After the threads have stopped: the VCD written; false if it lost records.
bool Daemon::Impl::finish_trace() {
  if (!trace) return true;
  const gpio::TraceOutcome t =
      trace->stop(stack->output().trace_dropped(), input_trace_dropped.load());
  if (trace_dropped() > 0) {
    spdlog::error(
        "trace: {} output and {} input records lost (ring full): the VCD is "
        "incomplete (it says so, and marks where)",
        stack->output().trace_dropped(), input_trace_dropped.load());
  }
  if (!t.complete) spdlog::error("trace: {}", t.problem);
  return t.complete && trace_dropped() == 0;
}

// The control thread: input events as they come, the PLC image once per scan.
void Daemon::Impl::control_loop(const std::atomic<bool>& stop) {
  module::Personality& personality = stack->personality();
  std::array<gpio::InputEvent, 64> events{};
  ImageWords in{};
  ImageWords given{};  // the output words the module last scanned (held while a drive gets ready)
  Nanos next_scan = monotonic_now();
  ipc::PlcSupervisor supervisor(config.plc_timeout_ns);
  LeaseKeeper lease;                             // INTERFACE 3.5
  ReasonPublisher reasons(stack->shape().axes);  // INTERFACE 3.4

  while (!stop.load(std::memory_order_acquire)) {
    // Both backends block until an input edge or the scan (the sim on a futex its writes end,
    // gpiod on its event file descriptors): no polling, moving or not.
    const std::size_t n = backend->wait_events(events, next_scan);
    for (std::size_t i = 0; i < n; ++i) {
      const gpio::InputEvent& e = events[i];
      trace_input_record(
          {e.t, e.axis, static_cast<std::uint8_t>(e.line), static_cast<std::uint8_t>(e.level), 1});
      personality.on_input(e);
    }
    const Nanos now = monotonic_now();
    check_lost_inputs(now);
    kick();
    if (panel) take_panel_forces();
    if (now < next_scan) continue;

    // One consistent snapshot per scan; a PLC caught mid-write keeps the previous snapshot.
    // The supervisor (ipc/plc_supervisor.hpp) decides what the module gets: the live words, or
    // while the PLC is lost (heartbeat stale, sequence stuck odd) the frozen last good ones.
    ipc::PlcSupervisor::Sample sample;
    sample.now = now;
    sample.heartbeat = image->heartbeat();
    sample.seq = image->output_seq();
    sample.snapshot_ok = image->read_outputs(sample.words, sample.snapshot_seq);
    sample.lease_until = lease.scan(*image, sample.heartbeat, now, personality);
    // While a drive enabled a moment ago is not ready, the module keeps scanning the words it
    // had: a command issued meanwhile is a new edge once the drive is ready.
    const ImageWords& live = supervisor.scan(sample);
    const ImageWords& out = drive_enable->holding(now) ? given : live;
    log_supervision(supervisor, now);
    // As a PLC leaving Run mode (INTERFACE 3.2): every move stops, position invalid. Once per
    // loss; the frozen words keep anything new from starting until the PLC is back.
    if (supervisor.tripped()) personality.plc_stopped(now);
    // The 3202's blend message (docs/interface.md 3): handed over before the scan that reports it.
    // Not while the PLC is lost: like the frozen words, nothing new is acted on until it is back.
    std::optional<ipc::BlendMessage> message;
    std::int32_t message_result = 0;
    if (!supervisor.plc_lost()) {
      message = image->pending_message();
      if (message) message_result = personality.on_message(message->data, now);
    }
    personality.scan(out, in, now);
    if (&out != &given) given = out;
    update_drive_enable(supervisor, now);
    kick();
    notice_cpu_need(now);
    reasons.scan(personality, *image);
    // The machine as of this scan, before the status: a reader that sees "stopped" in the status
    // finds the panel showing the motor's last step, not the one of the loop's top.
    if (panel) publish_panel();
    image->publish_inputs(in, health(supervisor.flags() | lease.flags()));
    note_scan_published();
    // Done only once the status that shows the message's effect is published: a PLC that reads
    // the status bits when its message is done (docs/interface.md 3: an error is in the status
    // bits) finds them. Marked done before this publication, a refused message was seen done with
    // Invalid Profile still clear (a loaded machine preempted the control thread in between).
    if (message) image->finish_message(message->seq, message_result);
    if (pulse != nullptr) watchdog.scan(now, pulse->loops());
    next_scan += config.scan_ns;
    if (next_scan <= now) next_scan = now + config.scan_ns;  // overrun: skip, never burst
  }
}

void Daemon::Impl::note_scan_published() noexcept {
  const Nanos now = monotonic_now();
  if (last_publish != 0) longest_scan_gap = std::max(longest_scan_gap, now - last_publish);
  last_publish = now;
}

ipc::Health Daemon::Impl::health(std::uint32_t supervisor_flags) {
  ipc::Health h;
  h.flags = supervisor_flags;
  Nanos worst = 0;
  for (unsigned a = 0; a < stack->shape().axes; ++a) {
    const planner::MotionPort& m = stack->motion(a);
    const planner::MotionPort::LateFault f = m.late_fault();
    if (f.count != late_faults_seen[a]) {
      late_faults_seen[a] = f.count;
      spdlog::error(
          "axis {}: late-edge fault at step {}: speed {} steps/s, pause {} us, lag {} steps "
          "(limits: {} steps above the starting speed, {} us at any speed); motion cut, no "
          "burst: the axis is stopped with position invalid (re-home). {} fault(s) on this "
          "axis so far",
          a + 1, f.step, f.interval_ns > 0 ? kNsPerSec / f.interval_ns : 0, f.late_ns / kNsPerUs,
          f.lag, config.axes[a].lag_limit_steps, config.late_limit_ns / kNsPerUs, f.count);
    }
    h.late_faults += f.count;
    worst = std::max(worst, f.worst_late_ns);
    // Bit 0 from the fault until the axis' next motion (the PLC's next accepted command).
    if (f.count != 0 && f.epoch == m.epoch()) h.flags |= STEPMOD_HEALTH_LATE_EDGE;
  }
  h.worst_late_us = static_cast<std::uint32_t>(
      std::min<Nanos>(worst / kNsPerUs, std::numeric_limits<std::uint32_t>::max()));
  if (input_loss_lasts()) h.flags |= STEPMOD_HEALTH_INPUT_LOST;
  // Bit 4 from the first lost record on: the trace stays incomplete (the VCD says so too).
  // A spool write that failed (disk full) as well, at once.
  const bool spool_failed = trace && trace->failed();
  if (output_trace && (trace_dropped() > 0 || spool_failed)) {
    h.flags |= STEPMOD_HEALTH_TRACE_LOST;
    if (!trace_loss_logged) {
      trace_loss_logged = true;
      spdlog::error("trace: records lost ({}): the VCD will be incomplete",
                    spool_failed ? "a trace spool could not be written: disk full?"
                                 : "the trace ring was full");
    }
  }
  return h;
}

// Issue 12 item 5, issue 18: a motion whose edges come closer together than the pulse thread's
// early wake-up keeps that thread on its CPU for the whole move. On a CPU shared with other
// threads the kernel then takes it away now and then (RT throttling, the fair server: tens of
// ms): the schedule slips, and above Vs a pause of more than [axis] lag_limit_steps steps is a
// fault. Said once per motion, from here (never the pulse thread), once the motion is past its
// acceleration, naming its programmed speed there (the planned step interval, not a count of
// steps per scan, which a late scan inflates).
void Daemon::Impl::notice_cpu_need(Nanos /*now*/) {
  for (unsigned a = 0; a < stack->shape().axes; ++a) {
    planner::MotionPort& m = stack->motion(a);
    const Nanos interval = m.planned_interval();
    if (pulse == nullptr || interval <= 0 || !m.busy() || cpu_notice_epoch[a] == m.epoch() ||
        m.phase() == planner::MotionPort::Phase::kAccelerating) {
      continue;
    }
    const Nanos edge_gap = interval / 2;  // two edges per step
    // Only once the thread has measured its wake-ups (before, its spin is a placeholder).
    if (pulse->wake_p99() == 0 || edge_gap >= pulse->stay_on_cpu_gap()) continue;
    cpu_notice_epoch[a] = m.epoch();
    spdlog::warn(
        "axis {}: programmed {} steps/s, an edge every {} us: closer than the pulse thread's "
        "wake-up ({} us early; measured p99 wake-up lateness {} us), so the thread stays on its "
        "CPU for this move. {}; a pause slips the move, and one of more than {} steps above the "
        "starting speed (or {} us at any speed) stops the axis (docs/slip.md)",
        a + 1, kNsPerSec / interval, edge_gap / 1000.0, pulse->spin_now() / kNsPerUs,
        pulse->wake_p99() / kNsPerUs,
        config.rt_cpu >= 0
            ? "Make sure no other thread runs on CPU " + std::to_string(config.rt_cpu)
            : std::string("This axis needs a CPU of its own ([rt] cpu + isolcpus= "
                          "or a cpuset)"),
        config.axes[a].lag_limit_steps, config.late_limit_ns / kNsPerUs);
  }
}

// Issue 18 item 5 / issue 19: an input edge the module never saw (a home, limit or capture edge,
// an encoder count) leaves a homing, a registration or a position that cannot be trusted, so a
// loss stops every moving axis as a PLC leaving Run mode does (immediate stop, position
// invalid), sets health bit 5 and is logged. Losses: the kernel's per-line event FIFO (seen by
// sequence-number gaps with libgpiod 2, by repeated edge directions with 1.6) or the simulated
// machine's event ring.
void Daemon::Impl::check_lost_inputs(Nanos now) {
  const std::uint64_t lost = backend->lost_events();
  if (lost == lost_inputs_seen) return;
  const std::uint64_t fresh = lost - lost_inputs_seen;
  lost_inputs_seen = lost;
  unsigned moving = 0;
  for (unsigned a = 0; a < stack->shape().axes; ++a) moving += stack->motion(a).busy() ? 1u : 0u;
  stack->personality().stop_every_axis(module::axis::items::kPiInputLost, now);
  input_loss_epochs.assign(stack->shape().axes, 0);
  for (unsigned a = 0; a < stack->shape().axes; ++a)
    input_loss_epochs[a] = stack->motion(a).epoch();
  spdlog::error(
      "{} input event(s) lost ({} in all): {} moving axis/axes stopped, position invalid "
      "(re-home); a homing or registration may have missed its edge",
      fresh, lost, moving);
}

void Daemon::Impl::update_drive_enable(const ipc::PlcSupervisor& sup, Nanos now) {
  if (!drive_enable->any_wired()) return;
  const bool input_loss = input_loss_lasts();
  for (unsigned a = 0; a < stack->shape().axes; ++a) {
    const module::Personality::DriveState s = stack->personality().drive_state(a);
    const planner::MotionPort& m = stack->motion(a);
    const planner::MotionPort::LateFault f = m.late_fault();
    DriveEnable::Conditions c;
    c.configured = s.configured;
    c.configuration_mode = s.configuration_mode;
    c.estop = s.estop;
    c.fault = input_loss || (f.count != 0 && f.epoch == m.epoch());
    c.plc_lost = sup.plc_lost();
    if (drive_enable->update(a, c, now)) {
      trace_input_record({drive_enable->changed_at(a), static_cast<std::uint8_t>(a),
                          gpio::kEnableTraceLine, drive_enable->asserted(a), 0});
    }
  }
}

// Control thread (or, once it has ended, the thread that ran it): one record into the input
// trace ring, whose only producer that thread is.
void Daemon::Impl::trace_input_record(const TraceRecord& r) {
  if (input_trace && !input_trace->try_push(r)) {
    input_trace_dropped.store(input_trace_dropped.load(std::memory_order_relaxed) + 1,
                              std::memory_order_relaxed);
  }
}

// Bit 5 from the loss until the PLC's next accepted motion on any axis.
bool Daemon::Impl::input_loss_lasts() const noexcept {
  if (input_loss_epochs.empty()) return false;
  for (unsigned a = 0; a < input_loss_epochs.size(); ++a) {
    if (stack->motion(a).epoch() != input_loss_epochs[a]) return false;
  }
  return true;
}

void Daemon::Impl::log_supervision(const ipc::PlcSupervisor& sup, Nanos now) {
  const std::uint32_t on = sup.started();
  const std::uint32_t off = sup.ended();
  if ((on | off) == 0) return;
  if (on & STEPMOD_HEALTH_PLC_STALE) {
    spdlog::warn(
        "PLC heartbeat unchanged for {} ms: the PLC is treated as out of Run mode (every axis "
        "stopped, position invalid; the output words are frozen and not acted on until the "
        "heartbeat moves again)",
        sup.heartbeat_age(now) / kNsPerMs);
  }
  if (off & STEPMOD_HEALTH_PLC_STALE) {
    spdlog::info(
        "PLC heartbeat moves again: output words acted on again (a command bit held "
        "through the outage needs a new 0->1 edge)");
  }
  if (on & STEPMOD_HEALTH_SEQ_STUCK) {
    spdlog::warn(
        "output sequence left odd ({}) for {} ms: a PLC died in the middle of a write; treated "
        "as the PLC out of Run mode (every axis stopped, position invalid, words frozen)",
        sup.stuck_seq(), sup.odd_timeout() / kNsPerMs);
  }
  if (off & STEPMOD_HEALTH_SEQ_STUCK) {
    spdlog::info(
        "output sequence moves again: output words acted on again (a command bit held "
        "through the outage needs a new 0->1 edge)");
  }
  if (on & STEPMOD_HEALTH_SEQ_BYPASS) {
    spdlog::warn(
        "output words changed while the output sequence did not: a writer bypasses the seqlock "
        "(INTERFACE 3.1); the module may act on torn words (an old MSW with a new LSW)");
  }
  if (off & STEPMOD_HEALTH_SEQ_BYPASS) {
    spdlog::info("no seqlock bypass for {} ms ({} bypassing change(s) seen in all)",
                 ipc::PlcSupervisor::kBypassQuiet / kNsPerMs, sup.bypass_changes());
  }
}

// The panel's forced inputs into the simulated machine: at every wake, so that a forced edge is
// an input event at once. The machine goes back to the panel once per scan (publish_panel).
void Daemon::Impl::take_panel_forces() {
  for (unsigned a = 0; a < stack->shape().axes; ++a) {
    sim->force(a, panel->force_mask(a), panel->force_levels(a));
  }
}

void Daemon::Impl::publish_panel() {
  for (unsigned a = 0; a < stack->shape().axes; ++a) {
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
    // The drive enables are released too (after the control loop: this thread fed its ring).
    if (drive_enable->asserted(a))
      trace_input_record({now, static_cast<std::uint8_t>(a), gpio::kEnableTraceLine, 0, 0});
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
  if (panel) publish_panel();
}

}  // namespace stepmod::tools
