#pragma once
// Shared helpers of the planner tests: a one-axis planner run in virtual time, and an independent
// reference of the manuals' profile shapes (written from the ch. 2 v(t) formulas, not from
// planner/profile.cpp) to check step times against.
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/spsc_ring.hpp"
#include "planner/planner.hpp"
#include "planner/profile.hpp"
#include "rt/axis_feedback.hpp"
#include "rt/edge.hpp"

namespace stepmod::planner::test {

inline constexpr Nanos kT0 = 1'000 * kNsPerSec;  // virtual "now" at which tests start

struct Harness {
  explicit Harness(AxisTiming timing = {}, PlannerOptions options = {},
                   std::size_t ring_capacity = 1u << 16)
      : ring(ring_capacity), opt(options) {
    PlannerAxis a;
    a.edges = &ring;
    a.control = &control;
    a.timing = timing;
    planner = std::make_unique<Planner>(std::span<const PlannerAxis>(&a, 1), options);
  }

  bool submit(Command c) {
    c.axis = 0;
    return planner->submit(c);
  }
  // Starts a motion as the next epoch. The raw Command protocol on purpose (not MotionPort): the
  // tests also send stale epochs, which MotionPort cannot.
  std::uint32_t start(Command c) {
    c.epoch = ++epoch;
    submit(c);
    return epoch;
  }
  std::uint32_t start_move(const MoveSpec& m) {
    Command c;
    c.what = m;
    return start(c);
  }
  std::uint32_t start_run(const RunSpec& r) {
    Command c;
    c.what = r;
    return start(c);
  }
  std::uint32_t start_blend(const BlendSpec& b) {
    Command c;
    c.epoch = ++epoch;
    planner->submit_blend(c, b);
    return epoch;
  }
  // A command for the newest motion.
  void send(CommandPayload what) {
    Command c;
    c.epoch = epoch;
    c.what = what;
    submit(c);
  }

  // One planner pass at `now`, then the pulse thread's side: take everything from the ring.
  Nanos service() {
    const Nanos next = planner->service(now);
    rt::Edge e;
    while (ring.try_pop(e)) {
      edges.push_back(e);
      if ((e.flags & rt::edge_flag::kLast) != 0) finished_epochs.push_back(e.epoch);
    }
    return next;
  }
  // Advances virtual time by `d` in steps of `tick`, servicing at each.
  void run_for(Nanos d, Nanos tick = 500 * kNsPerUs) {
    const Nanos end = now + d;
    while (now < end) {
      service();
      now += tick;
    }
  }
  bool finished(std::uint32_t ep) const {
    for (std::uint32_t f : finished_epochs) {
      if (f == ep) return true;
    }
    return false;
  }
  // Runs until motion `ep` has produced its kLast edge (or `limit` of virtual time passed).
  bool run_until_finished(std::uint32_t ep, Nanos limit = 3600 * kNsPerSec,
                          Nanos tick = 1 * kNsPerMs) {
    const Nanos end = now + limit;
    while (now < end) {
      service();
      if (finished(ep)) return true;
      now += tick;
    }
    return false;
  }

  // Leading edges (dpos != 0) of motion `ep`, in order.
  std::vector<rt::Edge> steps(std::uint32_t ep) const {
    std::vector<rt::Edge> out;
    for (const auto& e : edges) {
      if (e.epoch == ep && e.dpos != 0) out.push_back(e);
    }
    return out;
  }
  std::vector<rt::Edge> motion_edges(std::uint32_t ep) const {
    std::vector<rt::Edge> out;
    for (const auto& e : edges) {
      if (e.epoch == ep && (e.flags & rt::edge_flag::kMotion) != 0) out.push_back(e);
    }
    return out;
  }

  SpscRing<rt::Edge> ring;
  rt::AxisControl control;
  PlannerOptions opt;
  std::unique_ptr<Planner> planner;
  std::vector<rt::Edge> edges;
  std::vector<std::uint32_t> finished_epochs;  // epochs whose kLast edge was seen
  Nanos now = kT0;
  std::uint32_t epoch = 0;
};

inline Ramp ramp(double rate, AccelShape s = AccelShape::kConstant) {
  return Ramp{rate, s};
}

inline MoveSpec move(std::int64_t n, double vs, double vp, double a, double d,
                     AccelShape s = AccelShape::kConstant, Direction dir = Direction::kCw) {
  MoveSpec m;
  m.steps = n;
  m.dir = dir;
  m.vs = vs;
  m.vp = vp;
  m.accel = ramp(a, s);
  m.decel = ramp(d, s);
  return m;
}

// --- Independent reference of one ramp V1 -> V2 (the manuals' ch. 2, S-curve shapes). ---
struct RefRamp {
  long double v1, v2, a, t;  // a signed (negative for a deceleration), t = ramp time
  AccelShape shape;
  long double dist() const { return t * (v1 + v2) / 2; }
  // Distance covered after time x (0 <= x <= t).
  long double pos(long double x) const {
    switch (shape) {
      case AccelShape::kTriangularS: {
        // v = V1 + A x^2 / T up to T/2, V2 - A (T - x)^2 / T after.
        if (x <= t / 2) return v1 * x + a * x * x * x / (3 * t);
        const long double r = t - x;
        return dist() - (v2 * r - a * r * r * r / (3 * t));
      }
      case AccelShape::kTrapezoidalS: {
        // J = 4A/T: v = V1 + J x^2/2 up to T/4, slope A to 3T/4, symmetric end.
        const long double j = 4 * a / t;
        const long double q = t / 4;
        if (x <= q) return v1 * x + j * x * x * x / 6;
        if (x <= 3 * q) {
          const long double sq = v1 * q + j * q * q * q / 6;
          const long double vq = v1 + j * q * q / 2;
          const long double y = x - q;
          return sq + vq * y + a * y * y / 2;
        }
        const long double r = t - x;
        return dist() - (v2 * r - j * r * r * r / 6);
      }
      default:
        return v1 * x + a * x * x / 2;
    }
  }
};

inline RefRamp ref_ramp(double v1, double v2, const Ramp& r) {
  const long double k = r.shape == AccelShape::kTriangularS    ? 2.0L
                        : r.shape == AccelShape::kTrapezoidalS ? 4.0L / 3.0L
                                                               : 1.0L;
  const long double dv = static_cast<long double>(v2) - v1;
  RefRamp out{v1, v2, dv >= 0 ? static_cast<long double>(r.rate) : -r.rate,
              k * std::fabs(dv) / r.rate, r.shape};
  return out;
}

// Whole move: accel ramp, cruise, decel ramp, from the manuals' classification (recomputed here).
struct RefMove {
  RefRamp up, down;
  long double vpk, tp, n;
  long double total() const { return up.t + tp + down.t; }
  long double pos(long double t) const {
    if (t <= up.t) return up.pos(t);
    t -= up.t;
    if (t <= tp) return up.dist() + vpk * t;
    t -= tp;
    if (t > down.t) t = down.t;
    return up.dist() + vpk * tp + down.pos(t);
  }
  // Time at which pos = k, by bisection.
  long double time_of(long double k) const {
    long double lo = 0, hi = total();
    for (int i = 0; i < 200 && hi - lo > 1e-13L; ++i) {
      const long double mid = (lo + hi) / 2;
      if (pos(mid) < k) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    return (lo + hi) / 2;
  }
};

inline RefMove ref_move(const MoveSpec& m) {
  const long double ka = m.accel.shape == AccelShape::kTriangularS    ? 2.0L
                         : m.accel.shape == AccelShape::kTrapezoidalS ? 4.0L / 3.0L
                                                                      : 1.0L;
  const long double kd = m.decel.shape == AccelShape::kTriangularS    ? 2.0L
                         : m.decel.shape == AccelShape::kTrapezoidalS ? 4.0L / 3.0L
                                                                      : 1.0L;
  const long double vs = m.vs, vp = m.vp, n = static_cast<long double>(m.steps);
  const long double da = ka * (vp * vp - vs * vs) / (2 * m.accel.rate);
  const long double dd = kd * (vp * vp - vs * vs) / (2 * m.decel.rate);
  long double vpk = vp, tp = 0;
  if (da + dd <= n) {
    tp = (n - da - dd) / vp;
  } else {
    vpk = std::sqrt(vs * vs + 2 * n / (ka / m.accel.rate + kd / m.decel.rate));
  }
  RefMove r{ref_ramp(m.vs, static_cast<double>(vpk), m.accel),
            ref_ramp(static_cast<double>(vpk), m.vs, m.decel), vpk, tp, n};
  return r;
}

}  // namespace stepmod::planner::test
