#include "tools/backend_factory.hpp"

#include <vector>

#include "gpio/gpiod_backend.hpp"
#include "gpio/sim_backend.hpp"

namespace stepmod::tools {

std::unique_ptr<gpio::Backend> make_backend(const Config& config) {
  if (config.backend == Config::Backend::kGpiod) {
    std::vector<gpio::AxisLines> lines(config.axes.begin(), config.axes.end());
    return std::make_unique<gpio::GpiodBackend>(config.chip, lines);
  }
  std::vector<gpio::SimAxisSetup> axes;
  for (const AxisSection& a : config.axes) axes.push_back({a, a.sim});
  return std::make_unique<gpio::SimBackend>(axes);
}

}  // namespace stepmod::tools
