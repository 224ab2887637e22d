// AxisPlanner: command dispatch, and the commands that change a running motion's law.
#include <algorithm>
#include <type_traits>
#include <variant>

#include "planner/axis_planner.hpp"

namespace stepmod::planner {

void AxisPlanner::apply(const Command& c, Nanos now) noexcept {
  check_abort();
  if (c.starts_motion()) {
    resolve_cut(true);
    if (prepare_start(c, now)) launch(earliest_origin(now));
    return;
  }
  now -= slip();  // from here on: the running motion's time base
  now_ = std::max(now_, now);
  resolve_cut(true);
  const std::uint32_t epoch = c.epoch;
  std::visit(
      [&](const auto& p) {
        using P = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<P, FollowUpdate>) {
          follow_update(epoch, p.spec);
        } else if constexpr (std::is_same_v<P, SpeedChange>) {
          change_speed(epoch, p);
        } else if constexpr (std::is_same_v<P, StopSpec>) {
          if (follows_path(epoch)) {
            hold_path(std::max(now + opt_.start_delay_ns, path_frontier()), p.ramp);
          } else {
            stop(epoch, p);
          }
        } else if constexpr (std::is_same_v<P, PathHold>) {
          // Alone (the Planner holds every axis of the path together).
          if (follows_path(epoch)) {
            hold_path(std::max(now + opt_.start_delay_ns, path_frontier()), p.ramp);
          }
        } else if constexpr (std::is_same_v<P, StopAfterSpec>) {
          stop_after(epoch, p);
        } else if constexpr (std::is_same_v<P, AbortSpec>) {
          if (epoch == last_motion_epoch_) abort_last_motion();
        } else if constexpr (std::is_same_v<P, GpoSpec>) {
          out_.gpo(p.level, now);
        } else if constexpr (std::is_same_v<P, PulseFormatSpec>) {
          out_.pulse_format(p.step_dir, now, m_.active);
        }
      },
      c.what);
}

void AxisPlanner::change_speed(std::uint32_t epoch, const SpeedChange& c) noexcept {
  // Only a run's profile changes speed (ProfileSource::can_change_speed).
  if (!m_.active || m_.held || source_ != &profile_ || epoch != m_.epoch) return;
  if (!profile_.can_change_speed() || !(c.vp > 0.0)) return;
  profile_.change_speed(m_.at.k, m_.at.tk, c);
}

void AxisPlanner::follow_update(std::uint32_t epoch, const FollowSpec& f) noexcept {
  if (!m_.active || source_ != &follow_ || epoch != m_.epoch) return;
  follow_.update(f);
}

}  // namespace stepmod::planner
