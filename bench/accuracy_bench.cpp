// Benchmark 6 of issue 5: step-time accuracy. For each profile, every step's scheduled time (the
// leading edge the planner puts in the ring, relative to the motion's time 0) is compared with
// its ideal time from the manuals' profile equations (ch. 2):
//
//   ramp V1 -> V2 at rate A, factor k (constant 1, triangular S 2, trapezoidal S 4/3):
//     T = k |V2 - V1| / A,  D = T (V1 + V2) / 2;
//   constant: v = V1 + A t; triangular S: v = V1 + A t^2 / T up to T/2, then point-symmetric;
//   trapezoidal S: jerk J = 4A/T for T/4, constant A for T/2, jerk -J for T/4;
//   move of N: Da + Dd < N trapezoid (cruise N - Da - Dd at Vp), else triangle with
//   Vpk^2 = Vs^2 + 2N / (ka/a + kd/d); the motion jumps to Vs at time 0, step n is where the
//   position s(t) reaches n (first ~1/Vs after time 0, A29), the last one exactly at Tt.
//
// The reference below is written from those equations alone (long double, position by closed
// form per piece, step times by bisection), sharing no code with planner/profile.cpp.
//
//   accuracy_bench   (prints one line per profile and a RESULT line)
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/spsc_ring.hpp"
#include "planner/planner.hpp"
#include "rt/axis_feedback.hpp"
#include "rt/edge.hpp"

namespace {

using namespace stepmod;
using planner::AccelShape;
using LD = long double;

struct Profile {
  const char* name;
  AccelShape shape;
  std::int64_t n;
  double vs, vp, a, d;
};

LD factor(AccelShape s) {
  switch (s) {
    case AccelShape::kConstant:
      return 1.0L;
    case AccelShape::kTriangularS:
      return 2.0L;
    default:
      return 4.0L / 3.0L;
  }
}

// One ramp from v1 to v2 at rate a: position after tau (0 <= tau <= T).
struct RefRamp {
  AccelShape shape;
  LD v1, v2, a, T, D, sg;
  RefRamp(AccelShape s, LD from, LD to, LD rate) : shape(s), v1(from), v2(to), a(rate) {
    T = factor(s) * std::fabs(to - from) / rate;
    D = T * (from + to) / 2;
    sg = to >= from ? 1 : -1;
  }
  LD pos(LD t) const {
    if (T == 0) return 0;
    switch (shape) {
      case AccelShape::kConstant:
        return v1 * t + sg * a * t * t / 2;
      case AccelShape::kTriangularS: {
        if (t <= T / 2) return v1 * t + sg * a * t * t * t / (3 * T);
        const LD u = T - t;
        return D - (v2 * u - sg * a * u * u * u / (3 * T));
      }
      default: {
        const LD J = 4 * a / T, q = T / 4;
        if (t <= q) return v1 * t + sg * J * t * t * t / 6;
        if (t >= 3 * q) {
          const LD u = T - t;
          return D - (v2 * u - sg * J * u * u * u / 6);
        }
        const LD sq = v1 * q + sg * J * q * q * q / 6, vq = v1 + sg * J * q * q / 2, x = t - q;
        return sq + vq * x + sg * a * x * x / 2;
      }
    }
  }
};

struct RefMove {
  RefRamp up, down;
  LD tp = 0, vpk = 0, tt = 0;
  explicit RefMove(const Profile& p)
      : up(p.shape, p.vs, p.vp, p.a), down(p.shape, p.vp, p.vs, p.d) {
    const LD n = static_cast<LD>(p.n);
    if (up.D + down.D <= n) {
      vpk = p.vp;
      tp = (n - up.D - down.D) / p.vp;
    } else {
      const LD k = factor(p.shape);
      vpk = std::sqrt(static_cast<LD>(p.vs) * p.vs + 2 * n / (k / p.a + k / p.d));
      up = RefRamp(p.shape, p.vs, vpk, p.a);
      down = RefRamp(p.shape, vpk, p.vs, p.d);
      tp = 0;
    }
    tt = up.T + tp + down.T;
  }
  LD pos(LD t) const {
    if (t <= up.T) return up.pos(t);
    if (t <= up.T + tp) return up.D + vpk * (t - up.T);
    return up.D + vpk * tp + down.pos(std::min(t - up.T - tp, down.T));
  }
  // Ideal time of step n (1-based): s(t) = n by bisection; the last step at Tt.
  LD step_time(std::int64_t n, std::int64_t total, LD lo) const {
    if (n >= total) return tt;
    LD hi = tt;
    for (int i = 0; i < 100 && hi - lo > 1e-13L; ++i) {
      const LD mid = (lo + hi) / 2;
      if (pos(mid) < static_cast<LD>(n))
        lo = mid;
      else
        hi = mid;
    }
    return (lo + hi) / 2;
  }
};

// The planner's leading-edge times (ns from the motion's time 0) for the move.
std::vector<Nanos> planned(const Profile& p) {
  SpscRing<rt::Edge> ring(1u << 15);
  rt::AxisControl control;
  const planner::PlannerAxis axis{&ring, &control, {}};
  planner::Planner plan(std::span(&axis, 1));
  planner::MoveSpec m;
  m.steps = p.n;
  m.vs = p.vs;
  m.vp = p.vp;
  m.accel = {p.a, p.shape};
  m.decel = {p.d, p.shape};
  planner::Command c;
  c.epoch = 1;
  c.what = m;
  plan.submit(c);
  std::vector<Nanos> steps;
  Nanos origin = -1, now = 0;
  bool last = false;
  while (!last) {
    plan.service(now);
    rt::Edge e;
    while (ring.try_pop(e)) {
      // The motion's first edge (the direction edge) is at its time 0; the first step is at
      // least dir_setup after it, which every profile here satisfies (1/Vs >= 1 us).
      if ((e.flags & rt::edge_flag::kFirst) != 0) origin = e.t;
      if (e.dpos != 0) steps.push_back(e.t - origin);
      last = last || (e.flags & rt::edge_flag::kLast) != 0;
      now = e.t;
    }
  }
  return steps;
}

}  // namespace

int main() {
  // The worked values of the profile equations (manuals ch. 2), plus fast variants near the
  // hardware limits.
  const Profile profiles[] = {
      {"trapezoid", AccelShape::kConstant, 20'000, 1'000, 10'000, 10'000, 10'000},
      {"triangle", AccelShape::kConstant, 5'000, 1'000, 10'000, 10'000, 10'000},
      {"s-curve triangular", AccelShape::kTriangularS, 20'000, 1'000, 10'000, 10'000, 10'000},
      {"s-curve triangular (peak)", AccelShape::kTriangularS, 5'000, 1'000, 10'000, 10'000, 10'000},
      {"s-curve trapezoidal", AccelShape::kTrapezoidalS, 20'000, 1'000, 10'000, 10'000, 10'000},
      {"s-curve trapezoidal (peak)", AccelShape::kTrapezoidalS, 5'000, 1'000, 10'000, 10'000,
       10'000},
      {"unequal accel/decel", AccelShape::kConstant, 5'000, 1'000, 10'000, 20'000, 5'000},
      {"fast trapezoid", AccelShape::kConstant, 1'000'000, 1'000, 1'000'000, 2e6, 2e6},
      {"fast s-curve trapezoidal", AccelShape::kTrapezoidalS, 1'000'000, 1'000, 1'000'000, 2e6,
       1e6},
  };
  double worst = 0;
  for (const Profile& p : profiles) {
    const RefMove ref(p);
    const std::vector<Nanos> got = planned(p);
    double max_err = 0;
    std::int64_t at = 0;
    LD lo = 0;
    for (std::int64_t n = 1; n <= static_cast<std::int64_t>(got.size()); ++n) {
      const LD ideal = ref.step_time(n, p.n, lo);
      lo = ideal;
      const double err = static_cast<double>(std::fabs(static_cast<LD>(got[n - 1]) - ideal * 1e9L));
      if (err > max_err) {
        max_err = err;
        at = n;
      }
    }
    const bool count_ok = static_cast<std::int64_t>(got.size()) == p.n;
    if (!count_ok) max_err = 1e18;
    std::printf(
        "accuracy %-28s N=%-8lld steps %-8zu Tt %.6f s  max |scheduled - ideal| %.1f ns "
        "(step %lld)\n",
        p.name, static_cast<long long>(p.n), got.size(), static_cast<double>(ref.tt), max_err,
        static_cast<long long>(at));
    std::printf("RESULT bench=accuracy profile=\"%s\" max_err_ns=%.1f\n", p.name, max_err);
    if (max_err > worst) worst = max_err;
  }
  std::printf("RESULT bench=accuracy_max max_err_ns=%.1f\n", worst);
  return 0;
}
