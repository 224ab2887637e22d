#pragma once
// One axis of the planner: applies Commands to the axis' motion and turns the motion into timed
// edges in the axis' ring. Owned and run by the planner thread only. One job per file:
//   axis_apply.cpp     command dispatch (apply) and the commands that change a running motion
//   axis_start.cpp     a motion's start: which step source, group start (prepare/launch), aborts
//   axis_fill.cpp      filling the ring with the one fill loop (step_loop.hpp), the refill time
//   axis_stops.cpp     controlled stops: the profile's replans and the cut handshake
//   axis_path.cpp      this axis' part of an interpolated path (hold, resume, the path book)
#include <array>
#include <cstdint>
#include <limits>

#include "planner/edge_emitter.hpp"
#include "planner/follow_servo.hpp"
#include "planner/motion_request.hpp"
#include "planner/path_source.hpp"
#include "planner/planner.hpp"
#include "planner/profile.hpp"
#include "planner/profile_source.hpp"
#include "planner/step_source.hpp"
#include "rt/edge.hpp"

namespace stepmod::planner {

// An axis with nothing to do asks to be serviced again this far ahead; a submit wakes it anyway.
inline constexpr Nanos kIdleServiceInterval = 10 * kNsPerSec;

class AxisPlanner {
 public:
  AxisPlanner(const PlannerAxis& axis, const PlannerOptions& options) noexcept;
  AxisPlanner(const AxisPlanner&) = delete;
  AxisPlanner& operator=(const AxisPlanner&) = delete;

  // Applies one command for this axis at time `now` (a start: prepare_start + launch at once).
  void apply(const Command& c, Nanos now) noexcept;
  // A blend start's segment table, copied out of the planner's blend slot before apply().
  void take_blend(const BlendSpec& b) noexcept { blend_ = b; }
  // Group start, in two halves: prepare_start sets the motion up and holds it (no edge); false if
  // the start is stale or aborted. earliest_origin is the soonest time 0 it could have at `now`;
  // launch gives it its time 0 (>= earliest_origin) and lets it run.
  bool prepare_start(const Command& c, Nanos now) noexcept;
  Nanos earliest_origin(Nanos now) const noexcept;
  void launch(Nanos origin) noexcept;
  // Pushes edges while the ring has room, up to now + lookahead. Returns the time by which it
  // must be called again.
  Nanos fill(Nanos now) noexcept { return fill(now, slip()); }
  // The same with the motion's slip as read by the caller (a path's members: one read for all).
  Nanos fill(Nanos now, Nanos slip) noexcept;
  // How far the pulse thread has slipped the newest motion (rt/slip.hpp): its planned time t is
  // written at t + slip(). Wall-clock times (now, a trigger's timestamp) are converted to the
  // motion's time base with it; a start from rest is planned on the wall clock (no slip yet).
  Nanos slip() const noexcept;

  // Introspection (tests, diagnostics).
  bool active() const noexcept { return m_.active; }         // a motion is still being planned
  std::uint32_t epoch() const noexcept { return m_.epoch; }  // newest motion's epoch
  std::int64_t planned_steps() const noexcept { return m_.at.k; }  // steps generated so far
  // Speed at the newest planned step (steps/s; a path motion: the path's vector speed), 0 when
  // idle.
  double frontier_speed() const noexcept;
  // Steps of the newest motion planned at or before t (from the recent history).
  std::int64_t planned_steps_at(Nanos t) const noexcept;
  bool step_dir_format() const noexcept { return out_.step_dir_format(); }

  // The interpolated path (planner/path_source.hpp). The planner applies a hold to every axis of
  // the path (PathHold, sent on any one of them) from one common time; the book records which
  // path is held and resumable across the axes (planner.hpp).
  void set_path_book(PathBook* book) noexcept { book_ = book; }
  // Takes an immediate stop published in AxisControl::abort_epoch into account now.
  void poll_abort() noexcept { check_abort(); }
  // The path this axis' newest motion follows (its group id), while it runs or is held; 0 if
  // its newest motion is not a path, or its path was discarded.
  std::uint32_t path_id() const noexcept { return path_state_ == PathState::kNone ? 0 : path_id_; }
  // Motion `epoch` of this axis is a path that runs or is held (it may have made all its steps).
  bool follows_path(std::uint32_t epoch) const noexcept {
    return path_state_ != PathState::kNone && epoch == last_motion_epoch_;
  }
  // The newest step this axis has planned of the path it follows (none: min), also when that
  // was its last: a path step is planned (committed to the emitter) only once it lies within the
  // lookahead, so this is never more than a lookahead ahead of the time it was planned at.
  Nanos path_frontier() const noexcept {
    return path_state_ != PathState::kNone && m_.at.k > 0 ? m_.at.tk_ns
                                                          : std::numeric_limits<Nanos>::min();
  }
  // The axis is still planning the steps of a path motion.
  bool path_active() const noexcept { return m_.active && path_state_ != PathState::kNone; }
  // Stops the path along it from time t (>= every step either axis has planned): the path's
  // profile ramps down to vs with `ramp` from t, this axis makes the steps up to the point where
  // it stops and the path stays resumable from there.
  void hold_path(Nanos t, const Ramp& ramp) noexcept;

 private:
  // The motion being planned; its steps come from `source_`.
  struct Motion {
    bool active = false;
    bool held = false;  // prepared, waiting for launch() (group start)
    std::uint32_t epoch = 0;
    std::uint32_t group = 0;  // its group id (GroupTag), 0: alone
    StepProgress at;          // the newest step and the motion's time base
  };

  void change_speed(std::uint32_t epoch, const SpeedChange& s) noexcept;
  void stop(std::uint32_t epoch, const StopSpec& s) noexcept;
  void stop_at_frontier(const Ramp& ramp) noexcept;
  // Stop at the trigger (StopSpec::trigger_t): asks the pulse thread for a cut at the step
  // planned at max(trigger, now + margin); false if none is possible (then stop_at_frontier).
  bool request_cut(const StopSpec& s) noexcept;
  // The pulse thread's answer to a cut request; with `now_or_never` an undecided request is
  // withdrawn (another command for this axis must not wait). True when no request is open.
  bool resolve_cut(bool now_or_never) noexcept;
  // Accepted: replans from the cut's step; the new edges carry edge_flag::kReplacement.
  void apply_cut() noexcept;
  void stop_after(std::uint32_t epoch, const StopAfterSpec& s) noexcept;
  void abort_last_motion() noexcept;
  void check_abort() noexcept;
  void follow_update(std::uint32_t epoch, const FollowSpec& f) noexcept;

  // Ends the motion on its newest planned step (kLast on that step's trailing edge).
  void finish_at_frontier() noexcept;
  // Replans the profile from the newest step to end on step `end` (ProfileSource::replan_to_end).
  void replan_to_end(std::int64_t end, const Ramp& ramp, bool exact_ramp) noexcept;
  // Starts the step source `c` asks for; returns its first direction and end count.
  struct SourceStart {
    StepSource* source;
    Direction dir;
    std::int64_t end;
  };
  SourceStart start_source(const Command& c) noexcept;
  // fill() on the motion's time base (`now` already converted).
  Nanos fill_planned(Nanos now) noexcept;
  // Tells the pulse thread the new motion's group and starting speed (rt::AxisControl).
  void publish_motion(const Motion& m, double vs) noexcept;
  // Tells the pulse thread (rt::AxisControl::refill_at) that this axis' next refilled edge lies
  // at or after t (0: unknown), so that it need not poll an empty ring before then.
  void publish_refill(Nanos t) noexcept;
  // The path source set up for a path start or resume; end 0: it makes no step (a resume
  // without a resumable path).
  SourceStart start_path(const Command& c) noexcept;
  // Another motion or an abort: the path this axis followed cannot be resumed any more (on
  // either axis: the book).
  void discard_path() noexcept;

  rt::AxisControl* control_;
  const rt::AxisFeedback* feedback_;
  AxisTiming timing_;
  PlannerOptions opt_;
  EdgeEmitter out_;

  std::uint32_t last_motion_epoch_ = 0;
  bool last_motion_aborted_ = false;
  std::uint32_t seen_abort_ = 0;

  // A cut requested from the pulse thread (request_cut) and not answered yet: this axis pushes
  // nothing meanwhile.
  struct PendingCut {
    bool open = false;
    Ramp ramp;
    std::int64_t k = 0;  // the last step kept
    Nanos t = 0;         // its leading edge: edges of the motion after it are replaced
  };
  PendingCut cut_;
  std::uint32_t cut_epoch_ = 0;  // the newest motion that was cut (one cut per motion)

  Motion m_;
  StepSource* source_ = nullptr;  // the step source of the newest motion
  ProfileSource profile_;         // moves, runs and blends
  FollowServo follow_;            // the encoder follower
  BlendSpec blend_;               // the newest blend start's table (take_blend)
  Nanos now_ = 0;  // time of the latest apply/fill (a follow step from rest starts after it)

  enum class PathState : std::uint8_t { kNone, kRunning, kHeld };
  PathSource path_;  // the step source of path motions
  PathState path_state_ = PathState::kNone;
  std::uint32_t path_id_ = 0;  // the group id of the newest path motion
  PathBook* book_ = nullptr;
};

}  // namespace stepmod::planner
