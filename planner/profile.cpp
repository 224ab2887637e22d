#include "planner/profile.hpp"

#include <algorithm>
#include <limits>

namespace stepmod::planner {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// Speeds are never zero on the motion path (the manuals' minimum is 1 step/s); this floor only
// keeps bad input from dividing by zero.
constexpr double kMinSpeed = 1e-3;
}  // namespace

double shape_factor(AccelShape shape) noexcept {
  switch (shape) {
    case AccelShape::kTriangularS:
      return 2.0;
    case AccelShape::kTrapezoidalS:
      return 4.0 / 3.0;
    default:
      return 1.0;
  }
}

double ramp_time(double v1, double v2, const Ramp& r) noexcept {
  if (r.rate <= 0.0) return 0.0;  // no rate: a jump
  return shape_factor(r.shape) * std::fabs(v2 - v1) / r.rate;
}

double ramp_distance(double v1, double v2, const Ramp& r) noexcept {
  return ramp_time(v1, v2, r) * (v1 + v2) / 2.0;
}

double rate_for_distance(double v1, double v2, AccelShape shape, double distance) noexcept {
  if (distance <= 0.0) return 0.0;
  return shape_factor(shape) * std::fabs(v2 * v2 - v1 * v1) / (2.0 * distance);
}

MoveProfile classify_move(const MoveSpec& m) noexcept {
  return classify_length(static_cast<double>(m.steps), m.vs, m.vp, m.accel, m.decel);
}

MoveProfile classify_length(double n, double vs_in, double vp, const Ramp& accel,
                            const Ramp& decel) noexcept {
  MoveProfile p;
  p.vs = std::max(vs_in, kMinSpeed);
  if (vp <= vs_in) {
    p.kind = ProfileKind::kConstantSpeed;
    p.vpk = std::max(constant_speed(vs_in, vp), kMinSpeed);
    p.vs = p.vpk;
    p.dp = n;
    p.tp = n / p.vpk;
    p.tt = p.tp;
    return p;
  }
  const double vs = p.vs;
  const double da = ramp_distance(vs, vp, accel);
  const double dd = ramp_distance(vp, vs, decel);
  const double sum = da + dd;
  if (std::fabs(sum - n) <= 1e-9 * n) {
    p.kind = ProfileKind::kTouch;
    p.vpk = vp;
  } else if (sum < n) {
    p.kind = ProfileKind::kTrapezoid;
    p.vpk = vp;
    p.dp = n - sum;
    p.tp = p.dp / vp;
  } else {
    // Vpk^2 = Vs^2 + 2N / (ka/a + kd/d); a missing rate is a jump and contributes no distance.
    p.kind = ProfileKind::kTriangle;
    double denom = 0.0;
    if (accel.rate > 0.0) denom += shape_factor(accel.shape) / accel.rate;
    if (decel.rate > 0.0) denom += shape_factor(decel.shape) / decel.rate;
    p.vpk = std::sqrt(vs * vs + 2.0 * n / denom);
  }
  p.da = ramp_distance(vs, p.vpk, accel);
  p.dd = ramp_distance(p.vpk, vs, decel);
  p.ta = ramp_time(vs, p.vpk, accel);
  p.td = ramp_time(p.vpk, vs, decel);
  p.tt = p.ta + p.tp + p.td;
  return p;
}

void PhaseList::reset(double t0, double s0, double v0) noexcept {
  n_ = 0;
  overflow_ = false;
  t_start_ = t_end_ = t0;
  s_end_ = s0;
  v_end_ = v0;
}

void PhaseList::push(double dur, double a0, double j, rt::Phase phase) noexcept {
  if (!(dur > 0.0)) return;
  if (n_ == kCapacity) {
    overflow_ = true;
    return;
  }
  JerkPhase& p = ph_[n_++];
  p.t0 = t_end_;
  p.dur = dur;
  p.s0 = s_end_;
  p.v0 = std::max(v_end_, kMinSpeed);
  p.a0 = a0;
  p.j = j;
  p.inv_v0 = 1.0 / p.v0;
  p.kind = j != 0.0 ? JerkPhase::kCubic : (a0 != 0.0 ? JerkPhase::kQuadratic : JerkPhase::kCruise);
  p.phase = phase;
  p.s1 = p.position(dur);
  t_end_ += dur;
  s_end_ = p.s1;
  v_end_ = p.velocity(dur);
}

void PhaseList::add_ramp(double v2, const Ramp& r) noexcept {
  const double v1 = v_end_;
  if (r.rate <= 0.0 || v1 == v2) {
    v_end_ = v2;
    return;
  }
  const double t = ramp_time(v1, v2, r);
  const double sg = v2 > v1 ? 1.0 : -1.0;
  const double a = sg * r.rate;
  const rt::Phase ph = v2 > v1 ? rt::Phase::kAccel : rt::Phase::kDecel;
  switch (r.shape) {
    case AccelShape::kTriangularS: {
      // Acceleration rises linearly 0 -> A over T/2 and falls back to 0 (the manuals' ch. 2).
      const double j = 2.0 * a / t;
      push(t / 2, 0.0, j, ph);
      push(t / 2, a, -j, ph);
      break;
    }
    case AccelShape::kTrapezoidalS: {
      // Jerk T/4, constant acceleration T/2, jerk T/4 with J = 4A/T (the manuals' ch. 2).
      const double j = 4.0 * a / t;
      push(t / 4, 0.0, j, ph);
      push(t / 2, a, 0.0, ph);
      push(t / 4, a, -j, ph);
      break;
    }
    default:
      push(t, a, 0.0, ph);
      break;
  }
  // The integrated end speed differs from v2 by rounding only; pin it so errors do not chain.
  v_end_ = v2;
}

void PhaseList::add_ramp_over(double v2, AccelShape shape, double distance) noexcept {
  add_ramp(v2, Ramp{rate_for_distance(v_end_, v2, shape, distance), shape});
}

void PhaseList::add_cruise(double distance) noexcept {
  if (!(distance > 0.0)) return;
  if (n_ == kCapacity) {
    overflow_ = true;
    return;
  }
  const double v = std::max(v_end_, kMinSpeed);
  JerkPhase& p = ph_[n_++];
  p.t0 = t_end_;
  p.s0 = s_end_;
  p.v0 = v;
  p.a0 = 0.0;
  p.j = 0.0;
  p.inv_v0 = 1.0 / v;
  p.kind = JerkPhase::kCruise;
  p.phase = rt::Phase::kCruise;
  if (distance == kInf) {
    p.dur = kInf;
    p.s1 = kInf;
  } else {
    p.dur = distance / v;
    p.s1 = s_end_ + distance;
  }
  t_end_ += p.dur;
  s_end_ = p.s1;
}

void PhaseList::truncate(double t) noexcept {
  if (t < t_start_) t = t_start_;
  for (std::size_t i = 0; i < n_; ++i) {
    JerkPhase& p = ph_[i];
    if (t < p.t0 + p.dur) {
      const double tau = t - p.t0;
      n_ = tau > 0.0 ? i + 1 : i;
      if (tau > 0.0) {
        p.dur = tau;
        p.s1 = p.position(tau);
      }
      t_end_ = t;
      s_end_ = tau > 0.0 ? p.s1 : p.s0;
      v_end_ = p.velocity(tau);
      return;
    }
  }
  // At or after the list's end: nothing to drop.
}

double PhaseList::position_at(double t) const noexcept {
  if (n_ == 0 || t <= t_start_) return n_ == 0 ? s_end_ : ph_[0].s0;
  for (std::size_t i = 0; i < n_; ++i) {
    const JerkPhase& p = ph_[i];
    if (t <= p.t0 + p.dur) return p.position(t - p.t0);
  }
  return s_end_ + (t - t_end_) * v_end_;
}

double PhaseList::velocity_at(double t) const noexcept {
  if (n_ == 0) return v_end_;
  if (t <= t_start_) return ph_[0].v0;
  for (std::size_t i = 0; i < n_; ++i) {
    const JerkPhase& p = ph_[i];
    if (t <= p.t0 + p.dur) return p.velocity(t - p.t0);
  }
  return v_end_;
}

MoveProfile build_move(const MoveSpec& m, PhaseList& out) noexcept {
  return build_length(static_cast<double>(m.steps), m.vs, m.vp, m.accel, m.decel, out);
}

MoveProfile build_length(double length, double vs, double vp, const Ramp& accel, const Ramp& decel,
                         PhaseList& out, double s0) noexcept {
  const MoveProfile p = classify_length(length, vs, vp, accel, decel);
  out.reset(0.0, s0, p.vs);
  if (p.kind == ProfileKind::kConstantSpeed) {
    out.add_cruise(length);
    return p;
  }
  out.add_ramp(p.vpk, accel);
  out.add_cruise(p.dp);
  out.add_ramp(p.vs, decel);
  return p;
}

void build_run(const RunSpec& r, PhaseList& out) noexcept {
  if (r.vp <= r.vs) {
    out.reset(0.0, 0.0, std::max(constant_speed(r.vs, r.vp), kMinSpeed));
  } else {
    out.reset(0.0, 0.0, std::max(r.vs, kMinSpeed));
    out.add_ramp(r.vp, r.accel);
  }
  out.add_cruise(kInf);
}

std::int64_t blend_length(const BlendSpec& b) noexcept {
  std::int64_t total = 0;
  const std::size_t n = std::min<std::size_t>(b.count, kMaxBlendSegments);
  for (std::size_t i = 0; i < n; ++i) total += std::max<std::int64_t>(b.segments[i].length, 0);
  return total;
}

void build_blend(const BlendSpec& b, PhaseList& out) noexcept {
  const double vs = std::max(b.vs, kMinSpeed);
  out.reset(0.0, 0.0, vs);
  const std::size_t n = std::min<std::size_t>(b.count, kMaxBlendSegments);
  double end = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const BlendSegment& seg = b.segments[i];
    end += static_cast<double>(std::max<std::int64_t>(seg.length, 0));
    out.add_ramp(std::max(seg.speed, kMinSpeed), seg.ramp);
    if (i + 1 < n) {
      // Cruise to the segment's end, measured from the absolute end so rounding never chains.
      out.add_cruise(end - out.end_position());
    } else {
      // A21: the final deceleration lies inside the last segment and ends exactly at sum L.
      const double df = ramp_distance(out.end_speed(), vs, b.final_decel);
      out.add_cruise(end - df - out.end_position());
      out.add_ramp(vs, b.final_decel);
    }
  }
}

double StepSolver::newton(const JerkPhase& p, double x) noexcept {
  // Seed: the previous step's local time plus the distance over its speed (one Newton step
  // from a point already on the curve), or x/v0 at the phase start.
  double tau;
  if (tau_ > 0.0) {
    tau = tau_ + (x - x_) / p.velocity(tau_);
  } else {
    tau = x * p.inv_v0;
  }
  for (int i = 0; i < 40; ++i) {
    if (tau < 0.0) tau = 0.0;
    if (tau > p.dur) tau = p.dur;
    const double f = tau * (p.v0 + tau * (p.a0 / 2 + tau * p.j / 6)) - x;
    const double fp = p.velocity(tau);
    if (!(fp > 0.0)) break;
    const double d = f / fp;
    tau -= d;
    if (std::fabs(d) < 1e-13) break;
  }
  return tau;
}

}  // namespace stepmod::planner
