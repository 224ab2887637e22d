#include "daemon/backend_factory.hpp"

#include <vector>

#include "gpio/gpiod_backend.hpp"
#include "gpio/sim_backend.hpp"

namespace stepmod::tools {

std::vector<gpio::AxisLines> module_lines(const Config& config) {
  std::vector<gpio::AxisLines> lines(config.axes.begin(), config.axes.end());
  if (!lines.empty()) {
    lines.front().charge_pump = config.charge_pump.line;
    lines.front().charge_pump_opt = config.charge_pump.line_opt;
  }
  return lines;
}

BuiltBackend make_backend(const Config& config) {
  const std::vector<gpio::AxisLines> lines = module_lines(config);
  if (config.backend == Config::Backend::kGpiod) {
    return {std::make_unique<gpio::GpiodBackend>(config.chip, lines), nullptr};
  }
  std::vector<gpio::SimAxisSetup> axes;
  for (std::size_t a = 0; a < lines.size(); ++a) axes.push_back({lines[a], config.axes[a].sim});
  auto sim = std::make_unique<gpio::SimBackend>(axes);
  gpio::SimBackend* panel_side = sim.get();
  return {std::move(sim), panel_side};
}

}  // namespace stepmod::tools
