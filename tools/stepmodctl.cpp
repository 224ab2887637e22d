// stepmodctl: inspect and drive a running stepmod module through the same shared memory a soft
// PLC uses (docs/interface.md 1). This file is main and the commands every module shares (status,
// watch, raw, panel, trace), one function each in a command table; the command line itself is
// tools/ctl_cli.cpp. The module commands are parsed into a ctl::CtlRequest and run by the dialect
// the image header names, through its stepmodctl row (module_types/m3601/ctl_3601.cpp,
// ctl_3602.cpp, ctl_3202.cpp), which calls the PLC-side library (plc/).
//
// Exit status: 0 ok; 1 the module refused the command (an error bit with its reason), or a
// waited-for motion did not end in Move Complete / At Home, or another running process holds the
// commissioning lease (tools/ctl_lease.hpp); 2 usage error (nothing written); 3 the
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
#include "tools/ctl_board.hpp"
#include "tools/ctl_cli.hpp"
#include "tools/ctl_command.hpp"
#include "tools/ctl_dialects.hpp"
#include "tools/ctl_lease.hpp"
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
    "a waited-for motion (--wait, wait-idle) did not end in Move Complete / At Home, or\n"
    "another running process holds the commissioning lease (its pid is printed; nothing is\n"
    "written; stop is never refused; --steal takes the lease over, logged), 2 usage\n"
    "error (also a command or value the module's words cannot carry; nothing is written), 3\n"
    "module unreachable (no image /dev/shm/stepmod.NAME, or no scan in time: a stopped daemon).\n"
    "Numbers accept 0x.. and 16#.. hex; negative numbers are written as they are:\n"
    "  stepmodctl move rel -500 -s 1000 -a 10 -d 10\n"
    "Everything after '--' is positional, so options go before it:\n"
    "  stepmodctl move rel -s 1000 -a 10 -d 10 -- -500\n"
    "Commands that drive the module also bump the PLC heartbeat while they run; with --wait and\n"
    "no PLC they hold the commissioning lease instead (docs/commissioning.md).";

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

std::string stalled_reason(const std::string& name, const ipc::Client& client) {
  return "module '" + name + "' is not scanning (scan counter " +
         std::to_string(client.scan_counter()) +
         " unchanged for 1 s): stepmodd is stopped (SIGSTOP?) or hung; its words are stale";
}

std::string stalled_text(const std::string& name, const ipc::Client& client) {
  return "stepmodctl: " + stalled_reason(name, client) + "\n";
}

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

// ---- the commands that need no image ------------------------------------------------------

int run_panel(const CtlOptions& o, const CtlSubcommands& subs) {
  ipc::SimPanelClient p(o.name);
  if (o.p_axis < 1 || o.p_axis > p.axes()) {
    throw UsageError("AXIS must be 1.." + std::to_string(p.axes()));
  }
  const unsigned axis = o.p_axis - 1;
  if (subs.panel_force->parsed()) {
    p.force(axis, input_index(o.p_input), o.p_level != 0);
  } else if (subs.panel_release->parsed()) {
    if (o.p_input == "all") {
      p.release_all(axis);
    } else {
      p.release(axis, input_index(o.p_input));
    }
  }
  std::cout << format_panel(p);
  return kExitOk;
}

// ---- the commands every module shares, on its image ----------------------------------------

int run_status(const CtlOptions& o, ipc::Client& client) {
  const bool brief = o.brief, json = o.json;
  const auto snap = take_snapshot(client, std::chrono::milliseconds(brief || json ? 100 : 0));
  if (!snap) {
    // The words as they were left (what a stopped daemon last said), and why not to trust them.
    if (!brief && !json) std::cout << status_text(o.name, client);
    if (json) std::cout << json_error_text(o.name, stalled_reason(o.name, client));
    std::cerr << stalled_text(o.name, client);
    return kExitUnreachable;
  }
  std::cout << (json    ? json_text(o.name, client, *snap)
                : brief ? brief_text(o.name, client, *snap)
                        : status_text(o.name, client));
  return kExitOk;
}

int run_watch(const CtlOptions& o, ipc::Client& client) {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  while (!g_stop) {
    // The snapshot's two readings are the refresh period apart (the speed is over it).
    const auto snap = take_snapshot(client, std::chrono::milliseconds(o.interval_ms));
    // Home the cursor and clear: a steady display instead of a scrolling log.
    std::cout << "\x1b[H\x1b[2J";
    if (!snap) {
      std::cout << stalled_text(o.name, client) << std::flush;
      continue;
    }
    std::cout << (o.brief ? brief_text(o.name, client, *snap) : status_text(o.name, client))
              << std::flush;
  }
  return kExitOk;
}

int run_raw_get(const CtlOptions& o, ipc::Client& client) {
  ImageWords out;
  ImageWords in;
  client.read_outputs(out);
  client.read_inputs(in);
  const auto& s = client.shape();
  std::cout << "module '" << o.name << "' type " << static_cast<unsigned>(s.type) << ", "
            << s.word_bytes * 8 << "-bit words, scan " << client.scan_counter() << ", heartbeat "
            << client.heartbeat_value() << "\noutput words (PLC -> "
            << "module):\n"
            << format_words(out, s.output_words, s.word_bytes) << "input words (module -> PLC):\n"
            << format_words(in, s.input_words, s.word_bytes);
  return kExitOk;
}

int run_raw_set(const CtlOptions& o, ipc::Client& client) {
  const auto timeout = std::chrono::milliseconds(o.timeout_ms);
  const std::int64_t words = client.shape().output_words;
  const std::int64_t word = parse_in_range(o.raw_word, "WORD", 0, words - 1, "the output image");
  const bool narrow = client.shape().word_bytes == 2;
  const std::int64_t value = parse_in_range(o.raw_value, "VALUE", narrow ? INT16_MIN : INT32_MIN,
                                            narrow ? UINT16_MAX : UINT32_MAX, "the word size");
  // A write like any command: refused under another running process' lease (--steal: taken over).
  const LeasePlan lease =
      plan_lease(client, LeaseRequest{false, o.steal, false, timeout}, std::cerr);
  if (lease.refused) return kExitModuleError;
  client.write_word(static_cast<unsigned>(word),
                    static_cast<std::int32_t>(static_cast<std::uint32_t>(value)));
  if (!client.wait_scans(2, timeout)) {
    std::cerr << "stepmodctl: written, but the module did not scan within " << o.timeout_ms
              << " ms\n";
    return kExitUnreachable;
  }
  return kExitOk;
}

// ---- a module command, in the dialect the image header names --------------------------------

// The 0-based axis/channel of --axis / --channel (the same thing under two names).
unsigned unit_of(const CtlOptions& o) {
  if (o.axis_no != 0 && o.channel_no != 0 && o.axis_no != o.channel_no) {
    throw UsageError("--axis and --channel name the same thing: give one");
  }
  const unsigned unit_no = o.axis_no != 0 ? o.axis_no : o.channel_no != 0 ? o.channel_no : 1;
  return unit_no - 1;
}

// The commissioning lease (tools/ctl_lease.hpp): held by another running process, the command
// is refused (plan.refused: exit 1, nothing written) unless --steal; --wait holds it while no PLC
// is in control, and a lease holder is no PLC (no heartbeat). A stop (and `path wait`, which
// commands nothing) is never refused. Without
// --wait, say when plc_timeout_ms will cut the motion.
LeasePlan prepare_command(const CtlOptions& o, ipc::Client& client, plc::ShmPort& port) {
  LeaseRequest r;
  r.hold = o.wait && starts_motion(o.cmd.verb);
  r.steal = o.steal;
  r.never_refused = o.cmd.verb == Verb::kStop || o.cmd.verb == Verb::kPathWait;
  r.timeout = std::chrono::milliseconds(o.timeout_ms);
  LeasePlan plan = plan_lease(client, r, std::cerr);
  if (plan.refused) return plan;
  port.set_heartbeat(plan.heartbeat);
  if (!r.hold && starts_motion(o.cmd.verb)) warn_heartbeat_timeout(client, std::cerr);
  return plan;
}

// A stop or hold the module ignored (Command Error left set: 3601-CE-L1) while the axis still
// moves did not do its job, whatever the note says.
int judge_stop(const CtlOptions& o, ipc::Client& client, const plc::Outcome& out) {
  const CtlRequest& cmd = o.cmd;
  if ((cmd.verb == Verb::kStop || cmd.verb == Verb::kHold) && !out.note.empty()) {
    client.wait_scans(2, std::chrono::milliseconds(o.timeout_ms));
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
}

int run_module_command(CtlOptions& o, ipc::Client& client) {
  const auto timeout = std::chrono::milliseconds(o.timeout_ms);
  CtlRequest& cmd = o.cmd;
  cmd.unit = unit_of(o);
  cmd.gpo_on = o.gpo_state == "on";
  plc::ShmPort port(client, timeout);
  if (cmd.verb == Verb::kWaitIdle) {
    return wait_motion_end(client, {cmd.unit}, Motion::kAny, millis(cmd.wait_seconds), std::cout,
                           std::cerr);
  }
  const LeasePlan lease = prepare_command(o, client, port);
  if (lease.refused) return kExitModuleError;
  const plc::Outcome out = ctl_row_of(client.type()).run_command(cmd, port, client, timeout);
  print_outcome(client, out);
  if (!out.ok) return exit_for(out);
  if (o.wait && starts_motion(cmd.verb)) {
    const std::vector<unsigned> units =
        cmd.verb == Verb::kPath ? std::vector<unsigned>{0, 1} : std::vector<unsigned>{cmd.unit};
    return wait_motion_end(client, units, motion_of(cmd.verb), std::chrono::hours(24), std::cout,
                           std::cerr);
  }
  return judge_stop(o, client, out);
}

// ---- the command table ------------------------------------------------------------------------

// The commands on a module's image, by the sub-command that selects them; none parsed: a module
// command.
struct ImageCommand {
  CLI::App* CtlSubcommands::*sub;
  int (*run)(const CtlOptions& o, ipc::Client& client);
};
constexpr ImageCommand kImageCommands[] = {
    {&CtlSubcommands::status, run_status},
    {&CtlSubcommands::watch, run_watch},
    {&CtlSubcommands::raw_get, run_raw_get},
    {&CtlSubcommands::raw_set, run_raw_set},
};

int run_command(CtlOptions& o, const CtlSubcommands& subs) {
  if (subs.trace_recover->parsed()) {
    return recover_spools(o.spool_paths, o.recovered_vcd, o.keep_spools);
  }
  if (subs.panel->parsed()) return run_panel(o, subs);
  ipc::Client client(o.name);
  for (const ImageCommand& c : kImageCommands) {
    if ((subs.*c.sub)->parsed()) return c.run(o, client);
  }
  return run_module_command(o, client);
}

// CLI11's parse; nullopt: go on, else the exit status (help, version, a usage error).
std::optional<int> parse(CLI::App& app, int argc, char** argv) {
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
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{kDescription};
  app.require_subcommand(1);
  app.set_version_flag("--version", "stepmodctl " STEPMOD_VERSION);
  CtlOptions options;
  const CtlSubcommands subs = define_cli(app, options);
  BoardCommands board;  // doctor, isolate: no module needed
  add_board_commands(app, board);
  if (const auto exit_status = parse(app, argc, argv)) return *exit_status;
  if (const auto exit_status = run_board_command(board)) return *exit_status;
  try {
    return run_command(options, subs);
  } catch (const UsageError& e) {
    std::cerr << "stepmodctl: " << e.what() << "\n";
    return kExitUsage;
  } catch (const ipc::IpcError& e) {
    // No image to read: `status --json` still prints its one object, the error one.
    if (options.json) std::cout << json_error_text(options.name, e.what());
    std::cerr << "stepmodctl: " << e.what() << "\n";
    return kExitUnreachable;
  }
}
