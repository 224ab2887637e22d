#pragma once
// The 3601 as a module::Personality: one shared axis (module/axis/) with the 3601's rules, and
// the 3601 dialect around it (config_3601, dialect_3601) that turns its eight output words into
// decoded configuration and commands and the axis' status into its eight input words. The verbs
// every module answers alike: module/shared/axes_personality.hpp.
#include "module/shared/axes_personality.hpp"
#include "module_types/m3601/dialect_3601.hpp"
#include "module_types/m3601/rules_3601.hpp"

namespace stepmod::module::m3601 {

struct Channel3601 {
  Channel3601(AxisIo& io, planner::MotionPort& motion);
  axis::Axis axis;
  ConfigMirror mirror{};  // configuration mirror (A26: only accepted data)
};

class Module3601 final : public shared::AxesPersonality<ModuleType::k3601, Channel3601> {
 public:
  static constexpr const axis::ModuleRules& kRules = kRules3601;  // rules_3601.hpp

  Module3601(AxisIo& io, planner::MotionPort& motion);

  void scan(const ImageWords& out, ImageWords& in, Nanos now) override;
};

}  // namespace stepmod::module::m3601
