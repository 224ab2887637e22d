// 3601 manual moves and registration moves (3601 manual Ch.4 "Manual Move", "Registration
// Move"; digest 7.8, 7.9) and the minimum registration distance.
#include "module/m3601/params_3601.hpp"
#include "module/m3601/personality_3601.hpp"

namespace stepmod::module::m3601 {

// Manual Move + / - (MSW bits 7/8, level held): 3601 manual Ch.4 "Manual Move".
void Personality3601::command_manual(const ImageWords& out, planner::Direction dir) {
  if (moving()) {
    reject();  // 3601-CE-03
    return;
  }
  const auto target = target_words(out);
  if (!target) {
    reject_profile();  // 3601-CE-04
    return;
  }
  if (*target != 0) {
    reject();  // registration moves are not emulated yet (A3)
    return;
  }
  const auto profile = read_profile(out, false);
  if (!profile) return;
  // 3601-IE-03: a manual move toward an active end limit raises IE and does not move; so does
  // one with the E-stop active (A15).
  if (inputs_.active(gpio::InputLine::kEStop) ||
      inputs_.active(dir == planner::Direction::kCw ? gpio::InputLine::kCwLimit
                                                    : gpio::InputLine::kCcwLimit)) {
    status_.input_error = true;
    return;
  }
  status_.move_complete = false;
  status_.hold = false;
  status_.stopped = false;
  status_.at_home = false;
  status_.input_error = false;
  activity_ = Activity::kManual;
  dir_ = dir;
  move_decel_ = profile->decel;
  stop_cause_ = StopCause::kNone;
  // One-shot (Vp = 0, digest 7.8; 3601-STP-N1: no Stopped on release) and a start with the
  // External input active (digest 7.6: one step, then stop) both output a single pulse.
  const bool external = inputs_.active(gpio::InputLine::kExternal);
  std::uint32_t epoch = 0;
  if (profile->vp == 0 || external) {
    planner::MoveSpec one;
    one.steps = 1;
    one.dir = dir;
    one.vs = cfg_.starting_speed;
    one.vp = cfg_.starting_speed;
    one.accel = profile->accel;
    one.decel = profile->decel;
    epoch = motion_.start_move(one);
    if (external) stop_cause_ = StopCause::kExternal;
  } else {
    planner::RunSpec run;
    run.dir = dir;
    run.vs = cfg_.starting_speed;
    run.vp = profile->vp;  // <= vs: constant-speed mode, no ramps (planner)
    run.accel = profile->accel;
    run.decel = profile->decel;
    epoch = motion_.start_run(run);
  }
  if (epoch == 0) {
    activity_ = Activity::kIdle;
    stop_cause_ = StopCause::kNone;
    reject();
  }
}

void Personality3601::manual_scan(const ImageWords& /*out*/) {}

void Personality3601::command_min_registration(const ImageWords& /*out*/) { reject(); }

bool Personality3601::manual_on_input(const gpio::InputEvent& /*e*/, bool /*now_active*/) {
  return false;
}

}  // namespace stepmod::module::m3601
