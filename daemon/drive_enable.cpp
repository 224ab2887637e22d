#include "daemon/drive_enable.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "config/config.hpp"

namespace stepmod::tools {

DriveEnable::DriveEnable(gpio::Backend& backend, std::vector<AxisSetup> axes, Nanos (*clock)())
    : backend_(backend), axes_(std::move(axes)), state_(axes_.size()), clock_(clock) {}

bool DriveEnable::any_wired() const noexcept {
  for (const AxisSetup& a : axes_) {
    if (a.wired) return true;
  }
  return false;
}

const char* DriveEnable::release_reason(const AxisSetup& s, const Conditions& c) const noexcept {
  if (!c.configured) return "axis not configured";
  if ((s.release & kReleaseOnConfigMode) && c.configuration_mode) return "configuration mode";
  if ((s.release & kReleaseOnEStop) && c.estop) return "E-stop input active";
  if ((s.release & kReleaseOnFault) && c.fault) return "fault";
  if ((s.release & kReleaseOnPlcLoss) && c.plc_lost) return "PLC lost";
  return nullptr;
}

bool DriveEnable::update(unsigned axis, const Conditions& c, Nanos now) {
  if (axis >= axes_.size() || !axes_[axis].wired) return false;
  State& st = state_[axis];
  const char* why = release_reason(axes_[axis], c);
  const bool assert_now = why == nullptr;
  if (assert_now == st.asserted) return false;
  st.asserted = assert_now;
  backend_.set_enable(axis, assert_now);
  st.changed_at = clock_ != nullptr ? std::max(now, clock_()) : now;
  if (assert_now) {
    st.ready_at = st.changed_at + axes_[axis].delay_ns;
    spdlog::info("axis {}: drive enabled; commands wait {} us for the drive", axis + 1,
                 axes_[axis].delay_ns / kNsPerUs);
  } else {
    spdlog::warn("axis {}: drive enable released ({})", axis + 1, why);
  }
  return true;
}

bool DriveEnable::holding(Nanos now) const noexcept {
  for (const State& s : state_) {
    if (s.asserted && now < s.ready_at) return true;
  }
  return false;
}

}  // namespace stepmod::tools
