// AxisPlanner: a motion's start (which step source, group start in two halves) and its end by an
// immediate stop.
#include <algorithm>
#include <variant>

#include "planner/axis_planner.hpp"

namespace stepmod::planner {

AxisPlanner::SourceStart AxisPlanner::start_source(const Command& c) noexcept {
  if (const auto* follow = std::get_if<FollowStart>(&c.what)) {
    // Steps and their direction come from the servo as the target moves.
    follow_.start(follow->spec);
    return {&follow_, follow->spec.target < 0 ? Direction::kCcw : Direction::kCw, kEndless};
  }
  if (c.kind() == RequestKind::kPath || c.kind() == RequestKind::kPathResume) return start_path(c);
  ProfileSource::Start st{};
  if (const auto* move = std::get_if<MoveSpec>(&c.what)) {
    st = profile_.start(*move);
  } else if (const auto* run = std::get_if<RunSpec>(&c.what)) {
    st = profile_.start(*run);
  } else {
    st = profile_.start(blend_);
  }
  return {&profile_, st.dir, st.end};
}

bool AxisPlanner::prepare_start(const Command& c, Nanos now) noexcept {
  check_abort();
  now_ = std::max(now_, now - slip());
  resolve_cut(true);
  if (control_ != nullptr && c.epoch <= control_->abort_epoch.load(std::memory_order_acquire)) {
    return false;  // aborted before it started
  }
  if (c.epoch <= last_motion_epoch_) return false;  // stale or repeated
  // A new motion replaces one that is still being planned: that one ends on its newest step.
  if (m_.active) finish_at_frontier();
  if (c.kind() != RequestKind::kPath && c.kind() != RequestKind::kPathResume) discard_path();

  const SourceStart st = start_source(c);
  Motion m;
  m.active = true;
  m.held = true;
  m.epoch = c.epoch;
  m.group = c.group.id;
  m.at.end = st.end;
  publish_motion(m, st.source->start_speed());  // before any of its edges is pushed
  out_.begin(c.epoch, st.dir, st.end > 0 ? st.source->first_step(st.end) : FirstStep{});

  source_ = st.source;
  last_motion_epoch_ = c.epoch;
  last_motion_aborted_ = false;
  m_ = m;
  return true;
}

Nanos AxisPlanner::earliest_origin(Nanos now) const noexcept {
  // The direction line's set-up before the first step may push time 0 later (out_.lead()).
  return std::max(now + opt_.start_delay_ns, out_.last_t()) + out_.lead();
}

void AxisPlanner::launch(Nanos origin) noexcept {
  if (!m_.active || !m_.held) return;  // aborted while it waited for its group
  m_.held = false;
  m_.at.origin = origin;
  m_.at.tk_ns = origin;
  if (m_.at.end <= 0) {
    finish_at_frontier();  // nothing to move: one marker edge tells the pulse thread it ended
    return;
  }
  out_.launch(origin);
}

void AxisPlanner::publish_motion(const Motion& m, double vs) noexcept {
  if (control_ == nullptr) return;
  // A rack's modules number their groups each on their own: the domain keeps them apart.
  const std::uint32_t key =
      m.group == 0 ? 0
                   : (1 + (m.group - 1) % 0x00FF'FFFFu) | std::uint32_t{opt_.group_domain} << 24;
  control_->motion_group.store(rt::pack_epoch(m.epoch, key), std::memory_order_release);
  control_->motion_vs.store(rt::pack_epoch(m.epoch, rt::vs_interval_ns(vs)),
                            std::memory_order_release);
}

void AxisPlanner::check_abort() noexcept {
  if (control_ == nullptr) return;
  const std::uint32_t a = control_->abort_epoch.load(std::memory_order_acquire);
  if (a == seen_abort_) return;
  seen_abort_ = a;
  if (last_motion_epoch_ != 0 && last_motion_epoch_ <= a) {
    resolve_cut(true);
    abort_last_motion();
  }
}

void AxisPlanner::abort_last_motion() noexcept {
  if (last_motion_aborted_ || last_motion_epoch_ == 0) return;
  last_motion_aborted_ = true;
  discard_path();
  m_.active = false;
  out_.abort(last_motion_epoch_);
}

}  // namespace stepmod::planner
