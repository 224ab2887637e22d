#include "module_types/m3601/module_3601.hpp"

#include "module_types/m3601/config_3601.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::module::m3601 {
using namespace words::m3601;  // this module's words: module_types/m3601/words_3601.hpp

Channel3601::Channel3601(AxisIo& io, planner::MotionPort& motion)
    : axis(kRules3601, io, motion) {}

Module3601::Module3601(AxisIo& io, planner::MotionPort& motion) : AxesPersonality(io, motion) {}

void Module3601::scan(const ImageWords& out, ImageWords& in, Nanos now) {
  axis::Axis& ax = axes_[0].axis;  // the one axis
  ConfigMirror& mirror = axes_[0].mirror;
  // The image read as configuration words matters only with the mode bit set.
  ConfigCheck check;
  std::optional<axis::AxisConfig> configuration;
  if (out.w[out_word::kMsw] & cfg_msw::kConfigMode) {
    check = check_config(out);
    if (check.fault == ConfigFault::kNone) configuration = to_axis_config(check.config);
  }
  ax.set_configuration_fault(checklist_item(check.fault), describe(check.fault));
  ax.scan(command_from_words(out), configuration, now);

  if (ax.in_configuration_mode()) {
    // The axis took this image's configuration. A26: the mirror shows the accepted
    // configuration; a rejected one leaves the last mirror.
    if (configuration) {
      mirror = {check.config.msw, check.config.lsw,
                static_cast<std::uint16_t>(check.config.vs_msw),
                static_cast<std::uint16_t>(check.config.vs_lsw)};
    }
    configuration_image_to_words(mirror, ax.status().configuration_error, in);
  } else {
    status_to_words(ax.status(), in);
  }
}

}  // namespace stepmod::module::m3601
