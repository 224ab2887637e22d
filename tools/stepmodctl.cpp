// stepmodctl: inspect and drive a running stepmod module through the same shared memory a soft
// PLC uses (INTERFACE.md 1). This file is the command line (CLI11) and the commands every module
// shares (status, watch, raw, panel); the module commands are parsed into a ctl::Command and run
// by the dialect the image header names (tools/ctl_3601.cpp, ctl_3602.cpp, ctl_3202.cpp), which
// calls the PLC-side library (plc/).
//
// Exit status: 0 ok; 1 the module refused the command (an error bit with its reason), or a
// waited-for motion did not end in Move Complete / At Home; 2 usage error (nothing written); 3 the
// module cannot be reached (no image, no scan within --timeout: a stopped daemon).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/version.hpp"
#include "gpio/trace_recover.hpp"
#include "ipc/client.hpp"
#include "ipc/sim_panel.hpp"
#include "plc/shm_port.hpp"
#include "tools/ctl_args.hpp"
#include "tools/ctl_command.hpp"
#include "tools/ctl_dialects.hpp"
#include "tools/ctl_report.hpp"
#include "tools/ctl_status.hpp"
#include "tools/ctl_wait.hpp"

namespace {

using namespace stepmod;
using namespace stepmod::tools::ctl;

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) {
  g_stop = 1;
}

constexpr const char* kDescription =
    "stepmodctl: inspect and drive a running stepmod module (3601, 3602 or 3202) through its\n"
    "shared-memory image, exactly as a PLC program would (write parameters + command bit, wait\n"
    "for the module's scan, release the bit, show the decoded status). The module type comes\n"
    "from the image; --axis 1|2 picks the 3602's axis, --channel 1|2 the 3202's channel (either\n"
    "option works for both).\n\n"
    "Exit status: 0 ok, 1 the module refused the command (an error bit it set for this command\n"
    "- Command Error, Invalid Profile, Home Invalid, Configuration Error - printed with the\n"
    "module's reason; a bit left by an earlier command is only a note for hold/resume/stop), or\n"
    "a waited-for motion (--wait, wait-idle) did not end in Move Complete / At Home, 2 usage\n"
    "error (also a command or value the module's words cannot carry; nothing is written), 3\n"
    "module unreachable (no image /dev/shm/stepmod.NAME, or no scan in time: a stopped daemon).\n"
    "Numbers accept 0x.. and 16#.. hex; negative numbers are written as they are:\n"
    "  stepmodctl move rel -500 -s 1000 -a 10 -d 10\n"
    "Everything after '--' is positional, so options go before it:\n"
    "  stepmodctl move rel -s 1000 -a 10 -d 10 -- -500\n"
    "Commands that drive the module also bump the PLC heartbeat while they run; with --wait and\n"
    "no PLC they hold the commissioning lease instead (docs/commissioning.md).";

// --speed/--accel/--decel[/--scurve] of a sub-command, as text: each dialect checks the range
// its words carry.
void add_profile(CLI::App* app, ProfileArgs& p, bool required, bool with_scurve = true) {
  auto* s = app->add_option("--speed,-s", p.speed, "programmed speed, steps/s")->type_name("N");
  auto* a = app->add_option("--accel,-a", p.accel,
                            "acceleration: steps/ms/s on a 3601/3602 (1..2000), steps/s^2 on a "
                            "3202 (1000..2000000)")
                ->type_name("N");
  auto* d = app->add_option("--decel,-d", p.decel, "deceleration, in the same unit as --accel")
                ->type_name("N");
  if (required) {
    s->required();
    a->required();
    d->required();
  }
  if (with_scurve) {
    app->add_option("--scurve", p.scurve, "S-curve acceleration: tri or trap (default constant)")
        ->check(CLI::IsMember({"tri", "trap", "const"}));
  }
}

void print_outcome(const ipc::Client& c, const plc::Outcome& o) {
  // After a timeout the image says nothing about the command: only the message.
  if (!o.timed_out) std::cout << format_status(c.type(), o.in);
  if (!o.ok) std::cerr << "stepmodctl: " << o.message << "\n";
  if (o.ok && !o.note.empty()) std::cerr << "stepmodctl: note: " << o.note << "\n";
}

// Commands that start a motion (for --wait, and the heartbeat-timeout note).
bool starts_motion(Verb v) {
  return v == Verb::kMove || v == Verb::kJog || v == Verb::kHome || v == Verb::kBlendRun ||
         v == Verb::kPath;
}

Motion motion_of(Verb v) {
  return v == Verb::kHome ? Motion::kHome : v == Verb::kJog ? Motion::kJog : Motion::kMove;
}

// A typo in the sub-command: named, with the closest one. nullopt: argv is fine (or CLI11 will
// say what else is wrong).
std::optional<std::string> unknown_command(int argc, char** argv, const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    names.push_back(sub->get_name());
  }
  static const std::vector<std::string> kValued = {"--name", "-n",        "--timeout",
                                                   "--axis", "--channel", "-c"};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--") return std::nullopt;
    if (std::find(kValued.begin(), kValued.end(), a) != kValued.end()) {
      ++i;
      continue;
    }
    if (a.starts_with("-")) continue;
    if (std::find(names.begin(), names.end(), a) != names.end()) return std::nullopt;
    const std::string guess = closest_command(a, names);
    return "unknown command '" + a + "'" +
           (guess.empty() ? "" : "; did you mean '" + guess + "'?") +
           " (stepmodctl --help lists them)";
  }
  return std::nullopt;
}

int exit_for(const plc::Outcome& o) {
  if (o.ok) return kExitOk;
  return o.timed_out ? kExitUnreachable : kExitModuleError;
}

std::string status_text(const std::string& name, ipc::Client& client) {
  ImageWords in;
  client.read_inputs(in);
  return "module '" + name + "' scan " + std::to_string(client.scan_counter()) + "\n" +
         format_status(client.type(), in) + reason_lines(client) +
         format_health(client.read_health());
}

std::string stalled_text(const std::string& name, const ipc::Client& client) {
  return "stepmodctl: module '" + name + "' is not scanning (scan counter " +
         std::to_string(client.scan_counter()) +
         " unchanged for 1 s): stepmodd is stopped (SIGSTOP?) or hung; its words are stale\n";
}

}  // namespace

// `stepmodctl trace recover`: no module needed, only the files.
int recover_spools(const std::vector<std::string>& spools, const std::string& vcd, bool keep) {
  try {
    const gpio::RecoverResult r = gpio::recover_trace(spools, vcd);
    std::cout << vcd << ": " << r.changes << " line changes recovered (" << r.late
              << " late); marked TRACE INCOMPLETE\n";
  } catch (const std::exception& e) {
    std::cerr << "stepmodctl: " << e.what() << "\n";
    return kExitModuleError;
  }
  if (!keep) {
    for (const std::string& s : spools) std::remove(s.c_str());
  }
  return kExitOk;
}

int main(int argc, char** argv) {
  CLI::App app{kDescription};
  app.require_subcommand(1);
  app.set_version_flag("--version", "stepmodctl " STEPMOD_VERSION);
  std::string name = "stepmod";
  int timeout_ms = 2000;
  unsigned axis_no = 0;
  unsigned channel_no = 0;
  app.add_option("--name,-n", name, "module name: /dev/shm/stepmod.NAME (default stepmod)");
  app.add_option("--timeout", timeout_ms, "ms to wait for the module's scans/handshakes (2000)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--axis", axis_no, "3602: the axis a command is for, 1 or 2 (1)")
      ->check(CLI::Range(1, 2));
  app.add_option("--channel,-c", channel_no, "3202: the channel a command is for, 1 or 2 (1)")
      ->check(CLI::Range(1, 2));

  Command cmd;
  // Each module command sets its verb when CLI11 parses it.
  const auto verb = [&cmd](CLI::App* sub, Verb v) {
    sub->parse_complete_callback([&cmd, v] { cmd.verb = v; });
    return sub;
  };

  // ---- inspection (every module) ----
  auto* status = app.add_subcommand("status",
                                    "decoded input image: every status bit by name (both axes "
                                    "/ channels of a 3602 / 3202), positions as numbers");
  bool brief = false;
  bool json = false;
  status->add_flag("--brief", brief,
                   "one line per axis/channel: state, position, speed, errors and their reason");
  status->add_flag("--json", json, "the --brief fields and the health as one JSON object");
  auto* watch = app.add_subcommand("watch", "status, refreshed until Ctrl-C");
  watch->add_flag("--brief", brief, "the one-line-per-axis form of status --brief");
  int interval_ms = 200;
  watch->add_option("--interval,-i", interval_ms, "refresh period in ms (200)")
      ->check(CLI::Range(1, 3'600'000));
  auto* raw = app.add_subcommand("raw", "read/write image words");
  raw->require_subcommand(1);
  auto* raw_get = raw->add_subcommand("get", "print output and input words (decimal and hex)");
  auto* raw_set = raw->add_subcommand("set", "write one output word (a PLC write)");
  std::string raw_word;
  std::string raw_value;
  raw_set->add_option("WORD", raw_word, "output word index")->required();
  raw_set->add_option("VALUE", raw_value, "value (decimal, 0x.. or 16#..)")->required();

  // ---- module commands ----
  ConfigureArgs& cf = cmd.configure;
  auto* configure =
      verb(app.add_subcommand("configure",
                              "configuration mode with these settings (the axis/channel's), then "
                              "command mode"),
           Verb::kConfigure);
  configure->add_flag("--capture", cf.capture, "capture input used");
  configure->add_flag("--external", cf.external, "external input used");
  configure->add_flag("--home", cf.home, "home input used");
  configure->add_flag("--estop", cf.estop, "3601/3202: E-stop input used");
  configure->add_flag("--cw-limit", cf.cw_limit, "CW limit used (3602: the CW input is a limit)");
  configure->add_flag("--ccw-limit", cf.ccw_limit,
                      "CCW limit used (3602: the CCW input is a limit)");
  configure->add_flag("--backplane-proximity", cf.proximity, "backplane home proximity");
  configure->add_flag("--encoder", cf.encoder, "3601/3202: quadrature encoder used");
  configure->add_flag("--diagnostic-feedback", cf.diagnostic, "3601/3202: diagnostic feedback");
  configure->add_flag("--cw-ccw", cf.cw_ccw, "CW/CCW pulse outputs (default step + direction)");
  configure->add_flag("--marker-homing", cf.marker, "3601/3202: marker-pulse homing");
  configure
      ->add_option("--active-low", cf.active_low,
                   "inputs that are active low (N.C.): capture,external,home,estop,cw_limit,"
                   "ccw_limit; all others active high")
      ->delimiter(',');
  configure->add_flag("--cw-estop", cf.cw_estop, "3602: the CW input is an E-stop (bits 4:3 = 10)");
  configure->add_flag("--ccw-estop", cf.ccw_estop,
                      "3602: the CCW input is an E-stop (bits 6:5 = 10)");
  configure->add_flag("--disable", cf.disable,
                      "3602: disable the axis (bit 14); 3202: disable the channel (bit 28)");
  configure->add_option("--homing-timeout", cf.homing_timeout, "3602: homing timeout, s (0 = none)")
      ->type_name("S");
  configure->add_option("--start-speed", cf.start_speed, "starting speed, steps/s (1000)")
      ->type_name("N");

  auto* move = verb(app.add_subcommand("move", "absolute or relative move"), Verb::kMove);
  move->add_option("KIND", cmd.kind, "abs or rel")
      ->required()
      ->check(CLI::IsMember({"abs", "rel"}));
  move->add_option("TARGET", cmd.value, "target position or offset, steps")->required();
  add_profile(move, cmd.profile, true);
  move->add_flag("--encoder", cmd.encoder_move, "3601/3202: encoder-count move");
  bool wait = false;
  const auto add_wait = [&wait](CLI::App* sub) {
    sub->add_flag("--wait,-w", wait,
                  "wait for the end of the motion: exit 0 on Move Complete (At Home after a "
                  "homing), 1 with the reason otherwise; holds the commissioning lease when no "
                  "PLC is in control");
  };
  add_wait(move);

  auto* jog = verb(app.add_subcommand("jog",
                                      "jog (manual move, level-held) for --for seconds; with "
                                      "--registration a registration move (3601, 3602)"),
                   Verb::kJog);
  jog->add_option("DIR", cmd.direction, "+ (cw) or - (ccw)")->required();
  add_profile(jog, cmd.profile, true);
  jog->add_option("--for,-t", cmd.jog_seconds, "seconds to hold the jog bit (1)")
      ->check(CLI::Range(0.0, 1e6));
  jog->add_option("--registration", cmd.registration,
                  "registration move: steps after the stop trigger")
      ->type_name("STEPS");
  add_wait(jog);

  auto* home =
      verb(app.add_subcommand("home", "find home in direction + (CW) or - (CCW)"), Verb::kHome);
  home->add_option("DIR", cmd.direction, "+ (cw) or - (ccw)")->required();
  add_profile(home, cmd.profile, true, false);
  add_wait(home);

  verb(app.add_subcommand("hold", "hold move (controlled stop, resumable)"), Verb::kHold);
  auto* resume = verb(app.add_subcommand("resume",
                                         "resume a held move (optionally with a new speed and "
                                         "rates: all of -s -a -d)"),
                      Verb::kResume);
  add_profile(resume, cmd.profile, false);
  verb(app.add_subcommand("stop", "immediate stop"), Verb::kStop);
  auto* preset = verb(app.add_subcommand("preset", "preset the current position"), Verb::kPreset);
  preset->add_option("POSITION", cmd.value, "new position")->required();
  auto* preset_enc =
      verb(app.add_subcommand("preset-encoder", "3601/3202: preset the encoder count"),
           Verb::kPresetEncoder);
  preset_enc->add_option("VALUE", cmd.value, "new encoder count (0)");
  verb(app.add_subcommand("reset", "reset errors"), Verb::kReset);
  auto* minreg = verb(
      app.add_subcommand("min-registration", "3601/3602: store the minimum registration distance"),
      Verb::kMinRegistration);
  minreg->add_option("DISTANCE", cmd.value, "steps, 0 disables")->required();

  auto* blend = app.add_subcommand("blend", "blend move profiles");
  blend->require_subcommand(1);
  auto* blend_prog =
      verb(blend->add_subcommand("program",
                                 "program a profile: 3601/3602 with the block handshake (program "
                                 "bit, transmit edges, acknowledge), 3202 as one message"),
           Verb::kBlendProgram);
  blend_prog->add_option("--segment", cmd.segments,
                         "LENGTH:SPEED:ACCEL[:tri|trap], once per segment in order (2..16)");
  blend_prog
      ->add_option("--final-decel", cmd.final_decel,
                   "final deceleration: steps/ms/s (3601 0..16383, 3602 0..2047) or "
                   "steps/s^2 (3202)")
      ->type_name("N");
  blend_prog->add_option("--final-type", cmd.final_type, "final deceleration type: const|tri|trap");
  blend_prog
      ->add_option("--file", cmd.blend_file,
                   "the profile from a file instead (segment = L:S:A[:type], final_decel "
                   "= N, final_type = T; one per line, # comments)")
      ->type_name("FILE");
  auto* blend_run =
      verb(blend->add_subcommand("run", "run the stored profile, + or -"), Verb::kBlendRun);
  blend_run->add_option("DIR", cmd.direction, "+ (cw) or - (ccw)")->required();
  add_wait(blend_run);

  auto* follow =
      verb(app.add_subcommand(
               "follow",
               "3601: encoder follower mode; its bits are levels: it stays on until 'follow off'"),
           Verb::kFollow);
  follow
      ->add_option("SENSE", cmd.follow_sense,
                   "+ (same sense as the master), - (reverse), 0 (follower mode, no motion), off")
      ->required()
      ->check(CLI::IsMember({"+", "-", "0", "off"}));
  // Words 2 and 3 carry multiplier and divisor as plain 16-bit integers (digest 3.5).
  follow->add_option("--multiplier,-m", cmd.follow_multiplier, "ratio multiplier, 1..32767 (1)")
      ->check(CLI::Range(1, 32767));
  follow->add_option("--divisor,-D", cmd.follow_divisor, "ratio divisor, 1..32767 (1)")
      ->check(CLI::Range(1, 32767));
  follow->add_option("--accel,-a", cmd.follow_accel, "acceleration, steps/ms/s (0..2000)")
      ->check(CLI::Range(INT16_MIN, INT16_MAX));
  follow->add_option("--decel,-d", cmd.follow_decel, "deceleration, steps/ms/s (0..2000)")
      ->check(CLI::Range(INT16_MIN, INT16_MAX));

  auto* wait_idle = verb(app.add_subcommand("wait-idle",
                                            "wait until the axis/channel is neither moving nor "
                                            "running a blend: exit 0 if the motion ended in Move "
                                            "Complete or At Home, 1 with the reason otherwise"),
                         Verb::kWaitIdle);
  wait_idle->add_option("--max", cmd.wait_seconds, "give up after this many seconds (60)")
      ->check(CLI::Range(0.0, 1e6));

  auto* gpo =
      verb(app.add_subcommand("gpo", "3602: the general-purpose output (command LSW bit 7)"),
           Verb::kGpo);
  std::string gpo_state;
  gpo->add_option("STATE", gpo_state, "on or off")->required()->check(CLI::IsMember({"on", "off"}));

  // ---- 3602 interpolated moves: both axes on one path, commanded on axis 1 ----
  auto* path = app.add_subcommand(
      "path",
      "3602: an interpolated move of both axes (X = axis 1, Y = axis 2) from where they stand: "
      "a line or a circular arc, points relative to the start unless --abs; -s/-a/-d are the "
      "vector speed and rates");
  path->require_subcommand(1);
  PathArgs& pa = cmd.path;
  const auto path_move = [&](const char* method, const char* help) {
    auto* sub = path->add_subcommand(method, help);
    sub->parse_complete_callback([&cmd, method] {
      cmd.verb = Verb::kPath;
      cmd.path.method = method;
    });
    return sub;
  };
  const auto end_point = [&](CLI::App* sub) {
    sub->add_option("X", pa.end_x, "end point X (axis 1), steps")->type_name("STEPS")->required();
    sub->add_option("Y", pa.end_y, "end point Y (axis 2), steps")->type_name("STEPS")->required();
  };
  const auto path_options = [&](CLI::App* sub) {
    sub->add_flag("--abs", pa.absolute, "points are positions (default: offsets from the start)");
    add_profile(sub, cmd.profile, true);
    add_wait(sub);
  };
  const auto sense = [&](CLI::App* sub) {
    sub->add_option("SENSE", pa.sense, "cw or ccw (X right, Y up)")
        ->required()
        ->check(CLI::IsMember({"cw", "ccw", "CW", "CCW"}));
  };
  auto* path_line = path_move("line", "linear interpolation to X Y");
  end_point(path_line);
  path_options(path_line);
  auto* path_centre = path_move(
      "centre", "circular arc to X Y around the centre CX CY; X Y = the start: a full circle");
  sense(path_centre);
  end_point(path_centre);
  path_centre->add_option("CX", pa.point_x, "centre X, steps")->type_name("STEPS")->required();
  path_centre->add_option("CY", pa.point_y, "centre Y, steps")->type_name("STEPS")->required();
  path_options(path_centre);
  auto* path_radius = path_move(
      "radius", "circular arc to X Y of radius R: R > 0 the shorter arc, R < 0 the longer one");
  sense(path_radius);
  end_point(path_radius);
  path_radius->add_option("R", pa.radius, "signed radius, steps")->type_name("STEPS")->required();
  path_options(path_radius);
  auto* path_via =
      path_move("via", "circular arc to X Y through the via point VX VY (its sense follows)");
  end_point(path_via);
  path_via->add_option("VX", pa.point_x, "via point X, steps")->type_name("STEPS")->required();
  path_via->add_option("VY", pa.point_y, "via point Y, steps")->type_name("STEPS")->required();
  path_options(path_via);
  auto* path_wait =
      verb(path->add_subcommand("wait", "waits until both axes have stopped"), Verb::kPathWait);
  path_wait->add_option("--max", cmd.wait_seconds, "give up after this many seconds (60)")
      ->check(CLI::Range(0.0, 1e6));

  // ---- simulator panel ----
  auto* panel = app.add_subcommand("panel", "simulator panel: show, force or release inputs");
  panel->add_subcommand("show", "positions, outputs and forced inputs");
  auto* panel_force = panel->add_subcommand("force", "force an input to an electrical level");
  auto* panel_release = panel->add_subcommand("release", "give an input back to the simulation");
  unsigned p_axis = 1;
  std::string p_input;
  int p_level = 0;
  panel_force->add_option("AXIS", p_axis, "axis number, 1-based")->required();
  panel_force->add_option("INPUT", p_input, "capture|external|home|estop|cw_limit|ccw_limit")
      ->required();
  panel_force->add_option("LEVEL", p_level, "0 or 1 (electrical)")
      ->required()
      ->check(CLI::Range(0, 1));
  panel_release->add_option("AXIS", p_axis, "axis number, 1-based")->required();
  panel_release->add_option("INPUT", p_input, "input name, or 'all'")->required();

  // ---- trace files ----
  auto* trace = app.add_subcommand("trace", "trace files (--trace FILE.vcd of stepmodd)");
  auto* trace_recover =
      trace->add_subcommand("recover",
                            "write the VCD from the spools a daemon left behind (killed, or a "
                            "full disk); the spools are removed once it is written");
  std::vector<std::string> spool_paths;
  std::string recovered_vcd;
  bool keep_spools = false;
  trace_recover->add_option("SPOOL", spool_paths, "FILE.vcd.out.spool FILE.vcd.in.spool")
      ->required();
  trace_recover->add_option("-o,--output", recovered_vcd, "the VCD to write")->required();
  trace_recover->add_flag("--keep", keep_spools, "leave the spools in place");
  trace->require_subcommand(1);

  if (const auto typo = unknown_command(argc, argv, app)) {
    std::cerr << "stepmodctl: " << *typo << "\n";
    return kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }

  try {
    const auto timeout = std::chrono::milliseconds(timeout_ms);

    if (trace_recover->parsed()) {
      return recover_spools(spool_paths, recovered_vcd, keep_spools);
    }
    if (panel->parsed()) {
      ipc::SimPanelClient p(name);
      if (p_axis < 1 || p_axis > p.axes()) {
        throw UsageError("AXIS must be 1.." + std::to_string(p.axes()));
      }
      const unsigned axis = p_axis - 1;
      if (panel_force->parsed()) {
        p.force(axis, input_index(p_input), p_level != 0);
      } else if (panel_release->parsed()) {
        if (p_input == "all") {
          p.release_all(axis);
        } else {
          p.release(axis, input_index(p_input));
        }
      }
      std::cout << format_panel(p);
      return kExitOk;
    }

    ipc::Client client(name);

    if (status->parsed()) {
      const auto snap = take_snapshot(client, std::chrono::milliseconds(brief || json ? 100 : 0));
      if (!snap) {
        // The words as they were left (what a stopped daemon last said), and why not to trust them.
        if (!brief && !json) std::cout << status_text(name, client);
        std::cerr << stalled_text(name, client);
        return kExitUnreachable;
      }
      std::cout << (json    ? json_text(name, client, *snap)
                    : brief ? brief_text(name, client, *snap)
                            : status_text(name, client));
      return kExitOk;
    }
    if (watch->parsed()) {
      std::signal(SIGINT, on_signal);
      std::signal(SIGTERM, on_signal);
      while (!g_stop) {
        // The snapshot's two readings are the refresh period apart (the speed is over it).
        const auto snap = take_snapshot(client, std::chrono::milliseconds(interval_ms));
        // Home the cursor and clear: a steady display instead of a scrolling log.
        std::cout << "\x1b[H\x1b[2J";
        if (!snap) {
          std::cout << stalled_text(name, client) << std::flush;
          continue;
        }
        std::cout << (brief ? brief_text(name, client, *snap) : status_text(name, client))
                  << std::flush;
      }
      return kExitOk;
    }
    if (raw_get->parsed()) {
      ImageWords out;
      ImageWords in;
      client.read_outputs(out);
      client.read_inputs(in);
      const auto& s = client.shape();
      std::cout << "module '" << name << "' type " << static_cast<unsigned>(s.type) << ", "
                << s.word_bytes * 8 << "-bit words, scan " << client.scan_counter()
                << ", heartbeat " << client.heartbeat_value() << "\noutput words (PLC -> "
                << "module):\n"
                << format_words(out, s.output_words, s.word_bytes)
                << "input words (module -> PLC):\n"
                << format_words(in, s.input_words, s.word_bytes);
      return kExitOk;
    }
    if (raw_set->parsed()) {
      const std::int64_t words = client.shape().output_words;
      const std::int64_t word = parse_in_range(raw_word, "WORD", 0, words - 1, "the output image");
      const bool narrow = client.shape().word_bytes == 2;
      const std::int64_t value = parse_in_range(raw_value, "VALUE", narrow ? INT16_MIN : INT32_MIN,
                                                narrow ? UINT16_MAX : UINT32_MAX, "the word size");
      client.write_word(static_cast<unsigned>(word),
                        static_cast<std::int32_t>(static_cast<std::uint32_t>(value)));
      if (!client.wait_scans(2, timeout)) {
        std::cerr << "stepmodctl: written, but the module did not scan within " << timeout_ms
                  << " ms\n";
        return kExitUnreachable;
      }
      return kExitOk;
    }

    // A module command, in the dialect the image header names.
    if (axis_no != 0 && channel_no != 0 && axis_no != channel_no) {
      throw UsageError("--axis and --channel name the same thing: give one");
    }
    const unsigned unit_no = axis_no != 0 ? axis_no : channel_no != 0 ? channel_no : 1;
    cmd.unit = unit_no - 1;
    cmd.gpo_on = gpo_state == "on";
    plc::ShmPort port(client, timeout);
    if (cmd.verb == Verb::kWaitIdle) {
      return wait_motion_end(client, {cmd.unit}, Motion::kAny, millis(cmd.wait_seconds), std::cout,
                             std::cerr);
    }
    // --wait: the commissioning lease while no PLC is in control; a lease holder is no PLC and
    // leaves the heartbeat alone. Without --wait, say when plc_timeout_ms will cut the motion.
    std::unique_ptr<ipc::LeaseClient> lease;
    if (wait && starts_motion(cmd.verb)) {
      lease = take_lease(client, std::cerr);
      if (lease) {
        port.set_heartbeat(false);
        client.wait_scans(3, timeout);  // the daemon has seen it (and acts on the words again)
      }
    } else if (starts_motion(cmd.verb)) {
      warn_heartbeat_timeout(client, std::cerr);
    }
    plc::Outcome o;
    switch (client.type()) {
      case ModuleType::k3601:
        o = run_3601(cmd, port, timeout);
        break;
      case ModuleType::k3602:
        o = run_3602(cmd, port, timeout);
        break;
      case ModuleType::k3202:
        o = run_3202(cmd, port, client, timeout);
        break;
    }
    print_outcome(client, o);
    if (!o.ok) return exit_for(o);
    if (wait && starts_motion(cmd.verb)) {
      const std::vector<unsigned> units =
          cmd.verb == Verb::kPath ? std::vector<unsigned>{0, 1} : std::vector<unsigned>{cmd.unit};
      return wait_motion_end(client, units, motion_of(cmd.verb), std::chrono::hours(24), std::cout,
                             std::cerr);
    }
    // A stop or hold the module ignored (Command Error left set: 3601-CE-L1) while the axis still
    // moves did not do its job, whatever the note says.
    if ((cmd.verb == Verb::kStop || cmd.verb == Verb::kHold) && !o.note.empty()) {
      client.wait_scans(2, timeout);
      ImageWords in;
      client.read_inputs(in);
      const auto s = summarize(client.type(), in);
      if (cmd.unit < s.size() && s[cmd.unit].moving()) {
        std::cerr << "stepmodctl: the axis is still moving: the module ignored the command "
                     "while Command Error is set; run 'stepmodctl reset', then the command again\n";
        return kExitModuleError;
      }
    }
    return kExitOk;
  } catch (const UsageError& e) {
    std::cerr << "stepmodctl: " << e.what() << "\n";
    return kExitUsage;
  } catch (const ipc::IpcError& e) {
    std::cerr << "stepmodctl: " << e.what() << "\n";
    return kExitUnreachable;
  }
}
