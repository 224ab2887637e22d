#pragma once
// The manuals' profile math (their ch. 2) in steps, steps/s and steps/s^2, and the exact
// step-time solver built on it.
//
// A motion is a list of phases of constant jerk, so position is an exact piecewise cubic s(t).
// Step k (k = 1, 2, ...) happens when s(t) = k: the first pulse comes about 1/Vs after time 0
// and the last pulse of an N-step move exactly at Tt (the manuals' ch. 2, A29).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "planner/motion_request.hpp"
#include "rt/edge.hpp"

namespace stepmod::planner {

// Ramp-time factor k of an acceleration type: constant 1, triangular S 2, trapezoidal S 4/3.
double shape_factor(AccelShape shape) noexcept;
// T = k |V2 - V1| / A.
double ramp_time(double v1, double v2, const Ramp& r) noexcept;
// D = T (V1 + V2) / 2 = k |V2^2 - V1^2| / (2A).
double ramp_distance(double v1, double v2, const Ramp& r) noexcept;
// The rate that makes a ramp V1 -> V2 of `shape` exactly `distance` long.
double rate_for_distance(double v1, double v2, AccelShape shape, double distance) noexcept;

enum class ProfileKind : std::uint8_t {
  kConstantSpeed,  // vp <= vs: no ramps
  kTrapezoid,      // Da + Dd < N: cruise at Vp
  kTouch,          // Da + Dd = N: reaches Vp, no cruise
  kTriangle,       // Da + Dd > N: peak Vpk < Vp
};

// Classification (the manuals' ch. 2) and totals of a MoveSpec (times in s, distances in steps).
struct MoveProfile {
  ProfileKind kind = ProfileKind::kConstantSpeed;
  double vs = 0.0;                      // speed of the first and last pulse
  double vpk = 0.0;                     // cruise (trapezoid) or peak (triangle) speed
  double ta = 0.0, td = 0.0, tp = 0.0;  // accel, decel and cruise time
  double da = 0.0, dd = 0.0, dp = 0.0;  // accel, decel and cruise distance
  double tt = 0.0;                      // total time = time of the last step
};
MoveProfile classify_move(const MoveSpec& m) noexcept;
// The same over a length that need not be an integer (the interpolated path's length).
MoveProfile classify_length(double length, double vs, double vp, const Ramp& accel,
                            const Ramp& decel) noexcept;

// Speed of a constant-speed motion (vp <= vs): vp, or vs for vp = 0 (one-shot, the manuals' ch. 2).
inline double constant_speed(double vs, double vp) noexcept {
  return vp > 0.0 ? vp : vs;
}

// One piece of constant jerk: s(tau) = s0 + v0 tau + a0 tau^2/2 + j tau^3/6, 0 <= tau <= dur.
struct JerkPhase {
  double t0 = 0.0;   // start, s from the motion's time 0
  double dur = 0.0;  // s; +inf for an endless cruise
  double s0 = 0.0;   // position at the start, steps from the motion's start
  double s1 = 0.0;   // position at the end (+inf for an endless cruise)
  double v0 = 0.0, a0 = 0.0, j = 0.0;
  double inv_v0 = 0.0;  // 1/v0, for cruise phases
  enum Kind : std::uint8_t { kCruise, kQuadratic, kCubic } kind = kCruise;
  rt::Phase phase = rt::Phase::kCruise;

  double position(double tau) const noexcept {
    return s0 + tau * (v0 + tau * (a0 / 2 + tau * j / 6));
  }
  double velocity(double tau) const noexcept { return v0 + tau * (a0 + tau * j / 2); }
  double accel(double tau) const noexcept { return a0 + tau * j; }
};

// A motion's phases, in a fixed array: building and replanning never allocate.
class PhaseList {
 public:
  // 16 blend segments x (3 ramp phases + cruise) + final decel + slack.
  static constexpr std::size_t kCapacity = 96;

  // Starts an empty list at time t0 (s) and position s0 (steps) with speed v0.
  void reset(double t0, double s0, double v0) noexcept;
  // Appends the ramp from the present end speed to v2 (1 phase for constant, 3 for S-curves);
  // a non-positive rate or v2 equal to the present speed jumps (no phase).
  void add_ramp(double v2, const Ramp& r) noexcept;
  // Appends a ramp from the present end speed to v2 exactly `distance` steps long.
  void add_ramp_over(double v2, AccelShape shape, double distance) noexcept;
  // Appends a cruise of `distance` steps at the present speed (+inf: endless). <= 0: nothing.
  void add_cruise(double distance) noexcept;
  // Jumps the present end speed to v (constant-speed mode, starting speed).
  void set_speed(double v) noexcept { v_end_ = v; }

  std::size_t size() const noexcept { return n_; }
  bool empty() const noexcept { return n_ == 0; }
  bool overflowed() const noexcept { return overflow_; }
  const JerkPhase& operator[](std::size_t i) const noexcept { return ph_[i]; }
  double end_time() const noexcept { return t_end_; }
  double end_position() const noexcept { return s_end_; }
  double end_speed() const noexcept { return v_end_; }
  double start_time() const noexcept { return t_start_; }

  // Keeps the law up to time t (>= the list's start): the phase under way at t ends there, later
  // ones are dropped (a replan that keeps the steps planned before t: the path's hold).
  void truncate(double t) noexcept;

  // Evaluation at any time from the list's start (for tests and replanning).
  double position_at(double t) const noexcept;
  double velocity_at(double t) const noexcept;

 private:
  void push(double dur, double a0, double j, rt::Phase phase) noexcept;

  std::array<JerkPhase, kCapacity> ph_{};
  std::size_t n_ = 0;
  bool overflow_ = false;
  double t_start_ = 0.0, t_end_ = 0.0, s_end_ = 0.0, v_end_ = 0.0;
};

// Builders: fill `out` (from time 0, position 0) with a whole motion.
MoveProfile build_move(const MoveSpec& m, PhaseList& out) noexcept;
// A move's profile over `length` (need not be an integer) from time 0 and position s0.
MoveProfile build_length(double length, double vs, double vp, const Ramp& accel, const Ramp& decel,
                         PhaseList& out, double s0 = 0.0) noexcept;
// Endless: ramp vs -> vp (or jump to vp in constant-speed mode), then cruise forever.
void build_run(const RunSpec& r, PhaseList& out) noexcept;
// Blend moves (manuals 3601/3202 ch. 4-5, 3602 ch. 9; A21): each segment ramps from the previous
// speed within its length, the last one also holds the final deceleration to vs, ending exactly at
// the sum of the lengths.
void build_blend(const BlendSpec& b, PhaseList& out) noexcept;
std::int64_t blend_length(const BlendSpec& b) noexcept;

// Times of consecutive steps over a PhaseList. Steps must be asked for in increasing order;
// `reset` restarts at the list's first phase. The per-step path is a few flops: closed form for
// constant-acceleration phases, Newton seeded from the previous step for cubic ones.
class StepSolver {
 public:
  void reset(const PhaseList* list) noexcept {
    list_ = list;
    idx_ = 0;
    tau_ = 0.0;
    x_ = 0.0;
  }
  // Time (s from the motion's time 0) at which s(t) = k.
  double time_of(double k) noexcept {
    const PhaseList& l = *list_;
    while (idx_ + 1 < l.size() && k > l[idx_].s1) {
      ++idx_;
      tau_ = 0.0;
      x_ = 0.0;
    }
    const JerkPhase& p = l[idx_];
    const double x = k - p.s0;
    if (k > p.s1) [[unlikely]] {
      // Past the end of the list (only when rounding leaves the end a hair short of an integer):
      // continue at the end speed.
      const double v = l.end_speed() > 1e-3 ? l.end_speed() : 1e-3;
      return p.t0 + p.dur + (k - p.s1) / v;
    }
    double tau = 0.0;
    switch (p.kind) {
      case JerkPhase::kCruise:
        tau = x * p.inv_v0;
        break;
      case JerkPhase::kQuadratic: {
        // Stable root of v0 tau + a0 tau^2 / 2 = x (no cancellation for either sign of a0).
        double disc = p.v0 * p.v0 + 2.0 * p.a0 * x;
        if (disc < 0.0) disc = 0.0;
        const double den = p.v0 + std::sqrt(disc);
        tau = den > 0.0 ? 2.0 * x / den : 0.0;
        break;
      }
      default:
        tau = newton(p, x);
        break;
    }
    if (tau < 0.0) tau = 0.0;
    if (tau > p.dur) tau = p.dur;
    tau_ = tau;
    x_ = x;
    return p.t0 + tau;
  }
  std::size_t phase_index() const noexcept { return idx_; }

 private:
  double newton(const JerkPhase& p, double x) noexcept;

  const PhaseList* list_ = nullptr;
  std::size_t idx_ = 0;
  double tau_ = 0.0;  // local time of the previous step in phase idx_
  double x_ = 0.0;    // its local position
};

}  // namespace stepmod::planner
