#pragma once
// One stepmodctl command as parsed from the command line, before any module dialect judges it:
// the verb and its options as the user wrote them (numbers still text, so each dialect checks
// them against what its own words can carry). stepmodctl.cpp fills it; module_types/m3601/ctl_3601.cpp,
// ctl_3602.cpp and ctl_3202.cpp turn it into the PLC library's calls (plc/).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace stepmod::tools::ctl {

enum class Verb {
  kConfigure,
  kMove,
  kJog,
  kHome,
  kHold,
  kResume,
  kStop,
  kPreset,
  kPresetEncoder,
  kReset,
  kMinRegistration,
  kBlendProgram,
  kBlendRun,
  kFollow,
  kWaitIdle,
  kGpo,
  kPath,      // 3602: an interpolated move of both axes
  kPathWait,  // 3602: waits until both axes have stopped
};

// configure's flags, one per configuration bit of some module.
struct ConfigureArgs {
  bool capture = false, external = false, home = false, estop = false, cw_limit = false,
       ccw_limit = false, proximity = false, encoder = false, diagnostic = false, cw_ccw = false,
       marker = false;
  bool cw_estop = false, ccw_estop = false, disable = false;  // 3602 / 3202
  std::vector<std::string> active_low;                        // input names (ctl_args.hpp)
  std::string start_speed = "1000";
  std::string homing_timeout;  // 3602 only; empty: not given
};

// --speed/--accel/--decel/--scurve; empty text: not given.
struct ProfileArgs {
  std::string speed, accel, decel, scurve;
  bool given() const { return !speed.empty() || !accel.empty() || !decel.empty(); }
};

// `path line|centre|radius|via`'s arguments (3602 interpolated moves), as written.
struct PathArgs {
  std::string method;  // line, centre, radius, via
  std::string sense;   // centre / radius: cw or ccw
  std::string end_x, end_y;
  std::string point_x, point_y;  // centre: the centre; via: the via point
  std::string radius;            // radius: signed, > 0 the shorter arc, < 0 the longer one
  bool absolute = false;         // positions, not offsets from the start point
};

// One stepmodctl module command as parsed from the command line (ctl_cli.cpp), before a module
// type's dialect (tools/ctl_dialects.hpp) checks it against its words and runs it.
struct CtlRequest {
  Verb verb = Verb::kConfigure;
  unsigned unit = 0;  // axis (3602) or channel (3202), 0-based; 0 on a 3601
  ConfigureArgs configure;
  std::string kind;           // move: abs | rel
  std::string value;          // TARGET / POSITION / VALUE (empty: 0) / DISTANCE
  bool encoder_move = false;  // move --encoder
  ProfileArgs profile;
  std::string direction;     // jog / home / blend run: + or -
  double jog_seconds = 1.0;  // jog --for
  double wait_seconds = 60;  // wait-idle --max
  std::string registration;  // jog --registration (empty: a plain jog)
  // blend program
  std::vector<std::string> segments;
  std::string final_decel, final_type, blend_file;
  // follow
  std::string follow_sense;
  std::int32_t follow_multiplier = 1, follow_divisor = 1, follow_accel = 0, follow_decel = 0;
  bool gpo_on = false;
  PathArgs path;
};

}  // namespace stepmod::tools::ctl
