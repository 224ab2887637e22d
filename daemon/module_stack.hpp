#pragma once
// One module of the rack, wired but without threads: its per-axis edge rings, step-output
// feedback and control blocks, its planner, its motion ports and its personality. The step
// output that drains its rings is the rack's (daemon/stack.hpp), one for every module.
#include <memory>
#include <vector>

#include "core/spsc_ring.hpp"
#include "daemon/module_io.hpp"
#include "daemon/stack_options.hpp"
#include "gpio/backend.hpp"
#include "module/personality.hpp"
#include "planner/motion_port.hpp"
#include "planner/planner.hpp"
#include "rt/axis_feedback.hpp"

namespace stepmod::tools {

class ModuleStack {
 public:
  // `backend` (the module's own lines) must outlive the module.
  ModuleStack(const StackOptions& options, gpio::Backend& backend);
  ~ModuleStack();
  ModuleStack(const ModuleStack&) = delete;
  ModuleStack& operator=(const ModuleStack&) = delete;

  gpio::Backend& backend() noexcept { return backend_; }
  planner::Planner& planner() noexcept { return *planner_; }
  module::Personality& personality() noexcept { return *personality_; }
  const ModuleShape& shape() const noexcept { return shape_; }
  planner::MotionPort& motion(unsigned axis) noexcept { return *axes_[axis]->port; }
  const rt::AxisFeedback& feedback(unsigned axis) const noexcept { return axes_[axis]->feedback; }
  // What the step output is given of each axis (rt::StepOutputWiring), in axis order.
  std::vector<rt::AxisLink> links() noexcept;

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
  std::unique_ptr<module::Personality> personality_;
};

}  // namespace stepmod::tools
