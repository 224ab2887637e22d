#pragma once
// Benchmark 12's judgement of one axis' step train from the VCD against its plan (issue 18's
// criteria, docs/slip.md): compressed intervals, pauses beyond the late-edge guard's rule that
// did not fault, the end within 2.5 x nominal + 3 s; and the VCD's step trains split into moves
// where the line rested. Shared by the single-axis moves (bench/daemon_bench.cpp), the 3602 paths
// (bench/path_slip.cpp) and the rack (bench/rack_bench.cpp).
#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/clock.hpp"

namespace stepmod::bench {

// The product's defaults the rule is judged with: [axis] lag_limit_steps, [rt] late_limit_us.
inline constexpr Nanos kDefaultLagLimitSteps = 8;
inline constexpr Nanos kDefaultLateLimitNs = 200 * kNsPerMs;

struct SlipVerdict {
  std::size_t compressed = 0;  // actual < 0.9 x planned - 2 us
  std::size_t unfaulted = 0;   // pauses beyond the guard's rule that did not fault
  Nanos worst_pause = 0;
  bool in_time = true;  // ended within 2.5 x nominal + 3 s
};

// `wire` and `plan`: the axis' step times (rising step edges), the same steps in both. `vs`: the
// motion's starting speed (a path's: the vector Vs, as the guard judges a path axis).
inline SlipVerdict judge_move(const std::vector<Nanos>& wire, const std::vector<Nanos>& plan,
                              double vs, bool faulted) {
  SlipVerdict v;
  const double vs_interval = 1e9 / vs;
  for (std::size_t k = 1; k < wire.size() && k < plan.size(); ++k) {
    const Nanos actual = wire[k] - wire[k - 1];
    const Nanos planned = plan[k] - plan[k - 1];
    if (static_cast<double>(actual) < 0.9 * static_cast<double>(planned) - 2'000) ++v.compressed;
    const Nanos pause = actual - planned;
    v.worst_pause = std::max(v.worst_pause, pause);
    const bool above = static_cast<double>(planned) < 0.99 * vs_interval;
    const bool beyond = pause > kDefaultLateLimitNs ||
                        (above && pause / std::max<Nanos>(planned, 1) > kDefaultLagLimitSteps);
    if (beyond && !faulted) ++v.unfaulted;
  }
  if (wire.size() >= 2 && plan.size() >= 2) {
    const double nominal = static_cast<double>(plan.back() - plan.front());
    v.in_time = static_cast<double>(wire.back() - wire.front()) <= 2.5 * nominal + 3e9;
  }
  return v;
}

// Step trains of consecutive moves, split where the line rested longer than `gap`.
inline std::vector<std::vector<Nanos>> split_moves(const std::vector<Nanos>& rising, Nanos gap) {
  std::vector<std::vector<Nanos>> moves;
  for (std::size_t i = 0; i < rising.size(); ++i) {
    if (i == 0 || rising[i] - rising[i - 1] > gap) moves.emplace_back();
    moves.back().push_back(rising[i]);
  }
  return moves;
}

}  // namespace stepmod::bench
