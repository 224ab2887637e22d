#include <stdexcept>

#include "module/m3202/module_3202.hpp"
#include "module/m3601/module_3601.hpp"
#include "module/m3602/module_3602.hpp"
#include "module/personality.hpp"

namespace stepmod::module {

std::unique_ptr<Personality> make_personality(ModuleType type, gpio::Backend& backend,
                                              std::span<planner::MotionPort* const> axes) {
  if (axes.size() != shape_of(type).axes) {
    throw std::invalid_argument("module needs one motion port per axis");
  }
  switch (type) {
    case ModuleType::k3601:
      return std::make_unique<m3601::Module3601>(backend, *axes[0]);
    case ModuleType::k3602:
      return std::make_unique<m3602::Module3602>(backend, *axes[0], *axes[1]);
    case ModuleType::k3202:
      return std::make_unique<m3202::Module3202>(backend, *axes[0], *axes[1]);
  }
  throw std::invalid_argument("unknown module type " +
                              std::to_string(static_cast<unsigned>(type)));
}

}  // namespace stepmod::module
