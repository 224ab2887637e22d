#pragma once
// The charge pump (daemon/charge_pump.hpp) fed after each scan from what the scan publishes: the
// health flags (a late-edge fault, lost inputs, the PLC lost, an expired lease, a lost trace)
// and the axes' E-stop inputs; stopped when the control loop ends. Every change of its line goes
// into the trace as the VCD's charge_pump wire. Control thread. Nothing without [charge_pump].
#include <cstdint>
#include <optional>

#include "config/config.hpp"
#include "core/clock.hpp"
#include "daemon/charge_pump.hpp"

namespace stepmod::tools {

class ModuleTrace;
class ModuleStack;

class ChargePumpFeed {
 public:
  // `trace` may be null (no --trace).
  ChargePumpFeed(ModuleStack& stack, const Config& config, ModuleTrace* trace);

  // After each module scan, with the health flags it publishes (STEPMOD_HEALTH_*).
  void scan(std::uint32_t health_flags, Nanos now);
  // The control loop has ended (a stop): the line inactive for good.
  void stop(Nanos now);

  // Which health flags stop the pump: every one that stops the axes, and a lost trace.
  static ChargePump::Conditions conditions(std::uint32_t health_flags, bool estop) noexcept;

 private:
  void record_change();

  ModuleStack& stack_;
  ModuleTrace* trace_;
  std::optional<ChargePump> pump_;
};

}  // namespace stepmod::tools
