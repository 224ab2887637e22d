#pragma once
// The 3602 as a module::Personality: two independent shared axes (module/axis/) with the 3602's
// rules, each fed its own eight words b+0 .. b+7 (b = 8 * axis) through the 3602 dialect
// (config_3602, dialect_3602). Axis 1 can be configured while axis 2 runs and vice versa (digest
// 4). What the module adds to each axis: the general-purpose output (command LSW bit 7, a level
// written to the axis' gpo line by its pulse path) and status bit 14, Axis Enabled. What spans
// both axes: the interpolated move (interpolated_move.hpp), whose block is all sixteen words.
#include <array>

#include "module/axis/axis.hpp"
#include "module_types/m3602/interpolated_move.hpp"
#include "module/personality.hpp"
#include "planner/motion_port.hpp"

namespace stepmod::module::m3602 {

class Module3602 final : public Personality {
 public:
  Module3602(AxisIo& io, planner::MotionPort& axis1, planner::MotionPort& axis2);

  const ModuleShape& shape() const noexcept override;
  void on_input(const InputEvent& e) override;
  void scan(const ImageWords& out, ImageWords& in, Nanos now) override;
  void plc_stopped(Nanos now) override;
  void stop_every_axis(const axis::Item& why, Nanos now) override;
  axis::ErrorReason reason(unsigned axis) const override;
  void shutdown() override;
  DriveState drive_state(unsigned axis) const noexcept override;

 private:
  struct Channel {
    Channel(AxisIo& io, planner::MotionPort& m);
    // The axis' scan with its decoded command, then its input words.
    void scan(const ImageWords& out, const axis::AxisCommand& c, Nanos now);
    void publish(const ImageWords& out, bool interpolating, ImageWords& in);
    void set_gpo(bool level);

    planner::MotionPort& motion;
    axis::Axis axis;
    // The disable bit of the configuration the axis holds or will take on leaving configuration
    // mode (3602-EN-01, A19: enabled only once configured enabled).
    bool disabled = false;
    bool pending_disabled = false;
    bool gpo = false;                  // the level last written to the gpo line
    bool configuration_valid = false;  // this scan's words read as a valid configuration
  };
  std::array<Channel, 2> axes_;
  InterpolatedMove interpolated_;
};

}  // namespace stepmod::module::m3602
