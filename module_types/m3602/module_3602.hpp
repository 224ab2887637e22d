#pragma once
// The 3602 as a module::Personality: two independent shared axes (module/axis/) with the 3602's
// rules, each fed its own eight words b+0 .. b+7 (b = 8 * axis) through the 3602 dialect
// (config_3602, dialect_3602). Axis 1 can be configured while axis 2 runs and vice versa (digest
// 4). What the module adds to each axis: the general-purpose output (command LSW bit 7, a level
// written to the axis' gpo line by its pulse path) and status bit 14, Axis Enabled. What spans
// both axes: the interpolated move (interpolated_move.hpp), whose block is all sixteen words. The
// verbs every module answers alike: module/shared/axes_personality.hpp.
#include <span>

#include "module/shared/axes_personality.hpp"
#include "module_types/m3602/interpolated_items.hpp"
#include "module_types/m3602/interpolated_move.hpp"
#include "module_types/m3602/rules_3602.hpp"

namespace stepmod::module::m3602 {

// One axis: the shared axis and what the 3602 adds to it.
struct Channel3602 {
  Channel3602(AxisIo& io, planner::MotionPort& m);
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

class Module3602 final : public shared::AxesPersonality<ModuleType::k3602, Channel3602> {
 public:
  static constexpr const axis::ModuleRules& kRules = kRules3602;  // rules_3602.hpp
  // The error conditions only the 3602 has (its interpolated moves), beside the shared ones.
  static constexpr std::span<const axis::Item* const> kOwnItems = items::kAll;

  Module3602(AxisIo& io, planner::MotionPort& axis1, planner::MotionPort& axis2);

  void on_input(const InputEvent& e) override;
  void scan(const ImageWords& out, ImageWords& in, Nanos now) override;
  void shutdown() override;

 private:
  InterpolatedMove interpolated_;
};

}  // namespace stepmod::module::m3602
