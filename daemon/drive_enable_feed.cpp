#include "daemon/drive_enable_feed.hpp"

#include <vector>

#include "daemon/daemon_trace.hpp"
#include "daemon/health_words.hpp"
#include "daemon/lost_input_watch.hpp"
#include "daemon/module_stack.hpp"
#include "gpio/vcd_trace.hpp"

namespace stepmod::tools {

namespace {
std::vector<DriveEnable::AxisSetup> enable_setups(const Config& config) {
  std::vector<DriveEnable::AxisSetup> enables;
  for (const AxisSection& a : config.axes) {
    enables.push_back({a.enable.has_value(), a.enable_delay_ns, a.enable_release});
  }
  return enables;
}
}  // namespace

DriveEnableFeed::DriveEnableFeed(ModuleStack& stack, const Config& config,
                                 const LostInputWatch& lost_inputs, ModuleTrace* trace)
    : stack_(stack),
      lost_inputs_(lost_inputs),
      trace_(trace),
      enable_(stack.backend(), enable_setups(config), &monotonic_now) {}

void DriveEnableFeed::scan(bool plc_lost, Nanos now) {
  if (!enable_.any_wired()) return;
  const bool input_loss = lost_inputs_.lasts();
  for (unsigned a = 0; a < stack_.shape().axes; ++a) {
    const module::Personality::DriveState s = stack_.personality().drive_state(a);
    DriveEnable::Conditions c;
    c.configured = s.configured;
    c.configuration_mode = s.configuration_mode;
    c.estop = s.estop;
    c.fault = input_loss || HealthWords::late_fault_lasts(stack_.motion(a));
    c.plc_lost = plc_lost;
    if (enable_.update(a, c, now) && trace_ != nullptr) {
      trace_->record_input({enable_.changed_at(a), static_cast<std::uint8_t>(a),
                            gpio::kEnableTraceLine, enable_.asserted(a), 0});
    }
  }
}

std::array<UnitStatePublisher::Enable, 2> DriveEnableFeed::states() const noexcept {
  std::array<UnitStatePublisher::Enable, 2> s{};
  for (unsigned a = 0; a < stack_.shape().axes && a < s.size(); ++a) {
    s[a] = {enable_.wired(a), enable_.wired(a) && enable_.asserted(a)};
  }
  return s;
}

void DriveEnableFeed::trace_release(Nanos now) noexcept {
  if (trace_ == nullptr) return;
  for (unsigned a = 0; a < stack_.shape().axes; ++a) {
    if (enable_.asserted(a))
      trace_->record_input({now, static_cast<std::uint8_t>(a), gpio::kEnableTraceLine, 0, 0});
  }
}

}  // namespace stepmod::tools
