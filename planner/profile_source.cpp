#include "planner/profile_source.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stepmod::planner {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

ProfileSource::Start ProfileSource::begin(const Facts& f, std::int64_t end) noexcept {
  solver_.reset(&phases_);
  vs_ = f.vs;
  decel_ = f.decel;
  constant_speed_ = f.constant_speed;
  can_change_speed_ = f.can_change_speed;
  dir_ = f.dir;
  return Start{f.dir, end};
}

ProfileSource::Start ProfileSource::start(const MoveSpec& m) noexcept {
  build_move(m, phases_);
  return begin({m.dir, m.vs, m.decel, m.vp <= m.vs, false}, m.steps);
}

ProfileSource::Start ProfileSource::start(const RunSpec& r) noexcept {
  build_run(r, phases_);
  return begin({r.dir, r.vs, r.decel, r.vp <= r.vs, true}, kEndless);
}

ProfileSource::Start ProfileSource::start(const BlendSpec& b) noexcept {
  build_blend(b, phases_);
  return begin({b.dir, b.vs, b.final_decel, false, false}, blend_length(b));
}

FirstStep ProfileSource::first_step(std::int64_t end) noexcept {
  const rt::Phase phase = phases_.empty() ? rt::Phase::kCruise : phases_[0].phase;
  if (end == 1) return FirstStep{true, phases_.end_time(), phase};
  StepSolver probe;
  probe.reset(&phases_);
  return FirstStep{true, probe.time_of(1.0), phase};
}

rt::Phase ProfileSource::phase_at(double t) const noexcept {
  for (std::size_t i = 0; i < phases_.size(); ++i) {
    if (t <= phases_[i].t0 + phases_[i].dur) return phases_[i].phase;
  }
  return phases_.empty() ? rt::Phase::kCruise : phases_[phases_.size() - 1].phase;
}

void ProfileSource::change_speed(std::int64_t k, double tk, const SpeedChange& c) noexcept {
  // Replanned from step k (the newest planned: at most the lookahead ahead of the pulse thread).
  const double v = phases_.velocity_at(tk);
  phases_.reset(tk, static_cast<double>(k), v);
  phases_.add_ramp(c.vp, c.vp > v ? c.accel : c.decel);
  phases_.add_cruise(kInf);
  decel_ = c.decel;
  constant_speed_ = false;
  solver_.reset(&phases_);
}

std::int64_t ProfileSource::stop_end(std::int64_t k, double t, const Ramp& ramp) const noexcept {
  const double v = phases_.velocity_at(t);
  if (constant_speed_ || v <= vs_ * (1.0 + 1e-9) || ramp.rate <= 0.0) return k;
  return k + std::max<std::int64_t>(1, std::llround(ramp_distance(v, vs_, ramp)));
}

void ProfileSource::replan_to_end(std::int64_t k, double tk, std::int64_t end, const Ramp& ramp,
                                  bool exact_ramp) noexcept {
  const double v = phases_.velocity_at(tk);
  const double remaining = static_cast<double>(end - k);
  phases_.reset(tk, static_cast<double>(k), v);
  if (v <= vs_ || ramp.rate <= 0.0) {
    phases_.add_cruise(remaining);
  } else {
    const double d = ramp_distance(v, vs_, ramp);
    if (!exact_ramp && d <= remaining) {
      phases_.add_cruise(remaining - d);
      phases_.add_ramp(vs_, ramp);
    } else {
      // The ramp alone covers the rest: its rate is adjusted so that it ends exactly on `end`
      // (a little gentler or steeper than asked for a stop; steeper when a registration count
      // leaves too few steps).
      phases_.add_ramp_over(vs_, ramp.shape, remaining);
    }
  }
  can_change_speed_ = false;
  solver_.reset(&phases_);
}

}  // namespace stepmod::planner
