#include "daemon/backend_factory.hpp"

#include <vector>

#include "gpio/gpiod_backend.hpp"
#include "gpio/sim_backend.hpp"

namespace stepmod::tools {

BuiltBackend make_backend(const Config& config) {
  if (config.backend == Config::Backend::kGpiod) {
    std::vector<gpio::AxisLines> lines(config.axes.begin(), config.axes.end());
    return {std::make_unique<gpio::GpiodBackend>(config.chip, lines), nullptr};
  }
  std::vector<gpio::SimAxisSetup> axes;
  for (const AxisSection& a : config.axes) axes.push_back({a, a.sim});
  auto sim = std::make_unique<gpio::SimBackend>(axes);
  gpio::SimBackend* panel_side = sim.get();
  return {std::move(sim), panel_side};
}

}  // namespace stepmod::tools
