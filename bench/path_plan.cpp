#include "bench/path_plan.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <span>

#include "core/spsc_ring.hpp"
#include "planner/motion_request.hpp"
#include "planner/planner.hpp"
#include "rt/axis_feedback.hpp"
#include "rt/edge.hpp"

namespace stepmod::bench {
namespace {

constexpr Nanos kNoHold = std::numeric_limits<Nanos>::max();

// The planner of two path axes with their rings, driven in virtual time.
class VirtualPath {
 public:
  VirtualPath()
      : rings_{SpscRing<rt::Edge>(1u << 16), SpscRing<rt::Edge>(1u << 16)},
        axes_{planner::PlannerAxis{&rings_[0], &controls_[0], {}},
              planner::PlannerAxis{&rings_[1], &controls_[1], {}}},
        planner_(std::span<const planner::PlannerAxis>(axes_.data(), axes_.size())) {}

  void start(const planner::PathSpec& spec) {
    submit_both(1, [&](unsigned a) {
      return planner::PathStart{spec, static_cast<planner::PathCoordinate>(a)};
    });
  }
  void resume(const ResumeProfile& r) {
    submit_both(2, [&](unsigned a) {
      return planner::PathResume{static_cast<planner::PathCoordinate>(a), r.vp, r.accel, r.decel};
    });
  }
  void hold(const planner::Ramp& ramp) {
    planner::Command c;
    c.axis = 0;
    c.epoch = epoch_;
    c.what = planner::PathHold{ramp};
    planner_.submit(c);
  }
  // Runs until both axes' motions have ended; submits a hold at `hold_at` (kNoHold: none).
  AxisSteps run(Nanos hold_at, const planner::Ramp& ramp) {
    AxisSteps out;
    std::array<bool, 2> last{false, false};
    const Nanos limit = now_ + 3'600 * kNsPerSec;
    while (!(last[0] && last[1]) && now_ < limit) {
      if (hold_at != kNoHold && now_ >= hold_at) {
        hold(ramp);
        hold_at = kNoHold;
      }
      const Nanos next = planner_.service(now_);
      for (unsigned a = 0; a < 2; ++a) drain(a, out[a], last[a]);
      Nanos step = std::min(next, now_ + kNsPerMs);
      if (hold_at != kNoHold) step = std::min(step, std::max(hold_at, now_ + kNsPerUs));
      now_ = std::max(now_ + kNsPerUs, step);
    }
    return out;
  }

 private:
  template <typename Payload>
  void submit_both(std::uint32_t group, Payload payload) {
    ++epoch_;
    for (unsigned a = 0; a < 2; ++a) {
      planner::Command c;
      c.axis = static_cast<std::uint8_t>(a);
      c.epoch = epoch_;
      c.group = planner::GroupTag{group, 2};
      c.what = payload(a);
      planner_.submit(c);
    }
  }
  void drain(unsigned a, std::vector<Nanos>& steps, bool& last) {
    rt::Edge e;
    while (rings_[a].try_pop(e)) {
      if (e.dpos != 0) steps.push_back(e.t);
      last = last || (e.flags & rt::edge_flag::kLast) != 0;
    }
  }

  std::array<SpscRing<rt::Edge>, 2> rings_;
  std::array<rt::AxisControl, 2> controls_;
  std::array<planner::PlannerAxis, 2> axes_;
  planner::Planner planner_;
  Nanos now_ = 0;
  std::uint32_t epoch_ = 0;
};

std::size_t count(const AxisSteps& s) {
  return s[0].size() + s[1].size();
}

}  // namespace

AxisSteps plan_path(const planner::PathSpec& spec) {
  VirtualPath v;
  v.start(spec);
  return v.run(kNoHold, {});
}

HeldPlan plan_held_path(const planner::PathSpec& spec, const planner::Ramp& hold,
                        const ResumeProfile& resume, std::size_t steps_to_stop) {
  // The stop point moves forward with the hold's time: bisect for the time whose stop point is
  // the wire's (the nearest: a step of the stop point is a few microseconds of hold time).
  const AxisSteps whole = plan_path(spec);
  Nanos lo = 0, hi = std::max(whole[0].empty() ? 0 : whole[0].back(),
                              whole[1].empty() ? 0 : whole[1].back());
  const auto held_at = [&](Nanos t) {
    VirtualPath v;
    v.start(spec);
    return v.run(t, hold);
  };
  while (hi - lo > kNsPerUs) {
    const Nanos mid = lo + (hi - lo) / 2;
    (count(held_at(mid)) < steps_to_stop ? lo : hi) = mid;
  }
  const Nanos t =
      std::labs(static_cast<long>(count(held_at(lo))) - static_cast<long>(steps_to_stop)) <=
              std::labs(static_cast<long>(count(held_at(hi))) - static_cast<long>(steps_to_stop))
          ? lo
          : hi;
  VirtualPath v;
  v.start(spec);
  HeldPlan plan;
  plan.held = v.run(t, hold);
  v.resume(resume);
  plan.resumed = v.run(kNoHold, {});
  return plan;
}

std::vector<Nanos> plan_move(const planner::MoveSpec& spec) {
  SpscRing<rt::Edge> ring(1u << 16);
  rt::AxisControl control;
  const planner::PlannerAxis axis{&ring, &control, {}};
  planner::Planner p(std::span<const planner::PlannerAxis>(&axis, 1));
  planner::Command c;
  c.axis = 0;
  c.epoch = 1;
  c.what = spec;
  p.submit(c);
  std::vector<Nanos> t;
  bool last = false;
  for (Nanos now = 0; !last && now < 3'600 * kNsPerSec;) {
    const Nanos next = p.service(now);
    rt::Edge e;
    while (ring.try_pop(e)) {
      if (e.dpos != 0) t.push_back(e.t);
      last = last || (e.flags & rt::edge_flag::kLast) != 0;
    }
    now = std::max(now + kNsPerUs, std::min(next, now + kNsPerMs));
  }
  return t;
}

}  // namespace stepmod::bench
