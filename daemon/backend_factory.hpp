#pragma once
// Builds the GPIO backend a configuration asks for ([gpio] backend = "sim" | "gpiod").
#include <memory>
#include <vector>

#include "config/config.hpp"
#include "gpio/backend.hpp"

namespace stepmod::gpio {
class SimBackend;
}

namespace stepmod::tools {

// What make_backend built. The simulated machine is handed out by its own type as well: the
// daemon wires the simulator panel to it (forced inputs, the motors' positions), which is no
// part of the Backend interface since a real chip has nothing of the kind.
struct BuiltBackend {
  std::unique_ptr<gpio::Backend> backend;
  gpio::SimBackend* sim = nullptr;  // `backend` itself when it is the simulator; else null
};

// The module's lines as a backend takes them, axis by axis; its charge pump on the first axis'
// (gpio/axis_lines.hpp).
std::vector<gpio::AxisLines> module_lines(const Config& config);

// Throws std::runtime_error naming the chip and line when a gpiod line cannot be had.
BuiltBackend make_backend(const Config& config);

}  // namespace stepmod::tools
