// daemon_vm_test: the real stepmodd on the real kernel GPIO path, inside the test VM (issue 4).
// Each sub-command is one VM case (tests/vm/cases/daemon_*.sh): it writes a stepmod config for
// the gpio-sim board (scripts/vm/guest/board-setup.sh: BOARD_CHIP, GPIO_SIM_DIR, AX1_STEP, ...
// in the environment), starts stepmodd (gpiod backend, --trace), drives it as a PLC does
// (ipc::Client), drives the inputs through sim_gpioN/pull, samples the outputs through
// sim_gpioN/value and checks everything against the daemon's VCD (helpers shared with
// modules_vm_test, the 3202/3602 cases: tests/vm/vm_harness.hpp).
//
//   daemon_vm_test errors     missing chip, line out of range, line in use: exit 1 naming them
//   daemon_vm_test move       relative move: sampled outputs = VCD, exact pulse count
//   daemon_vm_test estop      E-stop pull change stops a move: IE, PI, Stopped, no motion bits
//   daemon_vm_test capture    kernel-stamped capture edges latch the step count of the VCD
//   daemon_vm_test burst      hundreds of input edges during a move: none lost, pulses exact
//   daemon_vm_test sigterm    SIGTERM mid-move: outputs idle, then released, lines free again
//   daemon_vm_test homing     home switch / limits through sysfs: Find Home completes
//   daemon_vm_test options    [[axis]] line options on the kernel's lines: bias, active_low,
//                             drive, debounce_us (libgpiod 2; refused by a libgpiod 1.6 build)
//   daemon_vm_test lost       input edges the kernel dropped (reader stopped): health bit 5 and
//                             the log say so (libgpiod 2: the exact count from sequence numbers)
//
// Prints what it does; the last line is "ok: ..." (exit 0), "FAIL: ..." (exit 1) or
// "skip: ..." (exit 77).
#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "ipc/client.hpp"
#include "module_types/m3601/plc_3601.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "plc/bit_names.hpp"
#include "plc/shm_port.hpp"
#include "tests/support/vcd_reader.hpp"
#include "tests/vm/gpio_uapi.hpp"
#include "tests/vm/vm_harness.hpp"

namespace {

namespace m = stepmod::words::m3601;
namespace st = m::status_msw;
namespace cmd = m::cmd_msw;
namespace cfg = m::cfg_msw;
using namespace stepmod::vmtest;  // NOLINT: the harness is this program's vocabulary

// ---- the config ------------------------------------------------------------------------------

struct ConfigOptions {
  std::string name = "vm";
  std::string chip;                              // default: the board's
  std::map<std::string, long> lines;             // key -> offset; default: every line of the board
  std::map<std::string, std::string> line_text;  // key -> its value as written (an inline table)
  long step_pulse_ns = 1'000'000;
  long dir_setup_ns = 20'000;
  int priority = 80;
};

const char* const kLineKeys[] = {"step",     "dir",       "capture", "external", "home", "estop",
                                 "cw_limit", "ccw_limit", "enc_a",   "enc_b",    "enc_z"};

std::string write_config(const ConfigOptions& o, const std::string& path) {
  std::ostringstream c;
  c << "[module]\ntype = \"3601\"\nname = \"" << o.name << "\"\nscan_us = 1000\n\n"
    << "[gpio]\nbackend = \"gpiod\"\nchip = \"" << (o.chip.empty() ? env("BOARD_CHIP") : o.chip)
    << "\"\n\n"
    << rt_section(o.priority) << "\n[[axis]]\n"
    << axis_guard();
  for (const char* k : kLineKeys) {
    const auto it = o.lines.find(k);
    if (const auto t = o.line_text.find(k); t != o.line_text.end()) {
      c << k << " = " << t->second << "\n";
    } else if (it == o.lines.end()) {
      c << k << " = " << line(k) << "\n";
    } else if (it->second >= 0) {
      c << k << " = " << it->second << "\n";
    }  // < 0: left out (wired to nothing)
  }
  c << "step_pulse_ns = " << o.step_pulse_ns << "\ndir_setup_ns = " << o.dir_setup_ns << "\n";
  std::ofstream(path) << c.str();
  return path;
}

// stepmodd as a 3601 on the config these options describe.
class Daemon3601 : public Daemon {
 public:
  Daemon3601(const ConfigOptions& o, const std::string& tag, bool trace = true)
      : Daemon(o.name, write_config(o, "/tmp/" + tag + ".toml"), tag, trace) {}
};

// ---- the PLC side -----------------------------------------------------------------------------

// The PLC-side library (module_types/m3601/plc_3601.hpp) over the shared-memory port, at the scan
// counts these cases were written for (a command's words held 3 scans, 2 after the release; 3 + 3
// for a configuration); a module that stops scanning fails the case.
class Plc {
 public:
  explicit Plc(const std::string& name)
      : c_(name), port_(c_, milliseconds(5'000)), plc_(port_, milliseconds(5'000), kSeq) {}
  stepmod::plc::m3601::Status decoded() const {
    stepmod::ImageWords w{};
    if (!port_.read_inputs(w)) fail("reading the input image: its sequence stayed busy");
    return stepmod::plc::m3601::decode_status(w);
  }
  std::uint16_t msw() const { return decoded().msw; }
  bool status(std::uint16_t bit) const { return decoded().has(bit); }
  std::int64_t position() const { return decoded().position; }
  std::int64_t capture() const { return decoded().capture; }
  bool moving() const { return decoded().moving(); }
  void scans(unsigned n) {
    if (!port_.wait_scans(n)) fail("the module stopped scanning");
  }
  // An edge-triggered command: set until the module has scanned it, then cleared.
  void command(std::uint16_t bit, std::int32_t target = 0, std::int32_t speed = 0,
               std::int16_t accel = 0, std::int16_t decel = 0) {
    const stepmod::plc::Outcome o =
        plc_.pulse(stepmod::plc::m3601::command_words(bit, 0, target, speed, accel, decel), bit);
    if (o.timed_out) fail("the module stopped scanning: " + o.message);
  }
  // Configuration mode with these "used" bits (all inputs active high), then command mode. The
  // home input and the end limits are always used: a 3601 accepts no configuration without the
  // home input (or marker homing) and at least one limit.
  void configure(std::uint16_t used, std::int32_t starting_speed) {
    used |= cfg::kHomeUsed | cfg::kCwLimitUsed | cfg::kCcwLimitUsed;
    stepmod::ImageWords in_config{};
    const stepmod::plc::Outcome o =
        plc_.configure(used | cfg::kStepDirOutput, 0x3F, starting_speed, &in_config);
    if (o.timed_out) fail("the module stopped scanning: " + o.message);
    const auto echo = stepmod::plc::m3601::decode_status(in_config);
    check(echo.has(st::kConfigMode), "configuration mode not entered");
    check(!echo.has(st::kConfigurationError), fmt("configuration refused (status %04x)", echo.msw));
    check(!status(st::kConfigMode), "command mode not entered");
  }
  bool wait(const std::function<bool()>& cond, int timeout_ms) {
    const std::int64_t end = now_ns() + std::int64_t{timeout_ms} * 1'000'000;
    while (now_ns() < end) {
      if (cond()) return true;
      sleep_ms(2);
    }
    return cond();
  }

 private:
  static constexpr stepmod::plc::Sequencing kSeq{
      .hold_scans = 3, .release_scans = 2, .config_scans = 3, .release_stale_bits = false};
  stepmod::ipc::Client c_;
  stepmod::plc::ShmPort port_;
  stepmod::plc::Plc3601 plc_;
};

// The status MSW's set bits by their names in the 3601's table.
std::string status_names(std::uint16_t s) {
  return stepmod::plc::set_bit_names(s, m::kStatusMswBits);
}

constexpr std::uint16_t kMotionBits =
    st::kMovingCw | st::kMovingCcw | st::kAccelerating | st::kDecelerating;

// =================================================================================================
// errors: the gpiod backend's errors, through stepmodd: exit status 1 and a message naming them.

int run_to_exit(const ConfigOptions& o, const std::string& tag, std::string& log) {
  Daemon3601 d(o, tag, false);
  const int rc = d.wait_exit(20'000);
  log = d.log();
  return rc;
}

void expect_start_error(const std::string& what, const ConfigOptions& o,
                        const std::vector<std::string>& must_name) {
  std::string log;
  const int rc = run_to_exit(o, "err", log);
  std::string last = log;
  while (!last.empty() && last.back() == '\n') last.pop_back();
  last = last.substr(last.rfind('\n') == std::string::npos ? 0 : last.rfind('\n') + 1);
  info(fmt("%s: exit %d: %s", what.c_str(), rc, last.c_str()));
  check(rc == 1, fmt("%s: exit status %d, expected 1", what.c_str(), rc));
  for (const std::string& s : must_name) {
    check(log.find(s) != std::string::npos,
          fmt("%s: message does not name '%s': %s", what.c_str(), s.c_str(), last.c_str()));
  }
  struct stat s {};
  check(::stat(("/dev/shm/stepmod." + o.name).c_str(), &s) != 0,
        what + ": the shared-memory image was left behind");
}

std::string case_errors() {
  const std::string chip = env("BOARD_CHIP");
  {
    ConfigOptions o;
    o.chip = "gpiochip7";
    expect_start_error("missing chip", o, {"gpiochip7", "not found"});
  }
  {
    ConfigOptions o;
    o.chip = "/dev/gpiochip7";
    expect_start_error("missing chip (path)", o, {"/dev/gpiochip7"});
  }
  const long lines = std::stol(env("BOARD_LINES"));
  {
    ConfigOptions o;
    o.lines["enc_z"] = lines;  // one past the last line
    expect_start_error("line out of range", o,
                       {chip, "line " + std::to_string(lines), "axis1.enc_z", "out of range"});
  }
  // A line held by another program (consumer "other-app").
  const unsigned home = line("home");
  {
    const HeldInput held(home, "other-app");
    ConfigOptions o;
    expect_start_error("line in use by another program", o,
                       {chip, "line " + std::to_string(home), "axis1.home", "busy", "other-app"});
    // Nothing of ours is left requested: every other line of the config is free.
    for (const char* k : kLineKeys) {
      if (line(k) != home)
        check(line_user(line(k)).empty(),
              fmt("line %u left requested after the failed start", line(k)));
    }
  }
  // A second stepmodd on the lines of a running one (another module name, same board).
  {
    ConfigOptions first;
    Daemon3601 a(first, "first");
    a.wait_ready();
    ConfigOptions second;
    second.name = "vm2";
    expect_start_error(
        "line in use by a running stepmodd", second,
        {chip, "line " + std::to_string(line("step")), "axis1.step", "busy", "stepmod"});
    const int rc = a.terminate();
    check(rc == 0, fmt("first stepmodd exit status %d", rc));
    // And once it has gone, the second one starts.
    Daemon3601 b(second, "second");
    b.wait_ready();
    check(b.terminate() == 0, "second stepmodd did not exit 0");
  }
  return "stepmodd exits 1 naming chip/line for: missing chip, line " + std::to_string(lines) +
         " out of range, line busy (other program, other stepmodd); starts once the lines are free";
}

// =================================================================================================
// move: a relative move; the step/dir outputs sampled through sysfs agree with the VCD and the
// pulse count is exact (sampled rising edges = VCD rising edges = commanded = position).

std::string case_move() {
  constexpr int kSteps = 500, kSpeed = 250, kMarks = 16;
  constexpr std::int64_t kSlack = 20'000;  // write of a line vs its VCD time, ns
  ConfigOptions o;
  o.step_pulse_ns = 1'000'000;  // 1 ms high (the most a config allows) of a 4 ms period
  Daemon3601 d(o, "move");
  d.wait_ready();
  Plc plc(d.name());
  plc.configure(0, kSpeed);  // capture not used: its line carries the time marks
  plc.command(cmd::kPresetPosition, 0);
  SimLine capture(line("capture"));
  // Time marks: capture edges, stamped by the kernel during our sysfs writes, tie the VCD's
  // time to CLOCK_MONOTONIC.
  std::vector<PullMark> marks;
  for (int i = 0; i < kMarks; ++i) {
    marks.push_back(pull_marked(capture, i % 2 == 0));
    sleep_ms(1);
  }
  Sampler sampler(line("step"), line("dir"));
  sleep_ms(20);
  const std::int64_t t_cmd = now_ns();
  // Vs = Vp: a constant rate (the module accepts Vp = Vs; accel is still required).
  plc.command(cmd::kRelativeMove, kSteps, kSpeed, 10, 10);
  check(plc.wait([&] { return plc.status(st::kMoveComplete); }, 20'000),
        fmt("move not complete: status %s, position %lld", status_names(plc.msw()).c_str(),
            static_cast<long long>(plc.position())));
  const std::int64_t t_done = now_ns();
  sleep_ms(20);
  const std::vector<Sample>& samples = sampler.stop();
  const std::int64_t pos = plc.position();
  const std::uint16_t s = plc.msw();
  const Vcd v = d.stop_and_trace();

  const auto rising = v.rising("axis1.step");
  const auto sw = wire(v, "axis1.step");
  const std::size_t sampled = sampled_rising(samples);
  const Alignment a = align_all(v, "axis1.capture", marks);
  const std::size_t observable = observable_pulses(samples, v, a, kSlack);
  const std::int64_t gap = max_sample_gap(samples, t_cmd, t_done);
  std::vector<std::int64_t> highs;
  for (std::size_t i = 0; i + 1 < sw.size(); i += 2) highs.push_back(sw[i + 1].t - sw[i].t);
  std::sort(highs.begin(), highs.end());
  info(fmt("move of %d steps at %d steps/s: position %lld, status %s", kSteps, kSpeed,
           static_cast<long long>(pos), status_names(s).c_str()));
  info(
      fmt("VCD: %zu step pulses (high time min %lld us, median %lld us), %zu dir changes; VCD "
          "origin known within %lld us from %d kernel-stamped marks",
          rising.size(), static_cast<long long>(highs.empty() ? 0 : highs.front() / 1000),
          static_cast<long long>(highs.empty() ? 0 : highs[highs.size() / 2] / 1000),
          wire(v, "axis1.dir").size(), static_cast<long long>((a.hi - a.lo) / 1000), kMarks));
  info(
      fmt("sysfs: %zu samples, longest gap %lld us; %zu rising edges of the step value; %zu "
          "pulses could not be missed by the sampler",
          samples.size(), static_cast<long long>(gap / 1000), sampled, observable));
  const Agreement step_ok = compare(samples, v, a, kSlack, false);
  const Agreement dir_ok = compare(samples, v, a, kSlack, true);
  info(fmt(
      "levels vs VCD: step %zu compared, %zu near an edge, %zu mismatched; dir %zu compared, "
      "%zu mismatched",
      step_ok.compared, step_ok.ambiguous, step_ok.mismatched, dir_ok.compared, dir_ok.mismatched));
  info(lateness_line(d.log()));

  check(pos == kSteps, fmt("position %lld, commanded %d", static_cast<long long>(pos), kSteps));
  check(rising.size() == static_cast<std::size_t>(kSteps),
        fmt("VCD: %zu step pulses, commanded %d", rising.size(), kSteps));
  check(step_ok.mismatched == 0, "step level: " + step_ok.first_mismatch);
  check(dir_ok.mismatched == 0, "dir level: " + dir_ok.first_mismatch);
  // Samples near an edge (within the VCD origin's uncertainty) are not compared. Under TCG on a
  // loaded host the uncertainty grows and about a third of the samples remain; a fifth is still
  // hundreds of levels checked, and far from a comparison that cannot fail.
  check(step_ok.compared > samples.size() / 5,
        fmt("only %zu of %zu samples could be compared", step_ok.compared, samples.size()));
  // Every pulse the sampler could not have missed was seen, and it saw no pulse the VCD lacks.
  check(sampled >= observable && sampled <= rising.size(),
        fmt("sysfs: %zu rising edges; VCD %zu pulses of which %zu could not be missed", sampled,
            rising.size(), observable));
  // Not every pulse can be seen through sysfs here: under qemu's TCG on a loaded host, timer
  // wake-ups of the emulated CPU come up to milliseconds late, and a late leading edge pulls the
  // trailing one in (edges are scheduled at absolute times), leaving pulses of a few us that no
  // sampler catches. The level comparison above covers every sample that can be decided.
  check(step_ok.compared >= 300, fmt("only %zu samples decided against the VCD", step_ok.compared));
  // CW: direction high before the first step, unchanged during the move.
  check(level_at(wire(v, "axis1.dir"), rising.front()) == 1, "dir not high (CW) at the first step");
  for (const VcdChange& c : wire(v, "axis1.dir")) {
    check(c.t < rising.front() || c.t > rising.back(), "dir changed during the move");
  }
  return fmt(
      "%d steps: position %lld = VCD %zu pulses = sysfs %zu rising edges (%zu could not be "
      "missed); %zu step / %zu dir samples match the VCD level, 0 mismatches",
      kSteps, static_cast<long long>(pos), rising.size(), sampled, observable, step_ok.compared,
      dir_ok.compared);
}

// =================================================================================================
// estop: a pull change on the E-stop line stops a running move (3601-IE-01, PI-03, STP-02).

std::string case_estop() {
  ConfigOptions o;
  Daemon3601 d(o, "estop");
  d.wait_ready();
  Plc plc(d.name());
  plc.configure(cfg::kEStopUsed | cfg::kCwLimitUsed | cfg::kCcwLimitUsed, 500);
  plc.command(cmd::kPresetPosition, 0);
  plc.command(cmd::kRelativeMove, -100'000, 2'000, 10, 10);
  check(plc.wait([&] { return plc.moving(); }, 2'000), "the move did not start");
  sleep_ms(400);
  check(plc.moving(), fmt("not moving before the E-stop: %s", status_names(plc.msw()).c_str()));
  SimLine estop(line("estop"));
  const PullMark e = pull_marked(estop, true);
  check(plc.wait([&] { return !plc.moving(); }, 2'000), "the move did not stop on the E-stop");
  const std::int64_t t_seen = now_ns();
  plc.scans(3);
  const std::uint16_t s = plc.msw();
  const std::int64_t pos = plc.position();
  sleep_ms(100);
  const std::int64_t pos_later = plc.position();
  estop.pull(false);
  plc.scans(3);
  const Vcd v = d.stop_and_trace();
  const auto rising = v.rising("axis1.step");
  const auto es = wire(v, "axis1.estop");
  info(fmt("E-stop pulled up: status %s, position %lld, seen by the PLC after %lld ms",
           status_names(s).c_str(), static_cast<long long>(pos),
           static_cast<long long>((t_seen - e.before) / 1'000'000)));
  check(!es.empty() && es.front().level == 1, "VCD: no rising edge on axis1.estop");
  const std::int64_t t_edge = es.front().t;
  const std::int64_t after = static_cast<std::int64_t>(rising.size()) - count_until(rising, t_edge);
  const std::int64_t last_step_after = rising.empty() ? 0 : rising.back() - t_edge;
  info(fmt("VCD: %zu step pulses, %lld after the E-stop edge (last one %lld us after it)",
           rising.size(), static_cast<long long>(after),
           static_cast<long long>(last_step_after / 1000)));
  check((s & st::kInputError) != 0, "Input Error (IE) not set");
  check((s & st::kPositionInvalid) != 0, "Position Invalid (PI) not set");
  check((s & st::kStopped) != 0, "Stopped not set");
  check((s & kMotionBits) == 0, "movement bits still set: " + status_names(s));
  check((s & st::kMoveComplete) == 0, "Move Complete set after an E-stop");
  check(pos < 0 && pos > -100'000, fmt("position %lld", static_cast<long long>(pos)));
  check(pos_later == pos, "the position kept changing after the stop");
  check(static_cast<std::int64_t>(rising.size()) == -pos,
        fmt("VCD: %zu pulses, position %lld", rising.size(), static_cast<long long>(pos)));
  // Immediate, not controlled: a controlled stop from 2,000 to 500 steps/s at 10 steps/ms/s takes
  // (2000^2 - 500^2) / (2 * 10,000) = 187 steps. Counted in steps, not time: the qemu guest runs
  // under TCG on a shared host and stalls for tens of ms now and then (the pulse thread with it).
  constexpr std::int64_t kControlledStopSteps = 187;
  check(after < kControlledStopSteps,
        fmt("%lld steps after the E-stop edge: no faster than a controlled stop (%lld)",
            static_cast<long long>(after), static_cast<long long>(kControlledStopSteps)));
  return fmt(
      "E-stop edge stopped the move: %s; %lld steps = position, last step %lld us after "
      "the kernel's edge time",
      status_names(s).c_str(), static_cast<long long>(-pos),
      static_cast<long long>(last_step_after / 1000));
}

// =================================================================================================
// capture: no encoder, so the capture input latches the motor position at the edge's kernel
// timestamp; the VCD's step count at that time must be the captured value.

std::string case_capture() {
  constexpr int kSteps = 1'500, kSpeed = 500, kCaptures = 6;
  ConfigOptions o;
  o.step_pulse_ns = 200'000;
  for (const char* k : {"enc_a", "enc_b", "enc_z"}) o.lines[k] = -1;  // no encoder wired
  Daemon3601 d(o, "capture");
  d.wait_ready();
  Plc plc(d.name());
  plc.configure(cfg::kCaptureUsed, kSpeed);
  plc.command(cmd::kPresetPosition, 0);
  plc.command(cmd::kRelativeMove, kSteps, kSpeed, 10, 10);
  SimLine cap(line("capture"));
  std::vector<PullMark> marks;
  std::vector<std::int64_t> captured;
  for (int i = 0; i < kCaptures; ++i) {
    sleep_ms(300 + 37 * i);  // not a multiple of the step period
    const std::int64_t before = plc.capture();
    marks.push_back(pull_marked(cap, true));
    // The edge reaches the module as a line event, whenever the guest gets to it (under TCG it
    // stalls for tens of ms): wait for the register to take it — each capture lies 150+ steps
    // after the one before — rather than for a number of scans. Unchanged after 2 s: the check
    // below fails on it.
    plc.wait([&] { return plc.capture() != before; }, 2'000);
    captured.push_back(plc.capture());
    cap.pull(false);
    plc.scans(2);
  }
  check(plc.wait([&] { return plc.status(st::kMoveComplete); }, 15'000), "move not complete");
  const std::int64_t pos = plc.position();
  const Vcd v = d.stop_and_trace();
  const auto rising = v.rising("axis1.step");
  const auto cw = wire(v, "axis1.capture");
  check(cw.size() == 2 * kCaptures,
        fmt("VCD: %zu capture edges, drove %d", cw.size(), 2 * kCaptures));
  check(pos == kSteps && rising.size() == static_cast<std::size_t>(kSteps),
        fmt("position %lld, VCD %zu pulses, commanded %d", static_cast<long long>(pos),
            rising.size(), kSteps));
  // The kernel's stamps: each capture edge lies inside the bracket of its sysfs write (given
  // the origin from the first one, every other one must fall inside its own bracket too).
  const Alignment a = align(v, "axis1.capture", marks[0], 0);
  std::string detail;
  for (int i = 0; i < kCaptures; ++i) {
    const std::int64_t t = cw[2 * i].t;
    check(cw[2 * i].level == 1, "VCD: capture edges not alternating");
    check(t + a.hi >= marks[i].before - 1'000 && t + a.lo <= marks[i].after + 1'000,
          fmt("capture edge %d: VCD time not within its sysfs write (kernel timestamp?)", i));
    const std::int64_t expect = count_until(rising, t);
    // A step within 2 us of the edge could honestly fall either side.
    const std::int64_t near_lo = count_until(rising, t - 2'000);
    const std::int64_t near_hi = count_until(rising, t + 2'000);
    info(fmt("capture %d: VCD t=%lld ns, steps up to then %lld, captured %lld", i,
             static_cast<long long>(t), static_cast<long long>(expect),
             static_cast<long long>(captured[i])));
    check(captured[i] >= near_lo && captured[i] <= near_hi,
          fmt("capture %d: captured %lld, VCD step count at the edge %lld", i,
              static_cast<long long>(captured[i]), static_cast<long long>(expect)));
    detail += (detail.empty() ? "" : " ") + std::to_string(captured[i]);
  }
  return fmt(
      "%d captures during a %d-step move equal the VCD's step count at each kernel-stamped "
      "edge (%s)",
      kCaptures, kSteps, detail.c_str());
}

// =================================================================================================
// burst: hundreds of input edges in quick succession while a move runs.

// The longest run of consecutive input edges (capture and external merged in time order) in
// [from, to] with no step edge between them: the input path running while the pulse thread
// made no step (printed by the burst case).
struct StepGap {
  std::size_t edges = 0;
  std::int64_t ns = 0;
};
StepGap longest_stepless_input_run(const std::vector<std::int64_t>& rising,
                                   const std::vector<VcdChange>& a, const std::vector<VcdChange>& b,
                                   std::int64_t from, std::int64_t to) {
  std::vector<std::int64_t> in;
  for (const auto* w : {&a, &b}) {
    for (const VcdChange& c : *w) {
      if (c.t >= from && c.t <= to) in.push_back(c.t);
    }
  }
  std::sort(in.begin(), in.end());
  StepGap best;
  std::size_t run_start = 0;
  for (std::size_t i = 1; i <= in.size(); ++i) {
    // A step between edge i-1 and edge i (or the end) closes the run.
    if (i == in.size() || count_until(rising, in[i]) != count_until(rising, in[i - 1])) {
      const std::size_t n = i - run_start;
      if (n > best.edges) best = {n, in[i - 1] - in[run_start]};
      run_start = i;
    }
  }
  return best;
}

std::string case_burst() {
  constexpr int kSteps = 1'000, kSpeed = 500, kEdges = 400, kBursts = 3;
  ConfigOptions o;
  o.step_pulse_ns = 200'000;
  Daemon3601 d(o, "burst");
  d.wait_ready();
  Plc plc(d.name());
  plc.configure(cfg::kCaptureUsed, kSpeed);
  plc.command(cmd::kPresetPosition, 0);
  plc.command(cmd::kRelativeMove, kSteps, kSpeed, 10, 10);
  SimLine cap(line("capture"));
  SimLine ext(line("external"));  // wired but not used by the module: traced, otherwise ignored
  std::vector<std::pair<std::int64_t, std::int64_t>> bursts;
  // The burst comes from a process at the lowest priority (nice 19), as an input source that
  // does not compete with the daemon for the one emulated CPU. At nice 0, toggling at ~3,500
  // edges/s on that CPU, a few % of the edges were lost even so (see the README of the cases).
  (void)!nice(19);
  for (int b = 0; b < kBursts; ++b) {
    sleep_ms(250);
    const std::int64_t t0 = now_ns();
    for (int i = 0; i < kEdges; ++i) {
      const SimLine& l = (i / 2) % 2 == 0 ? cap : ext;  // both lines, pairs of edges
      l.pull(i % 2 == 0);
    }
    bursts.emplace_back(t0, now_ns());
  }
  check(plc.wait([&] { return plc.status(st::kMoveComplete); }, 15'000), "move not complete");
  const std::int64_t pos = plc.position();
  const Vcd v = d.stop_and_trace();
  const auto rising = v.rising("axis1.step");
  const auto cw = wire(v, "axis1.capture");
  const auto ew = wire(v, "axis1.external");
  std::string rates;
  for (const auto& [t0, t1] : bursts) {
    rates += fmt(" %lld", static_cast<long long>(kEdges * 1'000'000'000LL /
                                                 std::max<std::int64_t>(std::int64_t{1}, t1 - t0)));
  }
  info(fmt("%d bursts of %d edges (edges/s:%s): VCD capture %zu, external %zu edges", kBursts,
           kEdges, rates.c_str(), cw.size(), ew.size()));
  bool alternating = true;
  for (const auto* w : {&cw, &ew}) {
    for (std::size_t i = 0; i < w->size(); ++i) {
      if ((*w)[i].level != (i % 2 == 0 ? 1 : 0)) alternating = false;
    }
  }
  // How the steps went on during each burst is printed, not judged: it is the emulated CPU's
  // speed, not the kernel path's doing. Each input edge costs the daemon's control and trace
  // threads (SCHED_FIFO) and the kernel's irq thread time on the guest's one CPU, and under TCG
  // on a loaded host that left the planner (a normal thread) no time to refill the pulse
  // thread's ring: 48 of the 214 steps due in a burst came in it, another time none in 635 ms
  // while 400 input edges came (the move then ends later, or a late-edge fault cuts it and the
  // case runs again). What the kernel path must get right is judged below: every input edge in
  // the VCD in order, none lost, and the exact pulse count.
  const std::size_t expect_each = static_cast<std::size_t>(kBursts * kEdges / 2);
  std::string in_window;
  for (int b = 0; b < kBursts && cw.size() == expect_each && ew.size() == expect_each; ++b) {
    const std::size_t first = static_cast<std::size_t>(b * kEdges / 2);
    const std::int64_t from = std::min(cw[first].t, ew[first].t);
    const std::int64_t to = std::max(cw[first + kEdges / 2 - 1].t, ew[first + kEdges / 2 - 1].t);
    const std::int64_t steps = count_until(rising, to) - count_until(rising, from);
    const std::int64_t expect = (to - from) * kSpeed / 1'000'000'000;
    const StepGap g = longest_stepless_input_run(rising, cw, ew, from, to);
    in_window += fmt(" %lld/%lld (at most %zu input edges in %lld ms without a step)",
                     static_cast<long long>(steps), static_cast<long long>(expect), g.edges,
                     static_cast<long long>(g.ns / 1'000'000));
  }
  info("steps during each burst / expected at the programmed rate:" + in_window);
  std::int64_t worst = 0;
  for (std::size_t i = 1; i < rising.size(); ++i) {
    worst = std::max<std::int64_t>(
        worst, std::abs(rising[i] - rising[i - 1] - std::int64_t{1'000'000'000} / kSpeed));
  }
  const long long late = lateness_max_ns(d.log());
  info(fmt("steps: %zu, position %lld; worst step-period error %lld us; %s", rising.size(),
           static_cast<long long>(pos), static_cast<long long>(worst / 1000),
           lateness_line(d.log()).c_str()));
  check(cw.size() == expect_each && ew.size() == expect_each && !cw.empty(),
        fmt("edges lost: VCD has %zu capture and %zu external edges, drove %zu each", cw.size(),
            ew.size(), expect_each));
  check(alternating, "VCD: input edges not alternating (one lost or reordered)");
  check(d.log().find("input events were lost") == std::string::npos,
        "stepmodd reports lost input events");
  check(pos == kSteps && rising.size() == static_cast<std::size_t>(kSteps),
        fmt("position %lld, VCD %zu pulses, commanded %d", static_cast<long long>(pos),
            rising.size(), kSteps));
  return fmt(
      "%zu input edges in %d bursts all in the VCD, %d pulses exact, worst step-period "
      "error %lld us, lateness max %lld us",
      cw.size() + ew.size(), kBursts, kSteps, static_cast<long long>(worst / 1000), late / 1000);
}

// =================================================================================================
// sigterm: outputs to their idle level, then the lines are released.

std::string case_sigterm() {
  const unsigned step_off = line("step"), dir_off = line("dir");
  // Pulled up (as by a drive's input pull-up): a released line reads 1, a line held at its idle
  // level reads 0, so the sampled sequence tells idle and released apart.
  SimLine(step_off).pull(true);
  SimLine(dir_off).pull(true);
  ConfigOptions o;
  o.step_pulse_ns = 200'000;
  std::vector<Sample> samples;
  std::int64_t t_term = 0, t_exit = 0;
  bool dir_high_before = false;  // moving CW: dir high, read through sysfs
  {
    Daemon3601 d(o, "sigterm");
    d.wait_ready();
    Plc plc(d.name());
    plc.configure(0, 500);
    plc.command(cmd::kRelativeMove, 100'000, 1'000, 10, 10);
    sleep_ms(300);
    check(plc.moving(), "not moving");
    // Read here, not from the sampler's first 50 ms: under load the pulse thread spinning
    // through its late edges kept the sampler off the guest's CPU until after the SIGTERM.
    dir_high_before = SimLine(dir_off).value() == 1;
    Sampler sampler(step_off, dir_off);
    sleep_ms(50);
    t_term = now_ns();
    const int rc = d.terminate();
    t_exit = d.exit_time();
    sleep_ms(20);
    samples = sampler.stop();
    d.print_log();
    check(rc == 0, fmt("stepmodd exit status %d after SIGTERM", rc));
    const Vcd v = d.trace();
    check(v.final_level("axis1.step") == 0 && v.final_level("axis1.dir") == 0,
          "VCD: outputs not idle (0) at the end");
    check(v.rising("axis1.step").size() > 50, "the move had not really run");
    struct stat s {};
    check(::stat(("/dev/shm/stepmod." + o.name).c_str(), &s) != 0,
          "shared-memory image left behind");
  }
  // Between SIGTERM and the exit: both idle (0) at some sample. After the exit: the pull (1) — the
  // lines were released.
  bool idle_seen = false;
  std::int64_t idle_at = 0;
  for (const Sample& s : samples) {
    if (s.t0 >= t_term && s.step == 0 && s.dir == 0 && !idle_seen) {
      idle_seen = true;
      idle_at = s.t0;
    }
  }
  const int step_now = SimLine(step_off).value(), dir_now = SimLine(dir_off).value();
  const std::string users = line_user(step_off) + line_user(dir_off) + line_user(line("estop")) +
                            line_user(line("capture"));
  info(
      fmt("SIGTERM -> exit %lld ms; idle (step 0, dir 0) sampled %s; after exit step=%d dir=%d "
          "(pull-up)",
          static_cast<long long>((t_exit - t_term) / 1'000'000),
          idle_seen
              ? fmt("%lld ms after SIGTERM", static_cast<long long>((idle_at - t_term) / 1'000'000))
                    .c_str()
              : "never",
          step_now, dir_now));
  check(dir_high_before, "dir was not high (CW) during the move");
  check(idle_seen, "the outputs were never seen at their idle level (0) between SIGTERM and exit");
  check(step_now == 1 && dir_now == 1,
        "outputs not back at their pull (1) after exit: not released");
  check(users.empty(), "lines still requested after exit: consumer " + users);
  // Pulled down again: released lines follow, and the same lines can be had again.
  SimLine(step_off).pull(false);
  SimLine(dir_off).pull(false);
  check(SimLine(step_off).value() == 0 && SimLine(dir_off).value() == 0,
        "released lines do not follow the pull");
  Daemon3601 again(o, "sigterm2");
  again.wait_ready();
  check(line_user(step_off) == "stepmod", "second stepmodd: step line not requested by 'stepmod'");
  check(again.terminate() == 0, "second stepmodd did not exit 0");
  check(SimLine(step_off).value() == 0 && SimLine(dir_off).value() == 0,
        "outputs not 0 after the second exit");
  return "SIGTERM mid-move: exit 0, outputs seen at idle (0) then released (follow the pull), "
         "lines "
         "free (line info), a second stepmodd gets them";
}

// =================================================================================================
// homing: Find Home with the home switch and the limits driven through sysfs by a machine model
// that follows the real outputs: it samples step/dir through sim_gpioN/value (1 ms pulses at a
// few hundred steps/s cannot be missed), counts the steps, and pulls the home and limit inputs up
// while the machine position is on the switch (manuals ch. 4: the home-input sequences).

class Machine {
 public:
  static constexpr std::int64_t kHomeFrom = 400, kHomeTo = 460, kCwLimitAt = 800,
                                kCcwLimitAt = -600;
  Machine()
      : step_(line("step")),
        dir_(line("dir")),
        home_(line("home")),
        cw_(line("cw_limit")),
        ccw_(line("ccw_limit")) {
    th_ = std::thread([this] { run(); });
  }
  ~Machine() {
    stop_ = true;
    th_.join();
  }
  Machine(const Machine&) = delete;
  Machine& operator=(const Machine&) = delete;
  std::int64_t position() const { return pos_.load(); }
  std::int64_t max_gap_ns() const { return max_gap_.load(); }
  unsigned home_edges() const { return home_edges_.load(); }

 private:
  void run() {
    // The machine is physics: it must see every pulse, so it looks above the pulse thread's
    // priority (80), and sleeps 100 us between looks. It used to spin at normal priority: on the
    // guest's one CPU it halved the planner's time (the pulse thread then ran out of ring, late-
    // edge faults), and the pulse thread, which spins through fast edges at SCHED_FIFO, kept it
    // off the CPU for 17 ms while pulses went out (it lost steps and never reached the CW
    // limit). Pulses of 1 ms at <= 300 steps/s leave >= 2.3 ms low: a look every ~0.1-1 ms sees
    // each; a stall of the whole guest stops the pulses as well.
    sched_param sp{};
    sp.sched_priority = 90;
    pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
    const timespec nap{0, 100'000};
    int last_step = step_.value();
    bool home = false, cw = false, ccw = false;
    std::int64_t last_t = now_ns();
    while (!stop_) {
      const std::int64_t t = now_ns();
      const int s = step_.value();
      const int d = dir_.value();
      if (s == 1 && last_step == 0) pos_ += d == 1 ? 1 : -1;  // dir high = CW
      last_step = s;
      const std::int64_t p = pos_.load();
      const bool h = p >= kHomeFrom && p <= kHomeTo, c = p >= kCwLimitAt, cc = p <= kCcwLimitAt;
      if (h != home) {
        home_.pull(h);
        home = h;
        ++home_edges_;
      }
      if (c != cw) cw_.pull(cw = c);
      if (cc != ccw) ccw_.pull(ccw = cc);
      if (s == 1 || t - last_t < 100'000'000) max_gap_ = std::max(max_gap_.load(), now_ns() - t);
      last_t = t;
      clock_nanosleep(CLOCK_MONOTONIC, 0, &nap, nullptr);
    }
  }
  SimLine step_, dir_, home_, cw_, ccw_;
  std::atomic<std::int64_t> pos_{0};
  std::atomic<std::int64_t> max_gap_{0};
  std::atomic<unsigned> home_edges_{0};
  std::atomic<bool> stop_{false};
  std::thread th_;
};

std::string case_homing() {
  constexpr int kVs = 100, kVp = 300;
  ConfigOptions o;
  o.step_pulse_ns = 1'000'000;
  Daemon3601 d(o, "homing");
  d.wait_ready();
  Plc plc(d.name());
  plc.configure(0, kVs);
  plc.command(cmd::kPresetPosition, 0);
  Machine machine;

  // H-A: Find Home CW from 0, the home switch at 400..460: search at Vp, stop past the switch,
  // 2 s, back CCW off it, 2 s, creep CW at Vs onto its edge at 400.
  const std::int64_t t0 = now_ns();
  plc.command(cmd::kFindHomeCw, 0, kVp, 10, 10);
  if (plc.status(st::kCommandError) && !plc.moving()) {
    const std::uint16_t s = plc.msw();
    d.terminate();
    fail("Find Home CW refused: " + status_names(s));
  }
  check(plc.wait([&] { return plc.status(st::kMovingCw); }, 2'000),
        "Find Home CW did not start moving CW: " + status_names(plc.msw()));
  check(plc.wait(
            [&] {
              return plc.status(st::kAtHome) || plc.status(st::kHomeInvalid) ||
                     plc.status(st::kInputError);
            },
            25'000),
        fmt("Find Home CW did not finish: %s, machine at %lld", status_names(plc.msw()).c_str(),
            static_cast<long long>(machine.position())));
  check(plc.wait([&] { return !plc.moving(); }, 2'000), "still moving after At Home");
  plc.scans(3);
  const std::uint16_t s1 = plc.msw();
  const std::int64_t pos1 = plc.position(), m1 = machine.position();
  info(fmt(
      "Find Home CW (H-A): %s after %.1f s, position %lld, machine at %lld (switch %lld..%lld), "
      "%u home edges",
      status_names(s1).c_str(), (now_ns() - t0) * 1e-9, static_cast<long long>(pos1),
      static_cast<long long>(m1), static_cast<long long>(Machine::kHomeFrom),
      static_cast<long long>(Machine::kHomeTo), machine.home_edges()));
  check((s1 & st::kAtHome) != 0, "At Home not set: " + status_names(s1));
  check((s1 & (st::kHomeInvalid | st::kInputError | st::kCommandError | st::kPositionInvalid)) == 0,
        "error bits after homing: " + status_names(s1));
  check(pos1 == 0, fmt("position after homing %lld, expected 0", static_cast<long long>(pos1)));
  check(m1 >= Machine::kHomeFrom && m1 <= Machine::kHomeFrom + 1,
        fmt("homed at machine position %lld, the switch's CW-side edge is %lld",
            static_cast<long long>(m1), static_cast<long long>(Machine::kHomeFrom)));

  // H-C: past the switch (machine 560), Find Home CW meets the CW limit at 800: immediate stop,
  // 2 s, CCW across the whole switch, 2 s, creep CW onto it.
  plc.command(cmd::kRelativeMove, 160, kVp, 10, 10);
  check(plc.wait([&] { return plc.status(st::kMoveComplete); }, 10'000),
        "move past home not complete");
  const std::int64_t t1 = now_ns();
  plc.command(cmd::kFindHomeCw, 0, kVp, 10, 10);
  check(plc.wait(
            [&] {
              return plc.status(st::kAtHome) || plc.status(st::kHomeInvalid) ||
                     plc.status(st::kInputError);
            },
            30'000),
        fmt("Find Home CW via the CW limit did not finish: %s, machine at %lld",
            status_names(plc.msw()).c_str(), static_cast<long long>(machine.position())));
  check(plc.wait([&] { return !plc.moving(); }, 2'000), "still moving after At Home");
  plc.scans(3);
  const std::uint16_t s2 = plc.msw();
  const std::int64_t pos2 = plc.position(), m2 = machine.position();
  const int rc = d.terminate();
  d.print_log();
  info(
      fmt("Find Home CW via the CW limit (H-C): %s after %.1f s, position %lld, machine at %lld; "
          "sampling gap max %lld us",
          status_names(s2).c_str(), (now_ns() - t1) * 1e-9, static_cast<long long>(pos2),
          static_cast<long long>(m2), static_cast<long long>(machine.max_gap_ns() / 1000)));
  check(rc == 0, fmt("stepmodd exit status %d", rc));
  // The machine model counts pulses through sysfs. After a guest stall the pulse thread writes
  // its late steps back to back, pulses of a few us that no look every 100 us can see: then the
  // model lost steps and its switches were not where the axis was. A check failing after that
  // is the emulated CPU's speed, as after a late-edge fault: the case runs again (run_case).
  const Vcd v = d.trace();
  std::int64_t net = 0;
  const auto dirw = wire(v, "axis1.dir");
  for (const std::int64_t t : v.rising("axis1.step")) net += level_at(dirw, t) ? 1 : -1;
  info(fmt("VCD net steps %lld, machine model %lld", static_cast<long long>(net),
           static_cast<long long>(m2)));
  if (net != m2 && guest_too_slow().empty()) {
    guest_too_slow() = fmt("the machine model saw %lld of the VCD's %lld net steps (%s)",
                           static_cast<long long>(m2), static_cast<long long>(net),
                           lateness_line(d.log()).c_str());
  }
  check((s2 & st::kAtHome) != 0, "At Home not set: " + status_names(s2));
  check((s2 & (st::kHomeInvalid | st::kInputError | st::kCommandError)) == 0,
        "error bits after homing: " + status_names(s2));
  check(pos2 == 0, fmt("position after homing %lld, expected 0", static_cast<long long>(pos2)));
  check(m2 >= Machine::kHomeFrom && m2 <= Machine::kHomeFrom + 1,
        fmt("homed at machine position %lld, expected %lld", static_cast<long long>(m2),
            static_cast<long long>(Machine::kHomeFrom)));
  const auto cwl = wire(v, "axis1.cw_limit");
  check(!cwl.empty(), "VCD: the CW limit never changed");
  return fmt(
      "Find Home CW by the home switch (H-A) and via the CW limit (H-C): At Home, position "
      "0, machine on the switch edge (%lld)",
      static_cast<long long>(m2));
}

}  // namespace

// =================================================================================================
// options: the line options of [[axis]] as the kernel applied them (its line info, what gpioinfo
// prints) and as gpio-sim shows them (sim_gpioN/pull and value).

#ifdef STEPMOD_VM_GPIOD_V2
constexpr bool kGpiodV2 = true;
#else
constexpr bool kGpiodV2 = false;
#endif

std::string sim_attr(unsigned offset, const char* attr) {
  std::string s =
      read_text(env("GPIO_SIM_DIR") + "/sim_gpio" + std::to_string(offset) + "/" + attr);
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

ConfigOptions options_config(bool debounce) {
  ConfigOptions o;
  o.line_text["home"] = fmt("{ offset = %u, bias = \"pull-up\"%s }", line("home"),
                            debounce ? ", debounce_us = 2000" : "");
  o.line_text["cw_limit"] =
      fmt("{ offset = %u, bias = \"pull-down\", active_low = true }", line("cw_limit"));
  o.line_text["capture"] = fmt("{ offset = %u, bias = \"disabled\" }", line("capture"));
  o.line_text["step"] = fmt("{ offset = %u, active_low = true }", line("step"));
  o.line_text["dir"] = fmt("{ offset = %u, drive = \"open-drain\" }", line("dir"));
  return o;
}

void expect_flags(const char* key, std::uint64_t want, std::uint64_t must_not = 0) {
  const KernelLine k = kernel_line(line(key));
  info(fmt("%s (line %u): consumer '%s', flags 0x%llx, debounce %u us", key, line(key),
           k.consumer.c_str(), static_cast<unsigned long long>(k.flags), k.debounce_us));
  check(k.used && k.consumer == "stepmod", fmt("%s: not held by stepmod", key));
  check((k.flags & want) == want,
        fmt("%s: flags 0x%llx lack 0x%llx", key, static_cast<unsigned long long>(k.flags),
            static_cast<unsigned long long>(want)));
  check((k.flags & must_not) == 0,
        fmt("%s: flags 0x%llx have 0x%llx", key, static_cast<unsigned long long>(k.flags),
            static_cast<unsigned long long>(must_not)));
}

// gpioinfo's row of a line ("" when gpioinfo is not in the VM): libgpiod's own tool (1.6:
// `line  13: "GPIO13" "stepmod" input active-high [used pull-up]`; 2: `line 13: "GPIO13" input
// bias=pull-up debounce-period=2ms consumer="stepmod"`), the view a user has of the lines.
std::string gpioinfo_row(unsigned offset) {
  if (::access("/vm/bin/gpioinfo", X_OK) != 0) return "";
  // No argument (every chip; the VM has one): 1.6 takes a chip there, 2 a line name (-c chip).
  std::FILE* p = ::popen("gpioinfo 2>&1", "r");
  if (p == nullptr) fail("cannot run gpioinfo");
  std::string row;
  char buf[512];
  const std::string key = "line " + std::to_string(offset) + ":";
  while (std::fgets(buf, sizeof buf, p) != nullptr) {
    std::string l(buf);
    // 1.6 pads the offset ("line  13:"): compare with the spaces squeezed.
    std::string squeezed;
    for (char c : l) {
      if (c == '\t') c = ' ';
      if (c != ' ' || squeezed.empty() || squeezed.back() != ' ') squeezed.push_back(c);
    }
    if (squeezed.find(key) != std::string::npos) row = squeezed;
  }
  ::pclose(p);
  while (!row.empty() && row.back() == '\n') row.pop_back();
  return row;
}

// With gpioinfo in the VM: its rows name the options too. Returns what was checked.
std::string check_gpioinfo() {
  const std::string home = gpioinfo_row(line("home"));
  if (home.empty()) return "; gpioinfo not in the VM";
  const std::string cw = gpioinfo_row(line("cw_limit"));
  const std::string dir = gpioinfo_row(line("dir"));
  info("gpioinfo: home:" + home);
  info("gpioinfo: cw_limit:" + cw);
  info("gpioinfo: dir:" + dir);
  check(home.find("pull-up") != std::string::npos, "gpioinfo: home row lacks pull-up: " + home);
  check(cw.find("pull-down") != std::string::npos && cw.find("active-low") != std::string::npos,
        "gpioinfo: cw_limit row lacks pull-down/active-low: " + cw);
  check(dir.find("open-drain") != std::string::npos, "gpioinfo: dir row lacks open-drain: " + dir);
  if (kGpiodV2) {
    check(home.find("debounce-period=2ms") != std::string::npos,
          "gpioinfo: home row lacks debounce-period=2ms: " + home);
  }
  return "; gpioinfo shows them";
}

std::string case_options() {
  std::string refused;
  if (!kGpiodV2) {
    // libgpiod 1.6 (v1 uAPI): no debounce. Refused as a configuration error (exit 2), naming
    // the key.
    std::string log;
    const int rc = run_to_exit(options_config(true), "opts-debounce", log);
    check(rc == 2 && log.find("debounce_us") != std::string::npos,
          fmt("debounce_us on a libgpiod 1.6 build: exit %d, log: %s", rc, log.c_str()));
    refused = "; debounce_us refused by this libgpiod 1.6 build (exit 2 naming it)";
  }
  Daemon3601 d(options_config(kGpiodV2), "opts", false);
  d.wait_ready();
  expect_flags("home", GPIO_V2_LINE_FLAG_INPUT | GPIO_V2_LINE_FLAG_BIAS_PULL_UP,
               GPIO_V2_LINE_FLAG_ACTIVE_LOW);
  expect_flags("cw_limit", GPIO_V2_LINE_FLAG_INPUT | GPIO_V2_LINE_FLAG_BIAS_PULL_DOWN |
                               GPIO_V2_LINE_FLAG_ACTIVE_LOW);
  expect_flags("capture", GPIO_V2_LINE_FLAG_INPUT | GPIO_V2_LINE_FLAG_BIAS_DISABLED);
  expect_flags("step", GPIO_V2_LINE_FLAG_OUTPUT | GPIO_V2_LINE_FLAG_ACTIVE_LOW);
  expect_flags("dir", GPIO_V2_LINE_FLAG_OUTPUT | GPIO_V2_LINE_FLAG_OPEN_DRAIN,
               GPIO_V2_LINE_FLAG_ACTIVE_LOW);
  expect_flags("ccw_limit", GPIO_V2_LINE_FLAG_INPUT,
               GPIO_V2_LINE_FLAG_BIAS_PULL_UP | GPIO_V2_LINE_FLAG_BIAS_PULL_DOWN |
                   GPIO_V2_LINE_FLAG_BIAS_DISABLED);
  const std::uint32_t debounce = kernel_line(line("home")).debounce_us;
  check(debounce == (kGpiodV2 ? 2000u : 0u), fmt("home: kernel debounce %u us", debounce));
  // gpio-sim applies the bias as the pad's pull: the board reset pulled every line down.
  check(sim_attr(line("home"), "pull") == "pull-up",
        "home: sim_gpio pull is '" + sim_attr(line("home"), "pull") + "', not pull-up");
  check(SimLine(line("home")).value() == 1, "home: an undriven input with a pull-up is not high");
  check(sim_attr(line("cw_limit"), "pull") == "pull-down", "cw_limit: pull not pull-down");
  // An idle active-low step output is a high wire; the open-drain dir output idles low.
  check(SimLine(line("step")).value() == 1, "step (active low): idle wire not high");
  check(SimLine(line("dir")).value() == 0, "dir (open drain): idle wire not low");
  const std::string tool = check_gpioinfo();
  const int rc = d.terminate();
  d.print_log();
  check(rc == 0, fmt("stepmodd exit status %d", rc));
  check(line_user(line("home")).empty(), "home still held after exit");
  return std::string("kernel line info: home pull-up") + (kGpiodV2 ? " debounce 2000 us" : "") +
         ", cw_limit pull-down active-low, capture bias disabled, step active-low (idle wire "
         "high), dir open-drain; sim_gpio pull-up/pull-down as configured" +
         tool + refused;
}

// =================================================================================================
// lost: edges the kernel dropped. The daemon is stopped (SIGSTOP) while 41 edges are driven on
// its capture line: the kernel keeps 16 per line request (v2: the newest, the sequence numbers
// count the rest; v1: the oldest, silently). After SIGCONT one more edge: with libgpiod 2 the
// gap in line_seqno is the exact loss; with 1.6 the repeated direction betrays one.

long long lost_in_all(const std::string& log) {
  const auto p = log.find(" input events were lost in all");
  if (p == std::string::npos) return 0;
  auto b = log.rfind(' ', p - 1);
  return std::atoll(log.c_str() + (b == std::string::npos ? 0 : b + 1));
}

std::string case_lost() {
  ConfigOptions o;
  Daemon3601 d(o, "lost", false);
  d.wait_ready();
  stepmod::ipc::Client client(o.name);
  SimLine cap(line("capture"));
  for (int i = 0; i < 4; ++i) {  // read as they come: nothing lost
    cap.pull(i % 2 == 0);
    sleep_ms(30);
  }
  check((client.read_health().flags & STEPMOD_HEALTH_INPUT_LOST) == 0,
        "health bit 5 set before any loss");
  d.signal(SIGSTOP);
  sleep_ms(50);
  constexpr int kEdges = 41;
  for (int i = 0; i < kEdges; ++i) cap.pull(i % 2 == 0);  // ends high
  d.signal(SIGCONT);
  sleep_ms(200);
  cap.pull(false);
  bool seen = false;
  for (const std::int64_t end = now_ns() + 5'000'000'000; !seen && now_ns() < end; sleep_ms(10)) {
    seen = (client.read_health().flags & STEPMOD_HEALTH_INPUT_LOST) != 0;
  }
  const int rc = d.terminate();
  d.print_log();
  check(seen, "health bit 5 (input events lost) not set after the kernel dropped edges");
  check(rc == 0, fmt("stepmodd exit status %d", rc));
  const std::string log = d.log();
  check(log.find("input event(s) lost") != std::string::npos, "no 'input event(s) lost' log line");
  const long long lost = lost_in_all(log);
  // v2: 41 - 16 kept = 25 (fewer if the reader took some before it stopped: one read of up to
  // 16 events may have been in flight); v1: one repeated direction.
  if (kGpiodV2) {
    check(lost >= kEdges - 32 && lost <= kEdges - 16,
          fmt("libgpiod 2: %lld lost edges counted, expected %d (at least %d)", lost, kEdges - 16,
              kEdges - 32));
  } else {
    check(lost >= 1, fmt("libgpiod 1.6: %lld lost edges counted, expected >= 1", lost));
  }
  return fmt("%d edges with the reader stopped: %lld counted lost (%s), health bit 5 set, logged",
             kEdges, lost,
             kGpiodV2 ? "libgpiod 2 sequence numbers" : "libgpiod 1.6 direction repeat");
}

int main(int argc, char** argv) {
  return run_case(argc, argv, "daemon_vm_test",
                  {{"errors", case_errors},
                   {"move", case_move},
                   {"estop", case_estop},
                   {"capture", case_capture},
                   {"burst", case_burst},
                   {"sigterm", case_sigterm},
                   {"homing", case_homing},
                   {"options", case_options},
                   {"lost", case_lost}});
}
