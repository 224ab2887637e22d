#pragma once
// The control thread's end of the unit-state blocks (docs/interface.md 3.6): after each scan,
// per axis/channel, the configuration words it took on leaving configuration mode, its input
// lines (level, wired, used, active) and its drive enable, handed to the image for the next input
// publication. What a console reads back: the module's words alone cannot say it once the axis
// is back in command mode.
#include <array>
#include <cstdint>

#include "core/module_shape.hpp"
#include "gpio/backend.hpp"
#include "ipc/shm_image.hpp"
#include "module/personality.hpp"

namespace stepmod::tools {

class UnitStatePublisher {
 public:
  // Per axis: whether a drive-enable line is wired and asserted now.
  struct Enable {
    bool wired = false;
    bool asserted = false;
  };

  UnitStatePublisher(const ModuleShape& shape, const gpio::Backend& backend);

  // After each scan: `out` the words the module scanned, `enables` the drive enables now.
  void scan(const module::Personality& personality, const ImageWords& out,
            const std::array<Enable, 2>& enables, ipc::ShmImage& image);

 private:
  struct Unit {
    bool in_config = false;
    std::array<std::int32_t, STEPMOD_UNIT_CONFIG_WORDS> config_scan{};  // last config scan's words
    stepmod_unit_state_t state{};
  };
  ModuleShape shape_;
  std::array<Unit, 2> units_{};
};

}  // namespace stepmod::tools
