#include "module_types/m3202/module_3202.hpp"

#include "module_types/m3202/blend_message_3202.hpp"
#include "module_types/m3202/config_3202.hpp"
#include "module_types/m3202/words_3202.hpp"

namespace stepmod::module::m3202 {
using namespace words::m3202;  // this module's words: module_types/m3202/words_3202.hpp

Channel3202::Channel3202(AxisIo& io, planner::MotionPort& motion)
    : axis(kRules3202, io, motion) {}

Module3202::Module3202(AxisIo& io, planner::MotionPort& ch1, planner::MotionPort& ch2)
    : AxesPersonality(io, ch1, ch2) {}

void Module3202::scan(const ImageWords& out, ImageWords& in, Nanos now) {
  for (unsigned ch = 0; ch < kAxes; ++ch) scan_channel(ch, out, in, now);
}

void Module3202::scan_channel(unsigned ch, const ImageWords& out, ImageWords& in, Nanos now) {
  Channel3202& c = axes_[ch];
  axis::AxisCommand command = command_from_words(out, ch);
  ConfigCheck check;
  std::optional<axis::AxisConfig> configuration;
  if (command.configuration_mode) {
    check = check_config(out, ch);
    if (check.fault == ConfigFault::kNone) configuration = to_axis_config(check.config);
    c.axis.set_configuration_fault(checklist_item(check.fault), describe(check.fault));
  }
  const bool was_config_mode = c.axis.in_configuration_mode();
  // A disabled channel ignores its command bits (3202 manual ch. 6 bit 28); the mode bit still
  // works.
  if (c.disabled && !was_config_mode) command.commands = axis::CommandSet{};
  c.axis.scan(command, configuration, now);

  if (c.axis.in_configuration_mode()) {
    if (configuration) {
      c.mirror = {check.config.bits, check.config.starting_speed};
      c.pending_disabled = configuration->disabled;
    } else {
      c.pending_disabled = false;  // an invalid configuration is no disabled one: CfgE shows
    }
    configuration_image_to_words(c.mirror, c.axis.status().configuration_error, c.pending_disabled,
                                 ch, in);
    return;
  }
  if (was_config_mode) c.disabled = c.pending_disabled;  // the configuration taken on leaving
  status_to_words(c.axis.status(), c.disabled, ch, in);
}

std::int32_t Module3202::on_message(std::span<const std::int32_t> data, Nanos /*now*/) {
  const BlendMessage m = blend_message_from_dints(data);
  if (m.channel != 1 && m.channel != 2) {
    // 3202-IP-11, A23: no channel is named: Invalid Profile on both, nothing stored.
    for (Channel3202& c : axes_) c.axis.set_invalid_profile();
    return kMessageRefused;
  }
  Channel3202& c = axes_[static_cast<unsigned>(m.channel - 1)];
  if (c.disabled) {
    c.axis.set_invalid_profile(axis::items::kBlendNotConfigured);  // 3202-IP-15: the channel is not
                                                                   // configured (or disabled)
    return kMessageRefused;
  }
  return c.axis.program_blend(m.first, m.segments) ? kMessageAccepted : kMessageRefused;
}

}  // namespace stepmod::module::m3202
