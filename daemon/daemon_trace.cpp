#include "daemon/daemon_trace.hpp"

#include <spdlog/spdlog.h>

#include <sched.h>

#include "daemon/stack.hpp"

namespace stepmod::tools {

namespace {
// Records per trace ring: 4 MB each, ~130 ms of 2 M records/s. The trace thread spools them as
// fast as a copy (gpio/trace_spool.hpp) and runs at SCHED_FIFO 1 where there is a second CPU,
// so it is not starved for that long; bigger rings cost memory that a small board (or the
// 256 MB VM test) does not have to spare, since they are touched (and locked) up front.
constexpr std::size_t kOutputTraceRing = 1u << 18;
constexpr std::size_t kInputTraceRing = 1u << 18;
}  // namespace

DaemonTrace::DaemonTrace()
    : output_(std::make_unique<SpscRing<TraceRecord>>(kOutputTraceRing)),
      input_(std::make_unique<SpscRing<TraceRecord>>(kInputTraceRing)) {}

DaemonTrace::~DaemonTrace() = default;

// A rack's wires carry their module's name (docs/interface.md section 7): "x.axis1.step".
std::vector<std::string> DaemonTrace::axis_names(std::span<const Config> modules, Stack& stack) {
  std::vector<std::string> names;
  for (unsigned k = 0; k < stack.modules(); ++k) {
    for (unsigned a = 0; a < stack.module(k).shape().axes; ++a) {
      names.push_back(modules[k].name + ".axis" + std::to_string(a + 1));
    }
  }
  return names;
}

void DaemonTrace::open(const std::string& path, Nanos start, std::span<const Config> modules,
                       bool rack_file, Stack& stack) {
  std::vector<gpio::TraceWire> wires;
  for (unsigned k = 0; k < stack.modules(); ++k) {
    const unsigned first = stack.first_axis(k);
    for (gpio::TraceWire w : gpio::trace_wires(stack.module(k).backend())) {
      w.axis = static_cast<std::uint8_t>(w.axis + first);
      wires.push_back(w);
    }
  }
  for (unsigned k = 0; k < stack.modules(); ++k) {
    const std::vector<AxisSection>& axes = modules[k].axes;
    for (unsigned a = 0; a < axes.size(); ++a) {
      if (axes[a].enable) {
        wires.push_back(
            gpio::enable_trace_wire(stack.first_axis(k) + a, axes[a].enable_opt.active_low));
      }
    }
    const ChargePumpSection& pump = modules[k].charge_pump;
    if (pump.line) {
      wires.push_back(
          gpio::charge_pump_trace_wire(stack.first_axis(k), pump.line_opt.active_low));
    }
  }
  writer_ = std::make_unique<gpio::TraceWriter>(path, wires, start, *output_, *input_);
  if (rack_file) writer_->name_axes(axis_names(modules, stack));
  output_dropped_ = &stack.output().trace_dropped_counter();
  writer_->watch_losses(output_dropped_, &input_dropped_);
}

// SCHED_FIFO 1: above every normal thread, below the pulse and control threads (gpio/vcd_trace),
// where there is a second CPU for it. On a single CPU it stays a normal thread: its wake-ups
// would otherwise come before everything else there (the PLC, a test's machine model).
void DaemonTrace::start_thread() {
  cpu_set_t cpus;
  CPU_ZERO(&cpus);
  const bool several = sched_getaffinity(0, sizeof cpus, &cpus) == 0 && CPU_COUNT(&cpus) >= 2;
  writer_->start(several ? 1 : 0);
}

void DaemonTrace::record_input(const TraceRecord& r) noexcept {
  const std::lock_guard<std::mutex> turn(input_producer_);
  if (!input_->try_push(r)) {
    input_dropped_.store(input_dropped_.load(std::memory_order_relaxed) + 1,
                         std::memory_order_relaxed);
  }
}

std::uint64_t DaemonTrace::dropped() const noexcept {
  return output_dropped_->load(std::memory_order_relaxed) +
         input_dropped_.load(std::memory_order_relaxed);
}

// Bit 4 from the first lost record on: the trace stays incomplete (the VCD says so too). A
// spool write that failed (disk full) as well, at once.
bool DaemonTrace::lost() {
  const bool spool_failed = writer_->failed();
  if (dropped() == 0 && !spool_failed) return false;
  if (!loss_logged_.exchange(true)) {
    spdlog::error("trace: records lost ({}): the VCD will be incomplete",
                  spool_failed ? "a trace spool could not be written: disk full?"
                               : "the trace ring was full");
  }
  return true;
}

void DaemonTrace::record_idle_outputs(Stack& stack, Nanos now) noexcept {
  for (unsigned k = 0; k < stack.modules(); ++k) {
    const ModuleStack& m = stack.module(k);
    for (unsigned a = 0; a < m.shape().axes; ++a) {
      const std::uint8_t levels = m.feedback(a).output_levels.load(std::memory_order_acquire);
      const auto axis = static_cast<std::uint8_t>(stack.first_axis(k) + a);
      for (unsigned l = 0; l < kOutputLinesPerAxis; ++l) {
        if ((levels >> l) & 1u) output_->try_push({now, axis, static_cast<std::uint8_t>(l), 0, 0});
      }
    }
  }
}

bool DaemonTrace::finish() {
  const std::uint64_t outputs = output_dropped_->load(std::memory_order_relaxed);
  const std::uint64_t inputs = input_dropped_.load();
  const gpio::TraceOutcome t = writer_->stop(outputs, inputs);
  if (dropped() > 0) {
    spdlog::error(
        "trace: {} output and {} input records lost (ring full): the VCD is "
        "incomplete (it says so, and marks where)",
        outputs, inputs);
  }
  if (!t.complete) spdlog::error("trace: {}", t.problem);
  return t.complete && dropped() == 0;
}

}  // namespace stepmod::tools
