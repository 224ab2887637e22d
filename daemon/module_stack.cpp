#include "daemon/module_stack.hpp"

#include <stdexcept>

#include "registry/module_registry.hpp"

namespace stepmod::tools {

ModuleStack::ModuleStack(const StackOptions& options, gpio::Backend& backend)
    : backend_(backend), module_io_(backend), shape_(shape_of(options.type)) {
  if (options.timing.size() != shape_.axes || backend.axes() != shape_.axes) {
    throw std::invalid_argument("the module, its timing and its backend disagree on the axes");
  }
  std::vector<planner::PlannerAxis> planner_axes;
  for (unsigned i = 0; i < shape_.axes; ++i) {
    auto& a = axes_.emplace_back(std::make_unique<AxisPipeline>(options.edge_ring));
    planner_axes.push_back({&a->edges, &a->control, options.timing[i], &a->feedback});
  }
  planner_ = std::make_unique<planner::Planner>(planner_axes, options.planner);
  std::vector<planner::MotionPort*> ports;
  for (unsigned i = 0; i < shape_.axes; ++i) {
    AxisPipeline& a = *axes_[i];
    a.port = std::make_unique<planner::MotionPort>(i, *planner_, a.feedback, a.control, a.history);
    ports.push_back(a.port.get());
  }
  personality_ = registry::make_personality(options.type, module_io_, ports);
}

ModuleStack::~ModuleStack() = default;

std::vector<rt::AxisLink> ModuleStack::links() noexcept {
  std::vector<rt::AxisLink> links;
  for (auto& a : axes_) links.push_back({&a->edges, &a->feedback, &a->control, &a->history});
  return links;
}

}  // namespace stepmod::tools
