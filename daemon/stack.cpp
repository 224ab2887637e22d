#include "daemon/stack.hpp"

#include <stdexcept>

#include "daemon/rack_lines.hpp"

namespace stepmod::tools {

Stack::Stack(std::span<const StackModule> modules, SpscRing<TraceRecord>* trace) {
  if (modules.empty()) throw std::invalid_argument("a stack needs a module");
  std::vector<rt::AxisLink> links;
  std::vector<gpio::Backend*> backends;
  for (const StackModule& m : modules) {
    first_axis_.push_back(static_cast<unsigned>(links.size()));
    ModuleStack& s = *modules_.emplace_back(std::make_unique<ModuleStack>(m.options, *m.backend));
    for (const rt::AxisLink& l : s.links()) links.push_back(l);
    backends.push_back(m.backend);
  }
  // A lone module's step output writes its backend directly: no look-up on the way.
  gpio::Backend* lines = backends.front();
  if (backends.size() > 1) {
    rack_lines_ = std::make_unique<RackLines>(backends);
    lines = rack_lines_.get();
  }
  const StackOptions& first = modules.front().options;
  output_ = rt::make_step_output(first.step_output, {*lines, links, trace});
  output_->set_late_limit(first.late_limit_ns);
  for (std::size_t k = 0; k < modules.size(); ++k) {
    const auto& lag = modules[k].options.lag_limit_steps;
    for (unsigned i = 0; i < lag.size() && i < modules_[k]->shape().axes; ++i) {
      output_->set_lag_limit(first_axis_[k] + i, lag[i]);
    }
  }
}

Stack::~Stack() = default;

}  // namespace stepmod::tools
