#pragma once
// The configuration bits that the 3601 (its configuration MSW) and the 3202 (its configuration
// DINT) name alike, in both manuals' ch. 3: the six inputs' "used" bits, the backplane proximity,
// the feedback, output and homing options. Each module's table holds them at its own positions
// (module_types/m3601/words_3601.hpp kConfigMswBits, module_types/m3202/words_3202.hpp
// kConfigBits); these masks are looked up in it by name, so the emulator's checks
// (module/shared/invalid_configs.hpp) and stepmodctl's configure (tools/ctl_args.hpp) name each
// bit once. The 3602 names its bits otherwise (an input function field per limit) and has its own.
#include <cstdint>

#include "core/bit_table.hpp"

namespace stepmod::words {

struct SharedConfigMasks {
  std::uint32_t capture, external, home, estop, cw_limit, ccw_limit;  // "used", InputLine order
  std::uint32_t proximity, encoder, diagnostic, step_dir, marker;

  constexpr std::uint32_t end_limits() const noexcept { return cw_limit | ccw_limit; }
};

template <typename Table>
consteval SharedConfigMasks shared_config_masks(const Table& t) {
  // Direct calls, no helper lambda: clang (clang-tidy) refuses a consteval lambda's call with a
  // captured parameter as "not a constant expression"; the body of a consteval function is not.
  using W = std::uint32_t;
  return {mask_of<W>(t, "Capture Input Used"),
          mask_of<W>(t, "External Input Used"),
          mask_of<W>(t, "Home Input Used"),
          mask_of<W>(t, "E-Stop Input Used"),
          mask_of<W>(t, "CW Limit Used"),
          mask_of<W>(t, "CCW Limit Used"),
          mask_of<W>(t, "Backplane Home Proximity"),
          mask_of<W>(t, "Quadrature Encoder"),
          mask_of<W>(t, "Diagnostic Feedback"),
          mask_of<W>(t, "Step+Direction Output (0 = CW/CCW)"),
          mask_of<W>(t, "Marker Homing (0 = home switch)")};
}

}  // namespace stepmod::words
