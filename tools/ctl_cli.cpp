// stepmodctl's command line (CLI11): every option and sub-command, bound to CtlOptions. The
// order of the add_* calls is the order of --help.
#include "tools/ctl_cli.hpp"

#include <cstdint>

namespace stepmod::tools::ctl {
namespace {

// A module command sets its verb when CLI11 parses it.
auto verb_setter(CtlRequest& cmd) {
  return [&cmd](CLI::App* sub, Verb v) {
    sub->parse_complete_callback([&cmd, v] { cmd.verb = v; });
    return sub;
  };
}

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

void add_wait(CLI::App* sub, bool& wait) {
  sub->add_flag("--wait,-w", wait,
                "wait for the end of the motion: exit 0 on Move Complete (At Home after a "
                "homing), 1 with the reason otherwise; holds the commissioning lease when no "
                "PLC is in control");
}

void add_globals(CLI::App& app, CtlOptions& o) {
  app.add_option("--name,-n", o.name,
                 "module name: /dev/shm/stepmod.NAME (default " + o.name + ")");
  app.add_option("--timeout", o.timeout_ms, "ms to wait for the module's scans/handshakes (2000)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--steal", o.steal,
               "take the commissioning lease over from the tool that holds it, for this command "
               "(logged by stepmodctl and stepmodd; without it a command is refused while another "
               "running process holds the lease, except stop)");
  app.add_option("--axis", o.axis_no, "3602: the axis a command is for, 1 or 2 (1)")
      ->check(CLI::Range(1, 2));
  app.add_option("--channel,-c", o.channel_no, "3202: the channel a command is for, 1 or 2 (1)")
      ->check(CLI::Range(1, 2));
}

// ---- inspection (every module) ----
void add_inspection(CLI::App& app, CtlOptions& o, CtlSubcommands& subs) {
  subs.status = app.add_subcommand("status",
                                   "decoded input image: every status bit by name (both axes "
                                   "/ channels of a 3602 / 3202), positions as numbers");
  subs.status->add_flag(
      "--brief", o.brief,
      "one line per axis/channel: state, position, speed, errors and their reason");
  subs.status->add_flag("--json", o.json, "the --brief fields and the health as one JSON object");
  subs.watch = app.add_subcommand("watch", "status, refreshed until Ctrl-C");
  subs.watch->add_flag("--brief", o.brief, "the one-line-per-axis form of status --brief");
  subs.watch->add_option("--interval,-i", o.interval_ms, "refresh period in ms (200)")
      ->check(CLI::Range(1, 3'600'000));
  auto* raw = app.add_subcommand("raw", "read/write image words");
  raw->require_subcommand(1);
  subs.raw_get = raw->add_subcommand("get", "print output and input words (decimal and hex)");
  subs.raw_set = raw->add_subcommand("set", "write one output word (a PLC write)");
  subs.raw_set->add_option("WORD", o.raw_word, "output word index")->required();
  subs.raw_set->add_option("VALUE", o.raw_value, "value (decimal, 0x.. or 16#..)")->required();
}

// ---- module commands ----
void add_configure(CLI::App& app, CtlRequest& cmd) {
  const auto verb = verb_setter(cmd);
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
}

void add_moves(CLI::App& app, CtlOptions& o) {
  CtlRequest& cmd = o.cmd;
  const auto verb = verb_setter(cmd);
  auto* move = verb(app.add_subcommand("move", "absolute or relative move"), Verb::kMove);
  move->add_option("KIND", cmd.kind, "abs or rel")
      ->required()
      ->check(CLI::IsMember({"abs", "rel"}));
  move->add_option("TARGET", cmd.value, "target position or offset, steps")->required();
  add_profile(move, cmd.profile, true);
  move->add_flag("--encoder", cmd.encoder_move, "3601/3202: encoder-count move");
  add_wait(move, o.wait);

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
  add_wait(jog, o.wait);

  auto* home =
      verb(app.add_subcommand("home", "find home in direction + (CW) or - (CCW)"), Verb::kHome);
  home->add_option("DIR", cmd.direction, "+ (cw) or - (ccw)")->required();
  add_profile(home, cmd.profile, true, false);
  add_wait(home, o.wait);
}

void add_commands(CLI::App& app, CtlRequest& cmd) {
  const auto verb = verb_setter(cmd);
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
}

void add_blend(CLI::App& app, CtlOptions& o) {
  CtlRequest& cmd = o.cmd;
  const auto verb = verb_setter(cmd);
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
  add_wait(blend_run, o.wait);
}

void add_follow(CLI::App& app, CtlRequest& cmd) {
  const auto verb = verb_setter(cmd);
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
  // Words 2 and 3 carry multiplier and divisor as plain 16-bit integers (3601 manual ch. 5).
  follow->add_option("--multiplier,-m", cmd.follow_multiplier, "ratio multiplier, 1..32767 (1)")
      ->check(CLI::Range(1, 32767));
  follow->add_option("--divisor,-D", cmd.follow_divisor, "ratio divisor, 1..32767 (1)")
      ->check(CLI::Range(1, 32767));
  follow->add_option("--accel,-a", cmd.follow_accel, "acceleration, steps/ms/s (0..2000)")
      ->check(CLI::Range(INT16_MIN, INT16_MAX));
  follow->add_option("--decel,-d", cmd.follow_decel, "deceleration, steps/ms/s (0..2000)")
      ->check(CLI::Range(INT16_MIN, INT16_MAX));
}

void add_wait_idle_and_gpo(CLI::App& app, CtlOptions& o) {
  CtlRequest& cmd = o.cmd;
  const auto verb = verb_setter(cmd);
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
  gpo->add_option("STATE", o.gpo_state, "on or off")
      ->required()
      ->check(CLI::IsMember({"on", "off"}));
}

// ---- 3602 interpolated moves: both axes on one path, commanded on axis 1 ----
// A point or length of a path, in steps (STEPS), never optional.
struct PathWord {
  const char* name;
  std::string* to;
  const char* help;
};

void add_path(CLI::App& app, CtlOptions& o) {
  CtlRequest& cmd = o.cmd;
  const auto verb = verb_setter(cmd);
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
  const auto path_options = [&](CLI::App* sub) {
    sub->add_flag("--abs", pa.absolute, "points are positions (default: offsets from the start)");
    add_profile(sub, cmd.profile, true);
    add_wait(sub, o.wait);
  };
  // One method: the sense (circles by centre or radius), the end point X Y, the method's own
  // words, then the options every method takes.
  const auto method = [&](const char* name, const char* help, bool with_sense,
                          std::initializer_list<PathWord> own) {
    auto* sub = path_move(name, help);
    if (with_sense) {
      sub->add_option("SENSE", pa.sense, "cw or ccw (X right, Y up)")
          ->required()
          ->check(CLI::IsMember({"cw", "ccw", "CW", "CCW"}));
    }
    const auto add = [sub](std::initializer_list<PathWord> words) {
      for (const PathWord& w : words)
        sub->add_option(w.name, *w.to, w.help)->type_name("STEPS")->required();
    };
    add({{"X", &pa.end_x, "end point X (axis 1), steps"},
         {"Y", &pa.end_y, "end point Y (axis 2), steps"}});
    add(own);
    path_options(sub);
  };
  method("line", "linear interpolation to X Y", false, {});
  method("centre", "circular arc to X Y around the centre CX CY; X Y = the start: a full circle",
         true, {{"CX", &pa.point_x, "centre X, steps"}, {"CY", &pa.point_y, "centre Y, steps"}});
  method("radius", "circular arc to X Y of radius R: R > 0 the shorter arc, R < 0 the longer one",
         true, {{"R", &pa.radius, "signed radius, steps"}});
  method("via", "circular arc to X Y through the via point VX VY (its sense follows)", false,
         {{"VX", &pa.point_x, "via point X, steps"}, {"VY", &pa.point_y, "via point Y, steps"}});
  auto* path_wait =
      verb(path->add_subcommand("wait", "waits until both axes have stopped"), Verb::kPathWait);
  path_wait->add_option("--max", cmd.wait_seconds, "give up after this many seconds (60)")
      ->check(CLI::Range(0.0, 1e6));
}

// ---- simulator panel ----
void add_panel(CLI::App& app, CtlOptions& o, CtlSubcommands& subs) {
  subs.panel = app.add_subcommand("panel", "simulator panel: show, force or release inputs");
  subs.panel->add_subcommand("show", "positions, outputs and forced inputs");
  subs.panel_force = subs.panel->add_subcommand("force", "force an input to an electrical level");
  subs.panel_release =
      subs.panel->add_subcommand("release", "give an input back to the simulation");
  subs.panel_force->add_option("AXIS", o.p_axis, "axis number, 1-based")->required();
  subs.panel_force->add_option("INPUT", o.p_input, "capture|external|home|estop|cw_limit|ccw_limit")
      ->required();
  subs.panel_force->add_option("LEVEL", o.p_level, "0 or 1 (electrical)")
      ->required()
      ->check(CLI::Range(0, 1));
  subs.panel_release->add_option("AXIS", o.p_axis, "axis number, 1-based")->required();
  subs.panel_release->add_option("INPUT", o.p_input, "input name, or 'all'")->required();
}

// ---- trace files ----
void add_trace(CLI::App& app, CtlOptions& o, CtlSubcommands& subs) {
  auto* trace = app.add_subcommand("trace", "trace files (--trace FILE.vcd of stepmodd)");
  subs.trace_recover =
      trace->add_subcommand("recover",
                            "write the VCD from the spools a daemon left behind (killed, or a "
                            "full disk); the spools are removed once it is written");
  subs.trace_recover->add_option("SPOOL", o.spool_paths, "FILE.vcd.out.spool FILE.vcd.in.spool")
      ->required();
  subs.trace_recover->add_option("-o,--output", o.recovered_vcd, "the VCD to write")->required();
  subs.trace_recover->add_flag("--keep", o.keep_spools, "leave the spools in place");
  trace->require_subcommand(1);
}

}  // namespace

CtlSubcommands define_cli(CLI::App& app, CtlOptions& o) {
  CtlSubcommands subs;
  add_globals(app, o);
  add_inspection(app, o, subs);
  add_configure(app, o.cmd);
  add_moves(app, o);
  add_commands(app, o.cmd);
  add_blend(app, o);
  add_follow(app, o.cmd);
  add_wait_idle_and_gpo(app, o);
  add_path(app, o);
  add_panel(app, o, subs);
  add_trace(app, o, subs);
  return subs;
}

}  // namespace stepmod::tools::ctl
