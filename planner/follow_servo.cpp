#include "planner/follow_servo.hpp"

#include <algorithm>
#include <cmath>

namespace stepmod::planner {

namespace {
Nanos to_ns(double seconds) noexcept {
  return seconds_to_ns(seconds);
}
}  // namespace

Answer FollowServo::next(const StepProgress& p, const StepWindow& w, SourceStep& out) noexcept {
  FollowStep st;
  switch (decide(p.tk_ns, p.k == 0, w.now, st)) {
    case Next::kWait:
      return Answer::kWait;
    case Next::kFinish:
      return Answer::kEnd;
    case Next::kStep:
      break;
  }
  out.t = std::max(st.t, w.last_edge + 1);
  out.ts = p.tk;  // the follow law has no time base of its own
  out.dir = st.dir < 0 ? Direction::kCcw : Direction::kCw;
  out.phase = st.phase;
  out.width = st.width;
  out.not_before = w.now;
  taken(st);
  return Answer::kStep;
}

FollowServo::Next FollowServo::decide(Nanos prev_t, bool first, Nanos now,
                                      FollowStep& out) noexcept {
  const FollowSpec& s = spec_;
  const double vs = std::max(s.vs, 1.0);
  const double vmax = std::max(s.vmax, 1.0);
  const double cap = s.accel > 0.0 ? vmax : std::clamp(s.speed, 1.0, vmax);
  // A step at the present speed would already be overdue: the axis has been waiting for its
  // target, so it starts again from rest.
  if (v_ > 0.0 && prev_t + to_ns(1.0 / v_) < now) v_ = 0.0;

  const std::int64_t e = s.target - pos_;
  const int want = e > 0 ? 1 : (e < 0 ? -1 : 0);
  int dir = want;
  double v = 0.0;
  if (v_ > 0.0 && want != dir_) {
    // On or past the target while moving: ramp down to vs at d, then stop.
    const double v2 = v_ * v_ - 2.0 * s.decel;
    if (s.decel > 0.0 && v_ > vs && v2 >= vs * vs) {
      v = std::sqrt(v2);
      dir = dir_;
    } else {
      v_ = 0.0;
    }
  }
  if (v == 0.0) {
    if (want == 0) {
      v_ = 0.0;
      return finishing_ ? Next::kFinish : Next::kWait;
    }
    const double n = static_cast<double>(want > 0 ? e : -e);
    v = cap;
    if (s.accel > 0.0) v = std::min(v, v_ > 0.0 ? std::sqrt(v_ * v_ + 2.0 * s.accel) : vs);
    if (s.decel > 0.0) {
      v = std::min(v, std::sqrt(vs * vs + 2.0 * s.decel * (n - 1.0)));
      // It cannot slow down faster than d either (the target came closer than planned for).
      if (v_ > 0.0) v = std::max(v, std::sqrt(std::max(0.0, v_ * v_ - 2.0 * s.decel)));
    }
    v = std::max(v, 1.0);
  }
  time_step(prev_t, first, now, v, dir, cap, out);
  return Next::kStep;
}

void FollowServo::time_step(Nanos prev_t, bool first, Nanos now, double v, int dir, double cap,
                            FollowStep& out) const noexcept {
  const FollowSpec& s = spec_;
  // Time of the step.
  out.from_rest = v_ <= 0.0;
  if (!out.from_rest) {
    out.t = prev_t + to_ns(2.0 / (v_ + v));
  } else {
    out.t = now + start_delay_;
    if (!first) out.t = std::max(out.t, prev_t + to_ns(1.0 / v));
  }
  out.phase = rt::Phase::kCruise;
  if (!out.from_rest && dir == dir_) {
    if (v > v_ * (1.0 + 1e-9)) out.phase = rt::Phase::kAccel;
    if (v < v_ * (1.0 - 1e-9)) out.phase = rt::Phase::kDecel;
  }
  // The trailing edge goes with the step (the next step is not known yet): the configured width,
  // or half the shortest period the next step can come at.
  const double v_up = s.accel > 0.0 ? std::sqrt(v * v + 2.0 * s.accel) : std::max(v, cap);
  out.width = std::max<Nanos>(1, std::min(pulse_ns_, to_ns(0.5 / v_up)));
  out.dir = dir;
  out.v = v;
}

}  // namespace stepmod::planner
