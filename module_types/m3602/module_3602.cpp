#include "module_types/m3602/module_3602.hpp"

#include "module_types/m3602/config_3602.hpp"
#include "module_types/m3602/dialect_3602.hpp"
#include "module_types/m3602/words_3602.hpp"

namespace stepmod::module::m3602 {
using namespace words::m3602;  // this module's words: module_types/m3602/words_3602.hpp

namespace {
// One axis' eight words of the module's sixteen (b = 8 * axis).
ImageWords axis_words(const ImageWords& image, unsigned axis) noexcept {
  ImageWords w;
  for (unsigned i = 0; i < kWordsPerAxis; ++i) w.w[i] = image.w[kWordsPerAxis * axis + i];
  return w;
}
void put_axis_words(const ImageWords& w, unsigned axis, ImageWords& image) noexcept {
  for (unsigned i = 0; i < kWordsPerAxis; ++i) image.w[kWordsPerAxis * axis + i] = w.w[i];
}
}  // namespace

Channel3602::Channel3602(AxisIo& io, planner::MotionPort& m)
    : motion(m), axis(kRules3602, io, m) {}

void Channel3602::set_gpo(bool level) {
  if (level == gpo) return;
  if (motion.set_gpo(level)) gpo = level;  // a full command queue: tried again next scan
}

void Channel3602::scan(const ImageWords& out, const axis::AxisCommand& c, Nanos now) {
  const bool was_config = axis.in_configuration_mode();
  // The image read as configuration words matters only with the mode bit set.
  std::optional<axis::AxisConfig> configuration;
  if (static_cast<std::uint16_t>(out.w[out_word::kMsw]) & cfg_msw::kConfigMode) {
    Config3602 decoded;
    const ConfigFault fault = check_config(out, decoded);
    if (fault == ConfigFault::kNone) configuration = to_axis_config(decoded);
    axis.set_configuration_fault(checklist_item(fault), describe(fault));
  }
  configuration_valid = configuration.has_value();
  axis.scan(c, configuration, now);
  if (axis.in_configuration_mode()) {
    // The axis evaluates the words every configuration scan; the verdict it keeps is this one.
    pending_disabled = configuration && configuration->disabled;
  } else if (was_config) {
    disabled = pending_disabled;  // the configuration the axis took on leaving the mode
  }
}

void Channel3602::publish(const ImageWords& out, bool interpolating, ImageWords& in) {
  const axis::AxisStatus s = axis.status();
  // 3602-EN-01 / A19: enabled = configured (no CfgE) and not disabled.
  const bool enabled = !s.configuration_error && !disabled;
  if (axis.in_configuration_mode()) {
    // A26: the 3602 echoes the last data written. Enabled: of the configuration now written.
    configuration_image_to_words(out, s.configuration_error,
                                 configuration_valid && !pending_disabled, in);
    return;
  }
  // The general-purpose output follows command LSW bit 7 at any time in command mode (digest
  // 4.7: a level, not a command).
  set_gpo(gpo_from_words(out));
  status_to_words(
      s, StatusExtras{.axis_enabled = enabled, .interpolating = interpolating, .gpo = gpo}, in);
}

Module3602::Module3602(AxisIo& io, planner::MotionPort& axis1,
                       planner::MotionPort& axis2)
    : AxesPersonality(io, axis1, axis2),
      interpolated_(axes_[0].axis, axis1, axes_[1].axis, axis2) {}

void Module3602::on_input(const InputEvent& e) {
  if (e.axis >= kAxes) return;
  AxesPersonality::on_input(e);
  interpolated_.after_input();  // a limit on one axis of a path stops the other at once
  for (Channel3602& c : axes_) c.axis.explain_new_errors();
}

void Module3602::scan(const ImageWords& out, ImageWords& in, Nanos now) {
  in = ImageWords{};
  const std::array<ImageWords, 2> words = {axis_words(out, 0), axis_words(out, 1)};
  axes_[0].scan(words[0], command_from_words(words[0]), now);
  // While a path runs, axis 2's commands are the interpolated move's business (A46).
  axes_[1].scan(words[1], interpolated_.filter_axis2(command_from_words(words[1])), now);
  // The interpolated block spans all sixteen words; axis 1's LSW bits 9..14 select it.
  interpolated_.scan(interpolated_from_words(out));
  // The path acts on the axes after their scans (a refusal, a stop carried over): the reasons
  // of this scan are complete only now, before the status that shows their bits.
  for (Channel3602& c : axes_) c.axis.explain_new_errors();
  for (unsigned a = 0; a < axes_.size(); ++a) {
    ImageWords axis_in;
    axes_[a].publish(words[a], a == 0 && interpolated_.running(), axis_in);
    put_axis_words(axis_in, a, in);
  }
}

void Module3602::shutdown() {
  AxesPersonality::shutdown();
  for (Channel3602& c : axes_) c.set_gpo(false);  // idle-low at shutdown
}

}  // namespace stepmod::module::m3602
