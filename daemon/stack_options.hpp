#pragma once
// How one module's stack is built (daemon/module_stack.hpp), and the step output over the rack
// (daemon/stack.hpp), whose keys a rack takes from its first module: the rack's [rt] gives every
// module the same.
#include <cstdint>
#include <string>
#include <vector>

#include "core/module_shape.hpp"
#include "planner/planner.hpp"
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

}  // namespace stepmod::tools
