#pragma once
// The first step output (rt/step_output.hpp): the pulse engine on the pulse thread. Each edge is
// written "now" through gpio::Backend at its slipped planned time by a SCHED_FIFO thread that
// sleeps to shortly before it and spins to it (rt/pulse_thread.hpp). The thread's loop calls the
// engine directly (no virtual call per edge); this class only adapts the control side's verbs.
#include <optional>

#include "rt/pulse_engine.hpp"
#include "rt/pulse_thread.hpp"
#include "rt/step_output.hpp"

namespace stepmod::rt {

class PulseThreadOutput final : public StepOutput {
 public:
  explicit PulseThreadOutput(const StepOutputWiring& wiring)
      : engine_(wiring.backend, wiring.axes, wiring.trace) {}
  ~PulseThreadOutput() override { stop(); }

  void set_late_limit(Nanos limit) noexcept override { engine_.set_late_limit(limit); }
  void set_lag_limit(unsigned axis, std::uint32_t steps) noexcept override {
    engine_.set_lag_limit(axis, steps);
  }

  bool start(const Options& options) override;
  void stop() override;
  bool running() const noexcept override { return thread_ && thread_->running(); }
  void ring() noexcept override {
    if (thread_) thread_->ring();
  }
  const Status& status() const noexcept override { return thread_ ? thread_->status() : idle_; }

  const LatenessStats& stats() const noexcept override { return engine_.stats(); }
  const std::atomic<std::uint64_t>& trace_dropped_counter() const noexcept override {
    return engine_.trace_dropped_counter();
  }
  std::uint64_t loops() const noexcept override { return thread_ ? thread_->loops() : 0; }
  std::uint64_t sleeps() const noexcept override { return thread_ ? thread_->sleeps() : 0; }
  std::uint64_t starved_polls() const noexcept override {
    return thread_ ? thread_->starved_polls() : 0;
  }
  Nanos stay_on_cpu_gap() const noexcept override {
    return thread_ ? thread_->stay_on_cpu_gap() : 0;
  }
  Nanos spin_now() const noexcept override { return thread_ ? thread_->spin_now() : 0; }
  Nanos wake_p99() const noexcept override { return thread_ ? thread_->wake_p99() : 0; }

  void set_clock(ClockFn clock) noexcept override { engine_.set_clock(clock); }
  Nanos next_due() noexcept override { return engine_.next_due(); }
  void execute_one(Nanos now) noexcept override { engine_.execute_one(now); }

 private:
  PulseEngine engine_;
  // Made by start() with its options (a PulseThread's are fixed); kept after stop() so that its
  // counters can still be read.
  std::optional<PulseThread> thread_;
  Status idle_;  // status() before the first start()
};

}  // namespace stepmod::rt
