// stepmodctl: inspect and drive a running stepmod module through the same shared memory a soft
// PLC uses (INTERFACE.md 1). Every command is the PLC-side library's (plc/): the dialect is
// chosen from the image header's module type.
//
// Exit status: 0 ok; 1 the module reported an error bit for the command; 2 usage error;
// 3 the module cannot be reached (no image, no scan within --timeout); 4 the module's command
// dialect is not implemented yet (3602, 3202: status, watch and raw work).
#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "ipc/client.hpp"
#include "ipc/codec.hpp"
#include "ipc/sim_panel.hpp"
#include "module/m3202/blend_message_3202.hpp"
#include "module/m3202/words_3202.hpp"
#include "module/m3601/words_3601.hpp"
#include "module/m3602/words_3602.hpp"
#include "plc/plc_3202.hpp"
#include "plc/plc_3601.hpp"
#include "plc/plc_3602.hpp"
#include "plc/shm_port.hpp"
#include "tools/ctl_3202.hpp"
#include "tools/ctl_status.hpp"

namespace {

using namespace stepmod;
using plc::AccelType;
using plc::Outcome;
using plc::Plc3601;
using plc::Profile;

constexpr int kExitOk = 0;
constexpr int kExitModuleError = 1;
constexpr int kExitUsage = 2;
constexpr int kExitUnreachable = 3;
constexpr int kExitNoDialect = 4;

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) {
  g_stop = 1;
}

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Accepts decimal, 0x hex and 16# (PLC notation) hex, with a sign.
std::int64_t parse_number(const std::string& s, const char* what) {
  std::string t = s;
  bool neg = false;
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) {
    neg = t[0] == '-';
    t.erase(0, 1);
  }
  int base = 10;
  if (t.rfind("0x", 0) == 0 || t.rfind("0X", 0) == 0) {
    base = 16;
    t.erase(0, 2);
  } else if (t.rfind("16#", 0) == 0) {
    base = 16;
    t.erase(0, 3);
  }
  std::size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(t, &used, base);
  } catch (const std::exception&) {
    used = 0;
  }
  if (t.empty() || used != t.size()) {
    throw UsageError(std::string(what) + ": '" + s + "' is not a number");
  }
  return neg ? -v : v;
}

// The 3601 carries a 32-bit parameter as MSW * 1000 + LSW in two 16-bit INTs (digest 2.1).
// Beyond this range the MSW would wrap and the module would read another, possibly valid,
// number (a target of 65,537,000 would arrive as 1,000 and move the axis). Values the words can
// carry but the module refuses (a target beyond 8,388,607) are sent: the module reports them.
constexpr std::int64_t kSplitMin = -32'768'999;
constexpr std::int64_t kSplitMax = 32'767'999;

std::int32_t split_number(const std::string& s, const char* what) {
  const std::int64_t v = parse_number(s, what);
  if (v < kSplitMin || v > kSplitMax) {
    throw UsageError(std::string(what) + ": '" + s + "' does not fit the 3601's two words (" +
                     std::to_string(kSplitMin) + ".." + std::to_string(kSplitMax) + ")");
  }
  return static_cast<std::int32_t>(v);
}

// The 3602 carries a 32-bit parameter as a binary split (digest 2.2): every int32 fits; the module
// itself refuses what is out of its ranges.
std::int32_t binary_number(const std::string& s, const char* what) {
  const std::int64_t v = parse_number(s, what);
  if (v < INT32_MIN || v > INT32_MAX) {
    throw UsageError(std::string(what) + ": '" + s + "' does not fit the 3602's two words");
  }
  return static_cast<std::int32_t>(v);
}

// A plain 16-bit word (accelerations); a wider value would be truncated to another number.
std::int32_t word_number(const std::string& s, const char* what) {
  const std::int64_t v = parse_number(s, what);
  if (v < INT16_MIN || v > INT16_MAX) {
    throw UsageError(std::string(what) + ": '" + s + "' does not fit a 16-bit word");
  }
  return static_cast<std::int32_t>(v);
}

bool parse_direction(const std::string& s) {
  if (s == "+" || s == "cw" || s == "CW") return true;
  if (s == "-" || s == "ccw" || s == "CCW") return false;
  throw UsageError("direction must be + (cw) or - (ccw), not '" + s + "'");
}

AccelType parse_accel(const std::string& s) {
  if (s.empty() || s == "const" || s == "constant") return AccelType::kConstant;
  if (s == "tri" || s == "triangular") return AccelType::kTriangularS;
  if (s == "trap" || s == "trapezoidal") return AccelType::kTrapezoidalS;
  throw UsageError("acceleration type must be const, tri or trap, not '" + s + "'");
}

// --speed/--accel/--decel/--scurve on a sub-command.
struct ProfileOpts {
  std::int32_t speed = 0;
  std::int32_t accel = 0;
  std::int32_t decel = 0;
  std::string scurve;
  CLI::Option* speed_opt = nullptr;

  void add(CLI::App* app, bool required, bool with_scurve = true) {
    speed_opt = app->add_option("--speed,-s", speed, "programmed speed, steps/s")
                    ->check(CLI::Range(kSplitMin, kSplitMax));
    app->add_option("--accel,-a", accel,
                    "acceleration: steps/ms/s on a 3601 (1..2000), steps/s^2 on a 3202 "
                    "(1000..2000000)");
    app->add_option("--decel,-d", decel, "deceleration, in the same unit as --accel");
    if (required) {
      speed_opt->required();
      app->get_option("--accel")->required();
      app->get_option("--decel")->required();
    }
    if (with_scurve) {
      app->add_option("--scurve", scurve, "S-curve acceleration: tri or trap (default constant)")
          ->check(CLI::IsMember({"tri", "trap", "const"}));
    }
  }
  Profile profile() const { return {speed, accel, decel, parse_accel(scurve)}; }
  // The 3601's accel/decel are 16-bit words: a wider value would arrive as another number.
  void require_16bit() const {
    if (accel < INT16_MIN || accel > INT16_MAX || decel < INT16_MIN || decel > INT16_MAX) {
      throw UsageError("--accel/--decel do not fit the 3601's 16-bit words");
    }
  }
};

void print_outcome(const ipc::Client& c, const Outcome& o) {
  // After a timeout the image says nothing about the command: only the message.
  if (!o.timed_out) std::cout << tools::ctl::format_status(c.type(), o.in);
  if (!o.ok) std::cerr << "stepmodctl: " << o.message << "\n";
}

int exit_for(const Outcome& o) {
  if (o.ok) return kExitOk;
  return o.timed_out ? kExitUnreachable : kExitModuleError;
}

unsigned panel_input(const std::string& s) {
  static const char* names[] = {"capture", "external", "home", "estop", "cw_limit", "ccw_limit"};
  for (unsigned i = 0; i < 6; ++i) {
    if (s == names[i]) return i;
  }
  throw UsageError("input must be one of capture, external, home, estop, cw_limit, ccw_limit");
}

std::string panel_text(const ipc::SimPanelClient& p) {
  static const char* names[] = {"capture", "external", "home", "estop", "cw_limit", "ccw_limit"};
  std::string s;
  for (unsigned a = 0; a < p.axes(); ++a) {
    const ipc::PanelAxis x = p.read(a);
    s += "axis " + std::to_string(a + 1) + ": position " + std::to_string(x.position) +
         "  encoder " + std::to_string(x.encoder) +
         "  outputs step/cw=" + std::to_string(x.outputs & 1) +
         " dir/ccw=" + std::to_string((x.outputs >> 1) & 1) +
         " gpo=" + std::to_string((x.outputs >> 2) & 1) + "\n  forced:";
    bool any = false;
    for (unsigned i = 0; i < 6; ++i) {
      if (x.force_mask & (1u << i)) {
        s += std::string(" ") + names[i] + "=" + std::to_string((x.force_levels >> i) & 1);
        any = true;
      }
    }
    s += any ? "\n" : " none\n";
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "stepmodctl: inspect and drive a running stepmod module through its shared-memory image,\n"
      "exactly as a PLC program would (write parameters + command bit, wait for the module's\n"
      "scan, release the bit, show the decoded status).\n\n"
      "Exit status: 0 ok, 1 the module reported an error bit (Command Error, Invalid Profile,\n"
      "Home Invalid, Configuration Error) for the command, 2 usage error, 3 module unreachable\n"
      "(no image /dev/shm/stepmod.NAME, or no scan in time), 4 the command is not implemented yet\n"
      "for this module (the 3602 has configure, move, preset, reset, stop, gpo and wait-idle, with\n"
      "--axis 1|2; the 3601 and the 3202, with --channel 1|2, have every command).\n"
      "Numbers accept 0x.. and 16#.. hex. Negative targets: use '--' before them if needed,\n"
      "e.g. stepmodctl move rel -- -500 -s 1000 -a 10 -d 10.\n"
      "Commands that drive the module also bump the PLC heartbeat while they run."};
  app.require_subcommand(1);
  std::string name = "stepmod";
  int timeout_ms = 2000;
  app.add_option("--name,-n", name, "module name: /dev/shm/stepmod.NAME (default stepmod)");
  unsigned channel = 1;
  app.add_option("--channel,-c", channel, "3202: the channel a command acts on, 1 or 2 (1)")
      ->check(CLI::Range(1, 2));
  app.add_option("--timeout", timeout_ms, "ms to wait for the module's scans/handshakes (2000)")
      ->check(CLI::NonNegativeNumber);
  unsigned axis_no = 1;
  app.add_option("--axis", axis_no, "3602: the axis a command is for, 1 or 2 (1)")
      ->check(CLI::Range(1, 2));

  // ---- inspection ----
  auto* status = app.add_subcommand("status",
                                    "decoded input image: every status bit by name, "
                                    "positions as numbers");
  auto* watch = app.add_subcommand("watch", "status, refreshed until Ctrl-C");
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

  // ---- 3601 commands ----
  auto* configure = app.add_subcommand(
      "configure", "3601: enter configuration mode with these settings, then command mode");
  bool c_capture = false, c_external = false, c_home = false, c_estop = false, c_cw = false,
       c_ccw = false, c_prox = false, c_enc = false, c_diag = false, c_cwccw = false,
       c_marker = false;
  std::vector<std::string> c_low;
  std::int32_t c_vs = 1000;
  configure->add_flag("--capture", c_capture, "capture input used (bit 0)");
  configure->add_flag("--external", c_external, "external input used (bit 1)");
  configure->add_flag("--home", c_home, "home input used (bit 2)");
  configure->add_flag("--estop", c_estop, "E-stop input used (bit 3)");
  configure->add_flag("--cw-limit", c_cw, "CW limit used (bit 4)");
  configure->add_flag("--ccw-limit", c_ccw, "CCW limit used (bit 5)");
  configure->add_flag("--backplane-proximity", c_prox, "backplane home proximity (bit 6)");
  configure->add_flag("--encoder", c_enc, "quadrature encoder used (bit 8)");
  configure->add_flag("--diagnostic-feedback", c_diag, "diagnostic feedback (bit 9)");
  configure->add_flag("--cw-ccw", c_cwccw, "CW/CCW pulse outputs (bit 10 = 0; default step+dir)");
  configure->add_flag("--marker-homing", c_marker, "marker-pulse homing (bit 12)");
  configure
      ->add_option("--active-low", c_low,
                   "inputs that are active low (N.C.): capture,external,home,estop,cw_limit,"
                   "ccw_limit; all others active high")
      ->delimiter(',');
  bool c_cw_estop = false, c_ccw_estop = false, c_disable = false;
  std::int16_t c_timeout = 0;
  configure->add_flag("--cw-estop", c_cw_estop, "3602: the CW input is an E-stop (bits 4:3 = 10)");
  configure->add_flag("--ccw-estop", c_ccw_estop,
                      "3602: the CCW input is an E-stop (bits 6:5 = 10)");
  configure->add_flag("--disable", c_disable,
                      "3602: disable the axis (bit 14); 3202: disable the channel (bit 28)");
  configure->add_option("--homing-timeout", c_timeout, "3602: homing timeout, s (0 = none)")
      ->check(CLI::Range(INT16_MIN, INT16_MAX));
  configure->add_option("--start-speed", c_vs, "starting speed, steps/s (1000)")
      ->check(CLI::Range(kSplitMin, kSplitMax));

  auto* move = app.add_subcommand("move", "3601: absolute or relative move");
  std::string move_kind;
  std::string move_target;
  bool move_encoder = false;
  ProfileOpts move_p;
  move->add_option("KIND", move_kind, "abs or rel")
      ->required()
      ->check(CLI::IsMember({"abs", "rel"}));
  move->add_option("TARGET", move_target, "target position or offset, steps")->required();
  move_p.add(move, true);
  move->add_flag("--encoder", move_encoder, "encoder-count move (command LSW bit 2)");

  auto* jog = app.add_subcommand("jog", "3601: manual move (level-held) for --for seconds");
  std::string jog_dir;
  double jog_for = 1.0;
  std::int32_t jog_reg = 0;
  ProfileOpts jog_p;
  jog->add_option("DIR", jog_dir, "+ (cw) or - (ccw)")->required();
  jog_p.add(jog, true);
  jog->add_option("--for,-t", jog_for, "seconds to hold the manual move bit (1)")
      ->check(CLI::Range(0.0, 1e6));
  jog->add_option("--registration", jog_reg, "registration move: steps after the stop trigger")
      ->check(CLI::Range(kSplitMin, kSplitMax));

  auto* home = app.add_subcommand("home", "3601: find home in direction + or -");
  std::string home_dir;
  ProfileOpts home_p;
  home->add_option("DIR", home_dir, "+ (cw) or - (ccw)")->required();
  home_p.add(home, true, false);

  auto* hold = app.add_subcommand("hold", "3601: hold move (controlled stop, resumable)");
  auto* resume = app.add_subcommand("resume", "3601: resume a held move");
  ProfileOpts resume_p;
  resume_p.add(resume, false);
  auto* stop = app.add_subcommand("stop", "3601: immediate stop");
  auto* preset = app.add_subcommand("preset", "3601: preset the current position");
  std::string preset_value;
  preset->add_option("POSITION", preset_value, "new position")->required();
  auto* preset_enc = app.add_subcommand("preset-encoder", "3601: preset the encoder count");
  std::string preset_enc_value = "0";
  preset_enc->add_option("VALUE", preset_enc_value, "new encoder count (0)");
  auto* reset = app.add_subcommand("reset", "3601: reset errors");
  auto* minreg =
      app.add_subcommand("min-registration", "3601: store the minimum registration distance");
  std::string minreg_value;
  minreg->add_option("DISTANCE", minreg_value, "steps, 0 disables")->required();

  auto* blend = app.add_subcommand("blend", "3601: blend move profiles");
  blend->require_subcommand(1);
  auto* blend_prog = blend->add_subcommand(
      "program",
      "program a profile with the block handshake (program bit, transmit edges, "
      "acknowledge)");
  std::vector<std::string> segs;
  std::int32_t final_decel = 0;
  std::string final_type;
  std::string blend_file;
  blend_prog->add_option("--segment", segs,
                         "LENGTH:SPEED:ACCEL[:tri|trap], once per segment in order (2..16)");
  // 3601: word 5 carries the type in bits 15..14 and the value in bits 13..0 (checked below);
  // 3202: DINT 3, bits 31..30 and 29..0.
  blend_prog->add_option("--final-decel", final_decel,
                         "final deceleration, steps/ms/s (3601) or steps/s^2 (3202)");
  blend_prog->add_option("--final-type", final_type, "final deceleration type: const|tri|trap");
  blend_prog->add_option("--file", blend_file,
                         "3202: the profile from a file (segment = L:S:A[:type], final_decel = "
                         "N, final_type = T; one per line)");
  auto* blend_run = blend->add_subcommand("run", "run the stored profile, + or -");
  std::string blend_dir;
  blend_run->add_option("DIR", blend_dir, "+ (cw) or - (ccw)")->required();

  auto* follow = app.add_subcommand(
      "follow", "3601: encoder follower mode; its bits are levels: it stays on until 'follow off'");
  std::string follow_sense;
  std::int16_t follow_mul = 1;
  std::int16_t follow_div = 1;
  std::int16_t follow_accel = 0;
  std::int16_t follow_decel = 0;
  follow
      ->add_option("SENSE", follow_sense,
                   "+ (same sense as the master), - (reverse), 0 (follower mode, no motion), off")
      ->required()
      ->check(CLI::IsMember({"+", "-", "0", "off"}));
  // Words 2 and 3 carry multiplier and divisor as plain 16-bit integers (digest 3.5).
  follow->add_option("--multiplier,-m", follow_mul, "ratio multiplier, 1..32767 (1)")
      ->check(CLI::Range(1, 32767));
  follow->add_option("--divisor,-D", follow_div, "ratio divisor, 1..32767 (1)")
      ->check(CLI::Range(1, 32767));
  follow->add_option("--accel,-a", follow_accel, "acceleration, steps/ms/s (0..2000)")
      ->check(CLI::Range(INT16_MIN, INT16_MAX));
  follow->add_option("--decel,-d", follow_decel, "deceleration, steps/ms/s (0..2000)")
      ->check(CLI::Range(INT16_MIN, INT16_MAX));

  auto* wait_idle = app.add_subcommand("wait-idle", "3601: wait until the axis is not moving");
  double wait_s = 60;
  wait_idle->add_option("--max", wait_s, "give up after this many seconds (60)")
      ->check(CLI::Range(0.0, 1e6));

  auto* gpo = app.add_subcommand("gpo", "3602: the general-purpose output (command LSW bit 7)");
  std::string gpo_state;
  gpo->add_option("STATE", gpo_state, "on or off")->required()->check(CLI::IsMember({"on", "off"}));

  // ---- simulator panel ----
  auto* panel = app.add_subcommand("panel", "simulator panel: show, force or release inputs");
  auto* panel_show = panel->add_subcommand("show", "positions, outputs and forced inputs");
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

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }

  try {
    const auto timeout = std::chrono::milliseconds(timeout_ms);

    if (panel->parsed()) {
      ipc::SimPanelClient p(name);
      const unsigned axis = p_axis - 1;
      if (panel_force->parsed()) {
        p.force(axis, panel_input(p_input), p_level != 0);
      } else if (panel_release->parsed()) {
        if (p_input == "all") {
          p.release_all(axis);
        } else {
          p.release(axis, panel_input(p_input));
        }
      }
      (void)panel_show;
      std::cout << panel_text(p);
      return kExitOk;
    }

    ipc::Client client(name);

    if (status->parsed()) {
      ImageWords in;
      client.read_inputs(in);
      std::cout << "module '" << name << "' scan " << client.scan_counter() << "\n"
                << tools::ctl::format_status(client.type(), in)
                << tools::ctl::format_health(client.read_health());
      return kExitOk;
    }
    if (watch->parsed()) {
      std::signal(SIGINT, on_signal);
      std::signal(SIGTERM, on_signal);
      while (!g_stop) {
        ImageWords in;
        client.read_inputs(in);
        // Home the cursor and clear: a steady display instead of a scrolling log.
        std::cout << "\x1b[H\x1b[2J"
                  << "module '" << name << "' scan " << client.scan_counter() << "\n"
                  << tools::ctl::format_status(client.type(), in)
                  << tools::ctl::format_health(client.read_health()) << std::flush;
        std::this_thread::sleep_for(std::chrono::milliseconds(interval_ms));
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
                << tools::ctl::format_words(out, s.output_words, s.word_bytes)
                << "input words (module -> PLC):\n"
                << tools::ctl::format_words(in, s.input_words, s.word_bytes);
      return kExitOk;
    }
    if (raw_set->parsed()) {
      const std::int64_t word = parse_number(raw_word, "WORD");
      const std::int64_t value = parse_number(raw_value, "VALUE");
      if (word < 0 || word >= static_cast<std::int64_t>(client.shape().output_words)) {
        throw UsageError("WORD must be 0.." + std::to_string(client.shape().output_words - 1));
      }
      const std::int64_t lo = client.shape().word_bytes == 2 ? -32768 : INT32_MIN;
      const std::int64_t hi = client.shape().word_bytes == 2 ? 65535 : UINT32_MAX;
      if (value < lo || value > hi) throw UsageError("VALUE does not fit the word size");
      client.write_word(static_cast<unsigned>(word),
                        static_cast<std::int32_t>(static_cast<std::uint32_t>(value)));
      if (!client.wait_scans(2, timeout)) {
        std::cerr << "stepmodctl: written, but the module did not scan within " << timeout_ms
                  << " ms\n";
        return kExitUnreachable;
      }
      return kExitOk;
    }

    // The 3202's commands, on channel `ch` (0 or 1); its numbers are native DINTs and its rates
    // steps/s^2, so the options are passed as given and the module judges them.
    auto run_3202 = [&](plc::Port& port, ipc::Client& c, std::chrono::milliseconds t,
                        unsigned ch) -> Outcome {
      namespace cb = module::m3202::cfg_bit;
      plc::Plc3202 plc(port, t);
      if (configure->parsed()) {
        std::uint32_t bits = 0;
        bits |= c_capture ? cb::kCaptureUsed : 0;
        bits |= c_external ? cb::kExternalUsed : 0;
        bits |= c_home ? cb::kHomeUsed : 0;
        bits |= c_estop ? cb::kEStopUsed : 0;
        bits |= c_cw ? cb::kCwLimitUsed : 0;
        bits |= c_ccw ? cb::kCcwLimitUsed : 0;
        bits |= c_prox ? cb::kBackplaneProximity : 0;
        bits |= c_enc ? cb::kQuadratureEncoder : 0;
        bits |= c_diag ? cb::kDiagnosticFeedback : 0;
        bits |= c_cwccw ? 0 : cb::kStepDirOutput;
        bits |= c_marker ? cb::kMarkerHoming : 0;
        bits |= c_disable ? cb::kDisable : 0;
        // Active levels in bits 16..21: active high unless named (digest 5.2).
        std::uint32_t levels = cb::kActiveLevels;
        for (const auto& in : c_low) levels &= ~(1u << (cb::kActiveLevelShift + panel_input(in)));
        return plc.configure(ch, bits | levels, c_vs);
      }
      if (move->parsed()) {
        return plc.move(ch, move_kind == "abs", split_number(move_target, "TARGET"),
                        move_p.profile(), move_encoder);
      }
      if (jog->parsed()) {
        if (jog_reg != 0) throw UsageError("the 3202 has no registration move");
        return plc.jog(ch, parse_direction(jog_dir), jog_p.profile(),
                       std::chrono::milliseconds(static_cast<long>(jog_for * 1000)));
      }
      if (home->parsed()) return plc.home(ch, parse_direction(home_dir), home_p.profile());
      if (hold->parsed()) return plc.hold(ch);
      if (resume->parsed()) {
        std::optional<Profile> p;
        if (resume_p.speed_opt->count() > 0) p = resume_p.profile();
        return plc.resume(ch, p);
      }
      if (stop->parsed()) return plc.immediate_stop(ch);
      if (preset->parsed()) return plc.preset_position(ch, split_number(preset_value, "POSITION"));
      if (preset_enc->parsed()) {
        return plc.preset_encoder(ch, split_number(preset_enc_value, "VALUE"));
      }
      if (reset->parsed()) return plc.reset_errors(ch);
      if (blend_run->parsed()) return plc.blend_run(ch, parse_direction(blend_dir));
      if (wait_idle->parsed()) {
        return plc.wait_idle(ch, std::chrono::milliseconds(static_cast<long>(wait_s * 1000)));
      }
      if (blend_prog->parsed()) {
        plc::BlendProfile b;
        try {
          if (!blend_file.empty()) {
            b = tools::ctl::read_blend_file(blend_file);
          } else {
            for (const std::string& s : segs)
              b.segments.push_back(tools::ctl::parse_blend_segment(s));
            b.final_decel = final_decel;
            b.final_type = tools::ctl::parse_accel_type(final_type);
          }
        } catch (const tools::ctl::BlendSyntaxError& e) {
          throw UsageError(e.what());
        }
        // The 52-DINT message through the image's mailbox (INTERFACE.md 3).
        const auto data = plc::m3202::blend_message(static_cast<std::int32_t>(ch + 1), b);
        const auto result = c.send_message(data, t);
        Outcome o = plc.status(ch);
        if (!result) {
          o.ok = false;
          o.timed_out = true;
          o.message = "blend: the module did not take the message (is stepmodd running?)";
        } else if (*result != module::m3202::kMessageAccepted) {
          o.ok = false;
          o.message = "blend: message refused (result " + std::to_string(*result) +
                      "; see Invalid Profile / Command Error)";
        }
        return o;
      }
      throw UsageError(std::string("this command does not exist on the 3202"));
    };

    // Everything below is a command in the module's dialect, chosen by the image header.
    switch (client.type()) {
      case ModuleType::k3601:
        for (const ProfileOpts* p : {&move_p, &jog_p, &home_p, &resume_p}) p->require_16bit();
        if (blend_prog->parsed() && (segs.empty() || final_decel < 0 || final_decel > 0x3FFF)) {
          throw UsageError("blend program: --segment (2..16) and --final-decel 0..16383 needed");
        }
        break;
      case ModuleType::k3602: {
        plc::ShmPort port(client, timeout);
        plc::Plc3602 p3(port, timeout);
        const unsigned ax = axis_no - 1;
        Outcome o3;
        if (configure->parsed()) {
          namespace cm = module::m3602::cfg_msw;
          if (c_estop || c_enc || c_diag || c_marker) {
            throw UsageError(
                "the 3602 has no E-stop terminal, encoder or marker homing (use --cw-estop / "
                "--ccw-estop)");
          }
          const auto function = [](bool limit, bool estop) -> unsigned {
            return estop ? cm::kFunctionEStop : limit ? cm::kFunctionLimit : cm::kFunctionUnused;
          };
          std::uint16_t msw = 0;
          msw |= c_capture ? cm::kCaptureEnabled : 0;
          msw |= c_external ? cm::kExternalEnabled : 0;
          msw |= c_home ? cm::kHomeEnabled : 0;
          msw |= static_cast<std::uint16_t>(function(c_cw, c_cw_estop) << cm::kCwFunctionShift);
          msw |= static_cast<std::uint16_t>(function(c_ccw, c_ccw_estop) << cm::kCcwFunctionShift);
          msw |= c_prox ? cm::kBackplaneProximity : 0;
          msw |= c_cwccw ? 0 : cm::kStepDirOutput;
          msw |= c_disable ? cm::kDisableAxis : 0;
          // Active levels: capture, external, home, CW, CCW (bits 0..4), active high unless named.
          std::uint16_t lsw = 0x1F;
          for (const auto& in : c_low) {
            const unsigned i = panel_input(in);
            if (i == 3) throw UsageError("the 3602 has no estop input");
            lsw = static_cast<std::uint16_t>(lsw & ~(1u << (i < 3 ? i : i - 1)));
          }
          o3 = p3.configure(ax, msw, lsw, c_vs, c_timeout);
        } else if (move->parsed()) {
          o3 = p3.move(ax, move_kind == "abs", binary_number(move_target, "TARGET"),
                       move_p.profile());
        } else if (preset->parsed()) {
          o3 = p3.preset_position(ax, binary_number(preset_value, "POSITION"));
        } else if (reset->parsed()) {
          o3 = p3.reset_errors(ax);
        } else if (stop->parsed()) {
          o3 = p3.immediate_stop(ax);
        } else if (gpo->parsed()) {
          o3 = p3.set_gpo(ax, gpo_state == "on");
        } else if (wait_idle->parsed()) {
          o3 = p3.wait_idle(ax, std::chrono::milliseconds(static_cast<long>(wait_s * 1000)));
        } else {
          std::cerr << "stepmodctl: module '" << name
                    << "' is a 3602: this command is not implemented yet for it (configure, "
                       "move, preset, reset, stop, gpo, wait-idle are)\n";
          return kExitNoDialect;
        }
        print_outcome(client, o3);
        return exit_for(o3);
      }
      case ModuleType::k3202: {
        plc::ShmPort port3202(client, timeout);
        const Outcome o3202 = run_3202(port3202, client, timeout, channel - 1);
        print_outcome(client, o3202);
        return exit_for(o3202);
      }
    }
    if (axis_no != 1) throw UsageError("the 3601 has one axis: --axis 1");
    if (c_cw_estop || c_ccw_estop || c_disable || c_timeout != 0) {
      throw UsageError("--cw-estop, --ccw-estop, --disable and --homing-timeout are the 3602's");
    }
    plc::ShmPort port(client, timeout);
    Plc3601 plc(port, timeout);
    Outcome o;
    if (configure->parsed()) {
      namespace cm = module::m3601::cfg_msw;
      std::uint16_t msw = 0;
      msw |= c_capture ? cm::kCaptureUsed : 0;
      msw |= c_external ? cm::kExternalUsed : 0;
      msw |= c_home ? cm::kHomeUsed : 0;
      msw |= c_estop ? cm::kEStopUsed : 0;
      msw |= c_cw ? cm::kCwLimitUsed : 0;
      msw |= c_ccw ? cm::kCcwLimitUsed : 0;
      msw |= c_prox ? cm::kBackplaneProximity : 0;
      msw |= c_enc ? cm::kQuadratureEncoder : 0;
      msw |= c_diag ? cm::kDiagnosticFeedback : 0;
      msw |= c_cwccw ? 0 : cm::kStepDirOutput;
      msw |= c_marker ? cm::kMarkerHoming : 0;
      // The manual advises active-high level bits even for unused inputs (digest 3.3).
      std::uint16_t lsw = 0x3F;
      for (const auto& in : c_low) lsw = static_cast<std::uint16_t>(lsw & ~(1u << panel_input(in)));
      o = plc.configure(msw, lsw, c_vs);
    } else if (move->parsed()) {
      const std::int32_t target = split_number(move_target, "TARGET");
      o = plc.move(move_kind == "abs", target, move_p.profile(), move_encoder);
    } else if (jog->parsed()) {
      o = plc.jog(parse_direction(jog_dir), jog_p.profile(),
                  std::chrono::milliseconds(static_cast<long>(jog_for * 1000)), jog_reg);
    } else if (home->parsed()) {
      o = plc.home(parse_direction(home_dir), home_p.profile());
    } else if (hold->parsed()) {
      o = plc.hold();
    } else if (resume->parsed()) {
      std::optional<Profile> p;
      if (resume_p.speed_opt->count() > 0) p = resume_p.profile();
      o = plc.resume(p);
    } else if (stop->parsed()) {
      o = plc.immediate_stop();
    } else if (preset->parsed()) {
      o = plc.preset_position(split_number(preset_value, "POSITION"));
    } else if (preset_enc->parsed()) {
      o = plc.preset_encoder(split_number(preset_enc_value, "VALUE"));
    } else if (reset->parsed()) {
      o = plc.reset_errors();
    } else if (minreg->parsed()) {
      o = plc.set_min_registration(split_number(minreg_value, "DISTANCE"));
    } else if (blend_prog->parsed()) {
      plc::BlendProfile b;
      for (const std::string& s : segs) {
        std::vector<std::string> f;
        std::size_t start = 0;
        for (std::size_t i = 0; i <= s.size(); ++i) {
          if (i == s.size() || s[i] == ':') {
            f.push_back(s.substr(start, i - start));
            start = i + 1;
          }
        }
        if (f.size() < 3 || f.size() > 4) {
          throw UsageError("--segment '" + s + "': expected LENGTH:SPEED:ACCEL[:tri|trap]");
        }
        b.segments.push_back({split_number(f[0], "LENGTH"), split_number(f[1], "SPEED"),
                              word_number(f[2], "ACCEL"), parse_accel(f.size() == 4 ? f[3] : "")});
      }
      b.final_decel = final_decel;
      b.final_type = parse_accel(final_type);
      o = plc.blend_program(b);
    } else if (blend_run->parsed()) {
      o = plc.blend_run(parse_direction(blend_dir));
    } else if (follow->parsed()) {
      if (follow_sense == "off") {
        o = plc.end_follow();
      } else {
        const int sense = follow_sense == "+" ? 1 : follow_sense == "-" ? -1 : 0;
        o = plc.follow(sense, follow_mul, follow_div, follow_accel, follow_decel);
      }
    } else if (wait_idle->parsed()) {
      o = plc.wait_idle(std::chrono::milliseconds(static_cast<long>(wait_s * 1000)));
    } else {
      std::cerr << app.help();
      return kExitUsage;
    }
    print_outcome(client, o);
    return exit_for(o);
  } catch (const UsageError& e) {
    std::cerr << "stepmodctl: " << e.what() << "\n";
    return kExitUsage;
  } catch (const ipc::IpcError& e) {
    std::cerr << "stepmodctl: " << e.what() << "\n";
    return kExitUnreachable;
  }
}
