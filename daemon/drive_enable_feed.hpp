#pragma once
// The drive-enable outputs (drive_enable.hpp) fed from the module and the motion after each
// scan: each axis' configuration, E-stop, faults (a late-edge fault, lost inputs) and the PLC's
// loss; every change of an enable line goes into the trace as the VCD's axis<N>.enable wire.
// Control thread.
#include "config/config.hpp"
#include "core/clock.hpp"
#include "daemon/drive_enable.hpp"
#include "daemon/unit_state_publisher.hpp"

namespace stepmod::tools {

class ModuleTrace;
class LostInputWatch;
class ModuleStack;

class DriveEnableFeed {
 public:
  // `trace` may be null (no --trace).
  DriveEnableFeed(ModuleStack& stack, const Config& config, const LostInputWatch& lost_inputs,
                  ModuleTrace* trace);

  // Whether a drive enabled a moment ago is not ready yet (the module keeps its previous words).
  bool holding(Nanos now) const noexcept { return enable_.holding(now); }
  // After each module scan.
  void scan(bool plc_lost, Nanos now);
  // Each axis' enable line: wired, and asserted now (docs/interface.md 3.6).
  std::array<UnitStatePublisher::Enable, 2> states() const noexcept;
  // After the control loop, as the daemon idles every output: the asserted enables' release.
  void trace_release(Nanos now) noexcept;

 private:
  ModuleStack& stack_;
  const LostInputWatch& lost_inputs_;
  ModuleTrace* trace_;
  DriveEnable enable_;
};

}  // namespace stepmod::tools
