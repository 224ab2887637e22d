#pragma once
// Electrical options of one GPIO line (the `[axis.lines.<key>]` config tables): what a real
// wiring needs besides the offset. Backends apply them (gpiod: as line request flags; sim: in
// its simulated wires).
#include <cstdint>
#include <string_view>

namespace stepmod::gpio {

enum class Bias : std::uint8_t { kAsIs, kPullUp, kPullDown, kDisabled };  // inputs
enum class Drive : std::uint8_t { kPushPull, kOpenDrain, kOpenSource };   // outputs

struct LineOptions {
  Bias bias = Bias::kAsIs;
  Drive drive = Drive::kPushPull;
  // The line's active (logical) level is electrical low: stepmod's "high" (step pulse, input
  // asserted) is a low wire. The kernel inverts values and edge directions.
  bool active_low = false;
  std::uint32_t debounce_us = 0;  // inputs; 0 = none. Kernel debounce: libgpiod 2 only.
};

std::string_view bias_name(Bias b) noexcept;
std::string_view drive_name(Drive d) noexcept;

// What the libgpiod this build uses can do (the backend source file CMake selected answers).
struct GpiodCapabilities {
  int libgpiod_major = 0;  // 1 (1.6, v1 uAPI) or 2 (2.x, v2 uAPI)
  bool debounce = false;   // per-line kernel debounce (v2 uAPI)
};
GpiodCapabilities gpiod_capabilities() noexcept;

}  // namespace stepmod::gpio
