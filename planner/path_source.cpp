#include "planner/path_source.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stepmod::planner {

PathSource::Start PathSource::start(const PathSpec& spec, PathCoordinate c) noexcept {
  law_.init(spec, c);
  vs_ = spec.vs;
  build_length(law_.length(), spec.vs, spec.vp, spec.accel, spec.decel, phases_);
  seg_ = 0;
  count_ = 0;
  u_ = 0.0;
  u_lim_ = 1.0;
  lim_seg_ = law_.segments() - 1;
  lim_target_ = law_.end();
  return begin();
}

PathSource::Start PathSource::resume(double vp, const Ramp& accel, const Ramp& decel) noexcept {
  const double s0 = u_lim_ * law_.length();
  build_length(std::max(0.0, law_.length() - s0), vs_, vp, accel, decel, phases_, s0);
  u_lim_ = 1.0;
  lim_seg_ = law_.segments() - 1;
  lim_target_ = law_.end();
  return begin();
}

PathSource::Start PathSource::begin() noexcept {
  solver_.reset(&phases_);
  next_valid_ = false;
  const std::int64_t n = remaining();
  if (n == 0) return Start{Direction::kCw, 0};
  return Start{peek().dir, n};
}

std::int64_t PathSource::hold(double t, const Ramp& ramp) noexcept {
  if (t < phases_.start_time()) t = phases_.start_time();
  if (t >= phases_.end_time()) return remaining();
  const double v = phases_.velocity_at(t);
  const double s_t = phases_.position_at(t);
  const double d = v > vs_ && ramp.rate > 0.0 ? ramp_distance(v, vs_, ramp) : 0.0;
  if (s_t + d >= phases_.end_position()) return remaining();  // it stops as soon anyway
  phases_.truncate(t);
  if (d > 0.0) phases_.add_ramp(vs_, ramp);
  const double len = law_.length();
  u_lim_ = len > 0.0 ? std::clamp(phases_.end_position() / len, 0.0, 1.0) : 1.0;
  // The stop point's segment and the count reached there (never behind the steps already taken:
  // they all lie at or before t).
  std::size_t i = seg_;
  while (i + 1 < law_.segments() && u_lim_ > law_.segment_end(i)) ++i;
  lim_seg_ = i;
  lim_target_ = law_.reached(i, u_lim_);
  if (i == seg_) {
    const int dir = law_.direction(i);
    if ((dir > 0 && lim_target_ < count_) || (dir < 0 && lim_target_ > count_)) {
      lim_target_ = count_;
    }
  }
  solver_.reset(&phases_);
  next_valid_ = false;
  return remaining();
}

std::int64_t PathSource::remaining() const noexcept {
  std::int64_t n = 0;
  std::int64_t at = count_;
  for (std::size_t i = seg_; i <= lim_seg_; ++i) {
    const std::int64_t tgt = i == lim_seg_ ? lim_target_ : law_.target(i);
    n += tgt > at ? tgt - at : at - tgt;
    at = tgt;
  }
  return n;
}

void PathSource::plan_next() noexcept {
  std::size_t i = seg_;
  std::int64_t tgt = i == lim_seg_ ? lim_target_ : law_.target(i);
  while (count_ == tgt && i < lim_seg_) {
    ++i;
    tgt = i == lim_seg_ ? lim_target_ : law_.target(i);
  }
  const int dir = tgt > count_ ? 1 : -1;
  Next& nx = next_;
  nx.seg = i;
  nx.n = count_ + dir;
  nx.step.dir = dir > 0 ? Direction::kCw : Direction::kCcw;
  const double len = law_.length();
  if (nx.n == tgt && i + 1 == law_.segments() && u_lim_ >= 1.0) {
    // The path's last step: exactly the end point, at the profile's end.
    nx.u = 1.0;
    nx.step.t = phases_.end_time();
    nx.step.phase = phases_.empty() ? rt::Phase::kCruise : phases_[phases_.size() - 1].phase;
  } else {
    // A step before the previous one's point (rounding near a reversal) is taken at that point.
    nx.u = law_.solve(i, static_cast<double>(nx.n), u_);
    nx.step.t = solver_.time_of(nx.u * len);
    nx.step.phase = phases_[solver_.phase_index()].phase;
  }
  next_valid_ = true;
}

FirstStep PathSource::first_step(std::int64_t /*end*/) noexcept {
  const rt::Phase phase = phases_.empty() ? rt::Phase::kCruise : phases_[0].phase;
  return FirstStep{true, peek().t, phase};
}

}  // namespace stepmod::planner
