#include "module_types/m3601/module_3601.hpp"
#include "module_types/m3601/rules_3601.hpp"

#include "module_types/m3601/config_3601.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::module::m3601 {
using namespace words::m3601;  // this module's words: module_types/m3601/words_3601.hpp

namespace {
constexpr ModuleShape kShape = shape_of(ModuleType::k3601);
}  // namespace

Module3601::Module3601(AxisIo& io, planner::MotionPort& motion)
    : axis_(kRules3601, io, motion) {}

const ModuleShape& Module3601::shape() const noexcept {
  return kShape;
}

void Module3601::on_input(const InputEvent& e) {
  axis_.on_input(e);
}

void Module3601::scan(const ImageWords& out, ImageWords& in, Nanos now) {
  // The image read as configuration words matters only with the mode bit set.
  ConfigCheck check;
  std::optional<axis::AxisConfig> configuration;
  if (out.w[out_word::kMsw] & cfg_msw::kConfigMode) {
    check = check_config(out);
    if (check.fault == ConfigFault::kNone) configuration = to_axis_config(check.config);
  }
  axis_.set_configuration_fault(checklist_item(check.fault), describe(check.fault));
  axis_.scan(command_from_words(out), configuration, now);

  if (axis_.in_configuration_mode()) {
    // The axis took this image's configuration. A26: the mirror shows the accepted
    // configuration; a rejected one leaves the last mirror.
    if (configuration) {
      mirror_ = {check.config.msw, check.config.lsw,
                 static_cast<std::uint16_t>(check.config.vs_msw),
                 static_cast<std::uint16_t>(check.config.vs_lsw)};
    }
    configuration_image_to_words(mirror_, axis_.status().configuration_error, in);
  } else {
    status_to_words(axis_.status(), in);
  }
}

void Module3601::plc_stopped(Nanos /*now*/) {
  axis_.plc_stopped();
}

void Module3601::shutdown() {
  axis_.plc_stopped();  // immediate stop of a motion under way
}

void Module3601::stop_every_axis(const axis::Item& why, Nanos /*now*/) {
  axis_.plc_stopped(why);
}

axis::ErrorReason Module3601::reason(unsigned /*axis*/) const {
  return axis_.reason();
}

Personality::DriveState Module3601::drive_state(unsigned axis) const noexcept {
  (void)axis;  // one axis
  const auto d = axis_.drive_state();
  return {d.configured, d.configuration_mode, d.estop};
}

}  // namespace stepmod::module::m3601
