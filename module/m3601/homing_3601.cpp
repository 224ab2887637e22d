// 3601 Find Home + / - (3601 manual Ch.3 item 10, Ch.4 "Find Home"; digest 7.11).
#include "module/m3601/params_3601.hpp"
#include "module/m3601/personality_3601.hpp"

namespace stepmod::module::m3601 {

void Personality3601::command_home(const ImageWords& /*out*/, planner::Direction /*dir*/) {
  reject();
}

void Personality3601::homing_scan(Nanos /*now*/) {}

void Personality3601::homing_on_input(const gpio::InputEvent& /*e*/, bool /*was_active*/,
                                      bool /*now_active*/) {}

void Personality3601::homing_motion_ended(StopCause /*cause*/) {}

}  // namespace stepmod::module::m3601
