#pragma once
// The pulse thread's doorbell. The pulse thread sleeps until its next edge
// (rt::StepOutput::Options::quiet_sleep_ns) rather than polling; after the control thread may
// have submitted commands (an immediate stop is submitted too), it is rung so that it polls for
// the new edges at once, and again once the planner has planned them (planner/output_doorbell.hpp
// says why). Control thread.
#include "planner/output_doorbell.hpp"
#include "planner/planner.hpp"
#include "rt/step_output.hpp"

namespace stepmod::tools {

class PulseDoorbell {
 public:
  // Before the planner thread starts (the counter read here is its starting value).
  PulseDoorbell(planner::Planner& planner, rt::StepOutput& pulse) noexcept
      : due_(planner), pulse_(pulse) {}

  void ring_if_submitted() noexcept {
    if (due_.due()) pulse_.ring();
  }

 private:
  planner::OutputDoorbell due_;
  rt::StepOutput& pulse_;
};

}  // namespace stepmod::tools
