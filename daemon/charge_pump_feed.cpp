#include "daemon/charge_pump_feed.hpp"

#include "daemon/daemon_trace.hpp"
#include "daemon/module_stack.hpp"
#include "gpio/vcd_trace.hpp"
#include "ipc/stepmod_image.h"

namespace stepmod::tools {

ChargePumpFeed::ChargePumpFeed(ModuleStack& stack, const Config& config, ModuleTrace* trace)
    : stack_(stack), trace_(trace) {
  const ChargePumpSection& c = config.charge_pump;
  if (!c.line) return;
  // On the module's first axis' lines (daemon/backend_factory.cpp).
  pump_.emplace(stack.backend(), ChargePump::Setup{0, c.half_period_scans, c.frequency_hz},
                &monotonic_now);
}

ChargePump::Conditions ChargePumpFeed::conditions(std::uint32_t health_flags, bool estop) noexcept {
  ChargePump::Conditions c;
  c.estop = estop;
  c.fault = (health_flags & (STEPMOD_HEALTH_LATE_EDGE | STEPMOD_HEALTH_INPUT_LOST)) != 0;
  c.plc_lost = (health_flags & (STEPMOD_HEALTH_PLC_STALE | STEPMOD_HEALTH_SEQ_STUCK)) != 0;
  c.lease_expired = (health_flags & STEPMOD_HEALTH_LEASE_EXPIRED) != 0;
  c.trace_lost = (health_flags & STEPMOD_HEALTH_TRACE_LOST) != 0;
  return c;
}

bool ChargePumpFeed::FaultDrop::stops(const ipc::Health& health, Nanos now) noexcept {
  const std::uint32_t bits = health.flags & (STEPMOD_HEALTH_LATE_EDGE | STEPMOD_HEALTH_INPUT_LOST);
  // A new fault: a bit rising, or one more late-edge fault while bit 0 stands.
  if (bits != 0 && ((bits & ~bits_) != 0 || health.late_faults != late_faults_)) at_ = now;
  bits_ = bits;
  late_faults_ = health.late_faults;
  return bits != 0 && now - at_ < kDrop;
}

void ChargePumpFeed::scan(const ipc::Health& health, Nanos now) {
  if (!pump_) return;
  bool estop = false;
  for (unsigned a = 0; a < stack_.shape().axes; ++a) {
    estop = estop || stack_.personality().drive_state(a).estop;
  }
  ChargePump::Conditions c = conditions(health.flags, estop);
  c.fault = fault_.stops(health, now);
  if (pump_->scan(c, now)) record_change();
}

void ChargePumpFeed::stop(Nanos now) {
  if (pump_ && pump_->stop(now)) record_change();
}

void ChargePumpFeed::record_change() {
  if (trace_ == nullptr) return;
  trace_->record_input({pump_->changed_at(), 0, gpio::kChargePumpTraceLine,
                        static_cast<std::uint8_t>(pump_->level() ? 1 : 0), 0});
}

}  // namespace stepmod::tools
