#pragma once
// The step-output seam: what turns each axis' ring of planned edges into line changes on time.
// The pulse thread (rt/pulse_thread_output.hpp: PulseEngine on PulseThread, each line written
// "now" through gpio::Backend) is the first implementation; an output whose edges a peripheral
// times (the Raspberry Pi 5's RP1 PIO, a DMA- or SPI-timed output, a microcontroller) is a
// second class behind the same verbs, made by name in rt/step_output_factory.cpp. What such a
// class must guarantee: docs/ARCHITECTURE.md, "Adding a step output".
//
// The verbs, and where they travel:
//  * take a ring of edges per axis — construction (StepOutputWiring: one AxisLink per axis: the
//    planner's SpscRing<Edge>, the feedback it writes, the control block it reads, the history);
//  * report progress and slip — per axis in AxisFeedback (steps, epochs, slip, the late-edge
//    guard's fault) and StepHistory, which the module and the planner read; the pulse thread's
//    own lateness in stats();
//  * cut and immediate stop — per axis in AxisControl (abort_epoch, limit_steps, the EdgeCut
//    handshake), written lock-free by the module and the planner, honoured by the output at its
//    next look; ring() makes it look now;
//  * start and stop the output — start(), stop().
// These are control-side calls: a virtual call per command or scan, never per edge. The
// real-time loop of an implementation is its own concrete code (PulseThread calls PulseEngine
// directly).
#include <atomic>
#include <cstdint>
#include <span>

#include "core/clock.hpp"
#include "core/spsc_ring.hpp"
#include "core/trace_record.hpp"
#include "gpio/backend.hpp"
#include "rt/axis_feedback.hpp"
#include "rt/edge.hpp"
#include "rt/lateness_stats.hpp"
#include "rt/output_thread.hpp"

namespace stepmod::rt {

// A clock in place of CLOCK_MONOTONIC (virtual time).
using ClockFn = Nanos (*)() noexcept;

// What every step output is made from. All of it must outlive the output.
struct StepOutputWiring {
  gpio::Backend& backend;                  // the axes' lines (and the simulated machine)
  std::span<const AxisLink> axes;          // one per axis, indexed by axis
  SpscRing<TraceRecord>* trace = nullptr;  // every line write, for --trace (may be null)
};

class StepOutput {
 public:
  using Options = OutputThreadOptions;
  using Status = OutputThreadStatus;

  virtual ~StepOutput() = default;  // stops the output if it runs
  StepOutput() = default;
  StepOutput(const StepOutput&) = delete;
  StepOutput& operator=(const StepOutput&) = delete;

  // --- The late-edge guard (docs/slip.md); before start() ---
  // The longest pause at any speed (0 = off), and per axis the lag above Vs (0 = off).
  virtual void set_late_limit(Nanos limit) noexcept = 0;
  virtual void set_lag_limit(unsigned axis, std::uint32_t steps) noexcept = 0;

  // --- Running (the control thread) ---
  // Starts the output and waits until its thread's setup is done (status() is final). False if
  // it could not be started or already runs.
  virtual bool start(const Options& options) = 0;
  // Ends the output and waits for it: once it returns, the output writes no line and reads no
  // ring. Lines are left as they are (the caller idles them). No-op when not running.
  virtual void stop() = 0;
  virtual bool running() const noexcept = 0;
  // Any thread but the output's: new work may be queued (a command was submitted, an immediate
  // stop or a cut requested): look at the rings and the control blocks now, not at the next poll.
  virtual void ring() noexcept = 0;
  virtual const Status& status() const noexcept = 0;

  // --- Reports (any thread) ---
  // Lateness of the output's writes against their slipped planned times (the error it adds).
  virtual const LatenessStats& stats() const noexcept = 0;
  // Trace records lost because the trace ring was full (gpio::TraceWriter::watch_losses).
  virtual const std::atomic<std::uint64_t>& trace_dropped_counter() const noexcept = 0;
  std::uint64_t trace_dropped() const noexcept {
    return trace_dropped_counter().load(std::memory_order_relaxed);
  }
  // Liveness: grows while the output's thread runs (the systemd watchdog is petted on it).
  virtual std::uint64_t loops() const noexcept = 0;
  // The thread's sleeps so far, and of those the short polls of a starved ring (log lines).
  virtual std::uint64_t sleeps() const noexcept = 0;
  virtual std::uint64_t starved_polls() const noexcept = 0;
  // What the output costs a CPU: edges closer than stay_on_cpu_gap() keep its thread on its CPU
  // (the daemon's "needs a CPU of its own" notice); spin_now() is how early it wakes before an
  // edge, wake_p99() its measured wake-up lateness. All 0 for an output that does not wake per
  // edge (0 = no notice).
  virtual Nanos stay_on_cpu_gap() const noexcept = 0;
  virtual Nanos spin_now() const noexcept = 0;
  virtual Nanos wake_p99() const noexcept = 0;

  // --- Virtual time (tests, simulations; never while running) ---
  // The clock the output stamps writes it makes on its own with (an immediate stop's).
  virtual void set_clock(ClockFn clock) noexcept = 0;
  // Applies what the control blocks ask (immediate stops, caps, cuts) and answers when the next
  // line change is due, or kNever.
  virtual Nanos next_due() noexcept = 0;
  // Makes the change next_due() found, stamped `now` (its lateness is now - its due time).
  virtual void execute_one(Nanos now) noexcept = 0;
};

}  // namespace stepmod::rt
