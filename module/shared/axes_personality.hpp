#pragma once
// The part of a module::Personality that every module type answers alike: an array of its axes
// (a 3601: one; a 3602: two axes; a 3202: two channels), each one shared axis (module/axis/), and
// the verbs that are handed to every axis or to the one named (inputs, PLC stopped, a stop of the
// daemon's own, shutdown, the reason and drive state of one axis). A module type derives from it
// and writes only its scan and what it adds (the 3602's general-purpose output, the 3202's blend
// message): module_types/mXXXX/module_XXXX.hpp.
//
// `Channel` is the module's per-axis record: constructible from (AxisIo&, MotionPort&), holding
// the shared axis as `axis`; where it has a `disabled` flag (3602-EN-01, 3202-DIS-01), a disabled
// axis reads as not configured to drive enable.
#include <array>
#include <cstddef>

#include "core/module_shape.hpp"
#include "module/axis/axis.hpp"
#include "module/personality.hpp"
#include "planner/motion_port.hpp"

namespace stepmod::module::shared {

template <ModuleType Type, typename Channel>
class AxesPersonality : public Personality {
 public:
  static constexpr ModuleShape kShape = shape_of(Type);
  static constexpr std::size_t kAxes = kShape.axes;

  const ModuleShape& shape() const noexcept final { return kShape; }

  void on_input(const InputEvent& e) override {
    if (e.axis < kAxes) axes_[e.axis].axis.on_input(e);
  }

  void plc_stopped(Nanos /*now*/) override {
    for (Channel& c : axes_) c.axis.plc_stopped();
  }

  void shutdown() override {
    for (Channel& c : axes_) c.axis.plc_stopped();  // immediate stop of motions under way
  }

  void stop_every_axis(const axis::Item& why, Nanos /*now*/) override {
    for (Channel& c : axes_) c.axis.plc_stopped(why);
  }

  axis::ErrorReason reason(unsigned axis) const override {
    return axis < kAxes ? axes_[axis].axis.reason() : axis::ErrorReason{};
  }

  DriveState drive_state(unsigned axis) const noexcept override {
    if (axis >= kAxes) return {};
    const Channel& c = axes_[axis];
    const auto d = c.axis.drive_state();
    bool disabled = false;
    if constexpr (requires { c.disabled; }) disabled = c.disabled;
    return {d.configured && !disabled, d.configuration_mode, d.estop};
  }

  InputLines input_lines(unsigned axis) const noexcept override {
    if (axis >= kAxes) return {};
    const InputBank& b = axes_[axis].axis.inputs();
    InputLines l;
    l.active = b.active_bits();
    for (unsigned i = 0; i < kPanelInputs; ++i) {
      const auto line = static_cast<InputLine>(i);
      if (b.level(line)) l.levels |= static_cast<std::uint16_t>(1u << i);
      if (b.used(line)) l.used |= static_cast<std::uint16_t>(1u << i);
    }
    return l;
  }

 protected:
  // One motion port per axis, in axis order.
  template <typename... Motion>
    requires(sizeof...(Motion) == kAxes)
  AxesPersonality(AxisIo& io, Motion&... motion) : axes_{Channel(io, motion)...} {}

  std::array<Channel, kAxes> axes_;
};

}  // namespace stepmod::module::shared
