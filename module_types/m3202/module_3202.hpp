#pragma once
// The 3202 as a module::Personality: two independent channels (3202 manual: configuration,
// commands, errors and Reset Errors per channel), each one shared axis (module/axis/) with the
// 3202's rules, and the 3202 dialect around them (config_3202, dialect_3202). The verbs every
// module answers alike: module/shared/axes_personality.hpp.
#include <cstdint>
#include <span>

#include "module_types/m3202/dialect_3202.hpp"
#include "module_types/m3202/rules_3202.hpp"
#include "module/shared/axes_personality.hpp"

namespace stepmod::module::m3202 {

struct Channel3202 {
  Channel3202(AxisIo& io, planner::MotionPort& motion);
  axis::Axis axis;
  ConfigMirror mirror{};  // A26: only accepted data
  // 3202-DIS-01: disabled from power-up until configured, and while configured with bit 28.
  bool disabled = true;
  // The verdict of the configuration words in configuration mode: valid and bit 28 set.
  bool pending_disabled = false;
};

class Module3202 final : public shared::AxesPersonality<ModuleType::k3202, Channel3202> {
 public:
  static constexpr const axis::ModuleRules& kRules = kRules3202;  // rules_3202.hpp

  Module3202(AxisIo& io, planner::MotionPort& ch1, planner::MotionPort& ch2);

  void scan(const ImageWords& out, ImageWords& in, Nanos now) override;
  // The blend profile message (3202 manual ch. 5; 3202-IP-11..17, CE-19).
  std::int32_t on_message(std::span<const std::int32_t> data, Nanos now) override;

 private:
  void scan_channel(unsigned ch, const ImageWords& out, ImageWords& in, Nanos now);
};

}  // namespace stepmod::module::m3202
