#pragma once
// The 3601 as a module::Personality: one shared axis (module/axis/) with the 3601's rules, and
// the 3601 dialect around it (config_3601, dialect_3601) that turns its eight output words into
// decoded configuration and commands and the axis' status into its eight input words.
#include "module/axis/axis.hpp"
#include "module_types/m3601/dialect_3601.hpp"
#include "module/personality.hpp"
#include "planner/motion_port.hpp"

namespace stepmod::module::m3601 {

class Module3601 final : public Personality {
 public:
  Module3601(AxisIo& io, planner::MotionPort& motion);

  const ModuleShape& shape() const noexcept override;
  void on_input(const InputEvent& e) override;
  void scan(const ImageWords& out, ImageWords& in, Nanos now) override;
  void plc_stopped(Nanos now) override;
  void stop_every_axis(const axis::Item& why, Nanos now) override;
  axis::ErrorReason reason(unsigned axis) const override;
  void shutdown() override;
  DriveState drive_state(unsigned axis) const noexcept override;

 private:
  axis::Axis axis_;
  ConfigMirror mirror_{};  // configuration mirror (A26: only accepted data)
};

}  // namespace stepmod::module::m3601
