#pragma once
// One emulated module's whole motion stack, wired but without threads: per-axis edge rings,
// step-output feedback and control, the planner, the step output (rt/step_output.hpp; made by
// name, not started) and the module personality.
// The daemon drives it with its threads (daemon.cpp); tests drive the very same objects in
// virtual time (tests/support/virtual_machine.hpp).
#include <memory>
#include <string>
#include <vector>

#include "core/spsc_ring.hpp"
#include "core/trace_record.hpp"
#include "daemon/module_io.hpp"
#include "gpio/backend.hpp"
#include "module/personality.hpp"
#include "planner/motion_port.hpp"
#include "planner/planner.hpp"
#include "rt/axis_feedback.hpp"
#include "rt/step_output.hpp"
#include "rt/step_output_factory.hpp"

namespace stepmod::tools {

struct StackOptions {
  ModuleType type = ModuleType::k3601;
  std::vector<planner::AxisTiming> timing;  // one per axis
  planner::PlannerOptions planner;
  std::size_t edge_ring = 1u << 15;  // edges per axis: > lookahead x max edge rate (2 MHz x 4 ms)
  Nanos late_limit_ns = 0;           // late-edge guard (rt::StepOutput::set_late_limit); 0 = off
  std::vector<std::uint32_t>
      lag_limit_steps;  // per axis (rt::StepOutput::set_lag_limit); none/0 = off
  std::string step_output{rt::kPulseThreadOutput};  // rt::make_step_output's name
};

class Stack {
 public:
  // `backend` and `trace` (may be null) must outlive the stack.
  Stack(const StackOptions& options, gpio::Backend& backend, SpscRing<TraceRecord>* trace);
  ~Stack();
  Stack(const Stack&) = delete;
  Stack& operator=(const Stack&) = delete;

  gpio::Backend& backend() noexcept { return backend_; }
  planner::Planner& planner() noexcept { return *planner_; }
  rt::StepOutput& output() noexcept { return *output_; }
  module::Personality& personality() noexcept { return *personality_; }
  const ModuleShape& shape() const noexcept { return shape_; }
  planner::MotionPort& motion(unsigned axis) noexcept { return *axes_[axis]->port; }
  const rt::AxisFeedback& feedback(unsigned axis) const noexcept { return axes_[axis]->feedback; }

 private:
  // One axis' way from the planner to the step output: its edge ring, feedback and motion port.
  struct AxisPipeline {
    explicit AxisPipeline(std::size_t ring) : edges(ring) {}
    SpscRing<rt::Edge> edges;
    rt::AxisFeedback feedback;
    rt::AxisControl control;
    rt::StepHistory history;
    std::unique_ptr<planner::MotionPort> port;
  };

  gpio::Backend& backend_;
  BackendAxisIo module_io_;  // the module's view of backend_: start-up levels, pulse format
  ModuleShape shape_;
  std::vector<std::unique_ptr<AxisPipeline>> axes_;  // stable addresses: the threads hold pointers
  std::unique_ptr<planner::Planner> planner_;
  // After the axes: destroyed (its thread stopped) before the rings and blocks it reads.
  std::unique_ptr<rt::StepOutput> output_;
  std::unique_ptr<module::Personality> personality_;
};

}  // namespace stepmod::tools
