#include "daemon/unit_state_publisher.hpp"

#include <algorithm>

namespace stepmod::tools {

UnitStatePublisher::UnitStatePublisher(const ModuleShape& shape, const gpio::Backend& backend)
    : shape_(shape) {
  for (unsigned a = 0; a < std::min<unsigned>(shape.axes, 2); ++a) {
    std::uint32_t wired = 0;
    for (unsigned i = 0; i < kPanelInputs; ++i) {
      if (backend.has_input(a, static_cast<InputLine>(i))) wired |= 1u << i;
    }
    units_[a].state.inputs = wired << STEPMOD_UNIT_WIRED_SHIFT;
  }
}

void UnitStatePublisher::scan(const module::Personality& personality, const ImageWords& out,
                              const std::array<Enable, 2>& enables, ipc::ShmImage& image) {
  const unsigned per_unit = shape_.output_words / std::max(1u, shape_.axes);
  for (unsigned a = 0; a < std::min<unsigned>(shape_.axes, 2); ++a) {
    Unit& u = units_[a];
    const bool config_mode = personality.drive_state(a).configuration_mode;
    if (config_mode) {
      // The words this configuration scan evaluated: the ones the axis takes if it leaves now.
      for (unsigned i = 0; i < u.config_scan.size(); ++i) {
        u.config_scan[i] = i < per_unit ? out.w[a * per_unit + i] : 0;
      }
    } else if (u.in_config) {
      std::copy(u.config_scan.begin(), u.config_scan.end(), u.state.config_words);
      ++u.state.config_seq;
    }
    u.in_config = config_mode;
    const module::Personality::InputLines lines = personality.input_lines(a);
    constexpr std::uint32_t kWiredMask = 0xFFu << STEPMOD_UNIT_WIRED_SHIFT;
    u.state.inputs = (u.state.inputs & kWiredMask) |
                     (std::uint32_t{lines.levels} << STEPMOD_UNIT_LEVELS_SHIFT) |
                     (std::uint32_t{lines.used} << STEPMOD_UNIT_USED_SHIFT) |
                     (std::uint32_t{lines.active} << STEPMOD_UNIT_ACTIVE_SHIFT);
    u.state.drive_enable = (enables[a].wired ? STEPMOD_UNIT_ENABLE_WIRED : 0u) |
                           (enables[a].asserted ? STEPMOD_UNIT_ENABLE_ASSERTED : 0u);
    image.set_unit_state(a, u.state);
  }
}

}  // namespace stepmod::tools
