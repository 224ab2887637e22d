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
#include "ipc/health.hpp"

namespace stepmod::tools {

class ModuleTrace;
class ModuleStack;

class ChargePumpFeed {
 public:
  // `trace` may be null (no --trace).
  ChargePumpFeed(ModuleStack& stack, const Config& config, ModuleTrace* trace);

  // After each module scan, with the health words it publishes.
  void scan(const ipc::Health& health, Nanos now);
  // The control loop has ended (a stop): the line inactive for good.
  void stop(Nanos now);

  // Which health flags stop the pump: every one that stops the axes, and a lost trace.
  static ChargePump::Conditions conditions(std::uint32_t health_flags, bool estop) noexcept;

  // A late-edge fault or lost input events is an event, not a state: the axes it cut stand still
  // at once, while its health bit (0, 5) stands until the PLC's next accepted motion. The pump
  // stops for kDrop from each new fault (every watchdog relay board has dropped by then, opening
  // the E-stop chain), then runs again with the bit still set: the operator's Reset of the chain
  // re-enables the drives, not a motion the PLC would have to issue to unpowered drives to clear
  // the bit (docs/safety.md, "Charge pump").
  class FaultDrop {
   public:
    static constexpr Nanos kDrop = 1'000 * kNsPerMs;
    // Whether the pump must stay stopped for a fault, after a scan that published `health`.
    bool stops(const ipc::Health& health, Nanos now) noexcept;

   private:
    std::uint32_t bits_ = 0;
    std::uint32_t late_faults_ = 0;
    Nanos at_ = 0;  // the newest fault (read only while a fault bit stands: one rose since)
  };

 private:
  void record_change();

  ModuleStack& stack_;
  ModuleTrace* trace_;
  FaultDrop fault_;
  std::optional<ChargePump> pump_;
};

}  // namespace stepmod::tools
