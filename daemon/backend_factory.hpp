#pragma once
// Builds the GPIO backend a configuration asks for ([gpio] backend = "sim" | "gpiod").
#include <memory>

#include "gpio/backend.hpp"
#include "config/config.hpp"

namespace stepmod::tools {

// Throws std::runtime_error naming the chip and line when a gpiod line cannot be had.
std::unique_ptr<gpio::Backend> make_backend(const Config& config);

}  // namespace stepmod::tools
