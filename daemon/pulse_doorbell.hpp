#pragma once
// The pulse thread's doorbell. The pulse thread sleeps until its next edge
// (rt::StepOutput::Options::quiet_sleep_ns) rather than polling; after the control thread may
// have submitted commands (an immediate stop is submitted too), it is rung so that it polls for
// the new edges at once. Rung only when the planner's wake counter moved. Control thread.
#include <atomic>
#include <cstdint>

#include "planner/planner.hpp"
#include "rt/step_output.hpp"

namespace stepmod::tools {

class PulseDoorbell {
 public:
  // Before the planner thread starts (the counter read here is its starting value).
  PulseDoorbell(planner::Planner& planner, rt::StepOutput& pulse) noexcept
      : planner_(planner), pulse_(pulse), seen_(planner.wake_counter().load()) {}

  void ring_if_submitted() noexcept {
    const std::uint32_t w = planner_.wake_counter().load(std::memory_order_acquire);
    if (w == seen_) return;
    seen_ = w;
    pulse_.ring();
  }

 private:
  planner::Planner& planner_;
  rt::StepOutput& pulse_;
  std::uint32_t seen_;
};

}  // namespace stepmod::tools
