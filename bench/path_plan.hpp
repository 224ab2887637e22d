#pragma once
// The plans the VCD's step trains are judged against, from the planner itself in virtual time:
// a single-axis move (the manuals' profile equations, ch. 2), and benchmark 12's 3602 path (the
// manual's profile on the path length, both axes on one time base; bench/path_slip.cpp). A
// held-and-resumed path is planned with its hold at the point the wire shows it stopped.
#include <array>
#include <cstddef>
#include <vector>

#include "core/clock.hpp"
#include "planner/motion_request.hpp"
#include "planner/path_spec.hpp"
#include "planner/ramp.hpp"

namespace stepmod::bench {

// The planned times of the steps of a single-axis move.
std::vector<Nanos> plan_move(const planner::MoveSpec& spec);

// Per axis (0 = X, 1 = Y): the planned times of its steps.
using AxisSteps = std::array<std::vector<Nanos>, 2>;

AxisSteps plan_path(const planner::PathSpec& spec);

struct ResumeProfile {
  double vp = 1.0;
  planner::Ramp accel;
  planner::Ramp decel;
};

struct HeldPlan {
  AxisSteps held;     // from the start to the hold's stop point
  AxisSteps resumed;  // from there to the end, after the resume
};

// The path held with `hold` at the time that makes it stop after `steps_to_stop` steps (both
// axes together; the nearest the planner reaches), then resumed with `resume`.
HeldPlan plan_held_path(const planner::PathSpec& spec, const planner::Ramp& hold,
                        const ResumeProfile& resume, std::size_t steps_to_stop);

}  // namespace stepmod::bench
