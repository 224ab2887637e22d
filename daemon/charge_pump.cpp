#include "daemon/charge_pump.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace stepmod::tools {

ChargePump::ChargePump(gpio::Backend& backend, const Setup& setup, Nanos (*clock)())
    : backend_(backend), setup_(setup), clock_(clock) {
  setup_.half_period_scans = std::max(setup_.half_period_scans, 1u);
}

const char* ChargePump::stop_reason(const Conditions& c) noexcept {
  if (c.estop) return "E-stop input active";
  if (c.fault) return "fault: a late edge or lost input events stopped an axis";
  if (c.plc_lost) return "PLC lost";
  if (c.lease_expired) return "commissioning lease expired";
  if (c.trace_lost) return "trace records lost";
  return nullptr;
}

bool ChargePump::scan(const Conditions& c, Nanos now) {
  if (stopped_for_good_) return false;
  if (const char* why = stop_reason(c)) return halt(why, now);
  if (!running_) {
    running_ = true;
    scans_ = 0;
    spdlog::info("charge pump running: {} Hz, a toggle every {} scan(s)", setup_.frequency_hz,
                 setup_.half_period_scans);
  }
  const bool toggle = scans_ == 0;
  scans_ = (scans_ + 1) % setup_.half_period_scans;
  return toggle && write(!level_, now);
}

bool ChargePump::stop(Nanos now) {
  if (stopped_for_good_) return false;
  stopped_for_good_ = true;
  if (running_) spdlog::info("charge pump stopped with the daemon: the watchdog relay drops");
  running_ = false;
  return level_ && write(false, now);
}

bool ChargePump::halt(const char* why, Nanos now) {
  if (running_) {
    running_ = false;
    spdlog::warn("charge pump stopped ({}): the watchdog relay drops", why);
  }
  return level_ && write(false, now);
}

bool ChargePump::write(bool level, Nanos now) {
  level_ = level;
  backend_.set_charge_pump(setup_.axis, level);
  changed_at_ = clock_ != nullptr ? std::max(now, clock_()) : now;
  return true;
}

}  // namespace stepmod::tools
