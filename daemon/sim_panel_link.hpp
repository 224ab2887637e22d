#pragma once
// The simulator panel (docs/interface.md section 4) wired to the simulated machine: a panel's
// forced inputs go into the machine, and the machine's motors, encoders and output levels come
// back to the panel. Only with [gpio] backend = "sim". Control thread.
#include <string>

#include "ipc/sim_panel.hpp"

namespace stepmod::gpio {
class SimBackend;
}

namespace stepmod::tools {

class SimPanelLink {
 public:
  // Creates the panel's shared memory (throws ipc::IpcError as SimPanelServer does).
  SimPanelLink(const std::string& name, gpio::SimBackend& sim, unsigned axes);

  // At every wake, so that a forced edge is an input event at once.
  void take_forces();
  // Once per scan, and after the last motion has stopped.
  void publish();

 private:
  gpio::SimBackend& sim_;
  ipc::SimPanelServer server_;
  unsigned axes_;
};

}  // namespace stepmod::tools
