#include "daemon/module_runtime.hpp"

#include <spdlog/spdlog.h>

#include "daemon/module_stack.hpp"

namespace stepmod::tools {

ModuleRuntime::ModuleRuntime(const Parts& parts) : config_(parts.config) {
  if (parts.trace != nullptr) {
    trace_ = std::make_unique<ModuleTrace>(*parts.trace, parts.first_axis);
  }
  image_ = std::make_unique<ipc::ShmImage>(config_.name, parts.stack.shape());
  // A crashed daemon's image is replaced silently by ShmImage; say what was there (a PLC still
  // attached to it would have been talking to nobody).
  if (const std::string old = image_->replaced_description(); !old.empty()) {
    spdlog::warn("replaced {}", old);
  }
  if (parts.sim != nullptr) {
    panel_ = std::make_unique<SimPanelLink>(config_.name, *parts.sim, parts.stack.shape().axes);
  }
  control_ = std::make_unique<ControlLoop>(ControlLoop::Parts{
      config_, parts.stack, parts.output, *image_, trace_.get(), panel_.get(), &plc_not_in_run_});
}

ModuleRuntime::~ModuleRuntime() = default;

}  // namespace stepmod::tools
