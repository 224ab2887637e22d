#pragma once
// One module of the running rack, what it shows the world under its own name: its shared-memory
// image (/dev/shm/stepmod.NAME), its simulator panel (the "sim" backend only) and its control
// loop, with its way into the rack's trace. (Its Modbus registers are served by the rack's
// server on its listen address: daemon/modbus_servers.hpp; its EtherNet/IP adapter:
// daemon/enip_adapters.hpp.) Built on the main thread; the control loop then runs on the
// module's control thread (daemon.cpp).
#include <atomic>
#include <memory>

#include "config/config.hpp"
#include "daemon/control_loop.hpp"
#include "daemon/daemon_trace.hpp"
#include "daemon/sim_panel_link.hpp"
#include "ipc/shm_image.hpp"

namespace stepmod::gpio {
class SimBackend;
}

namespace stepmod::tools {

class ModuleStack;

class ModuleRuntime {
 public:
  // What a module runs on; all of it outlives the module. `sim` and `trace` may be null.
  struct Parts {
    const Config& config;
    ModuleStack& stack;
    rt::StepOutput& output;
    gpio::SimBackend* sim;
    DaemonTrace* trace;
    unsigned first_axis;  // the step output's number of the module's first axis
  };
  // Throws std::runtime_error (ipc::IpcError: the shared memory).
  explicit ModuleRuntime(const Parts& parts);
  ~ModuleRuntime();
  ModuleRuntime(const ModuleRuntime&) = delete;
  ModuleRuntime& operator=(const ModuleRuntime&) = delete;

  const Config& config() const noexcept { return config_; }
  ControlLoop& control() noexcept { return *control_; }
  ipc::ShmImage& image() noexcept { return *image_; }
  // Set by the module's EtherNet/IP adapter while its owner PLC is out of Run; read by the
  // control loop each scan (the deadman: daemon/enip_adapters.hpp).
  std::atomic<bool>& plc_not_in_run() noexcept { return plc_not_in_run_; }

 private:
  const Config& config_;
  std::atomic<bool> plc_not_in_run_{false};
  std::unique_ptr<ModuleTrace> trace_;  // --trace
  std::unique_ptr<ipc::ShmImage> image_;
  std::unique_ptr<SimPanelLink> panel_;   // the "sim" backend only
  std::unique_ptr<ControlLoop> control_;  // last: destroyed before what it works on
};

}  // namespace stepmod::tools
