#pragma once
// The safe step rate per axis under the late-edge guard (docs/slip.md): a pause of L at a rate r
// lags L*r steps, so an axis whose guard allows lag_limit_steps is safe up to
// r_safe = lag_limit_steps / L for the worst pause L measured; a pause beyond late_limit faults
// at any speed.
#include <cstdint>
#include <span>
#include <vector>

#include "core/clock.hpp"

namespace stepmod::doctor {

struct AxisRate {
  unsigned axis = 0;  // 1-based, as in the config
  std::uint32_t lag_limit_steps = 0;
  double safe_rate = 0;  // steps/s
};

struct Fitness {
  Nanos worst_pause = 0;
  Nanos late_limit = 0;
  double needed_rate = 0;  // steps/s the user needs (0: not given)
  std::vector<AxisRate> axes;
  bool within_late_limit = false;  // the worst pause does not fault at any speed
  bool fit = false;                // that, and every axis' safe rate >= needed_rate
};

Fitness judge_fitness(Nanos worst_pause, Nanos late_limit, std::span<const std::uint32_t> lag_limits,
                      double needed_rate);

}  // namespace stepmod::doctor
