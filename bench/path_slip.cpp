// Benchmark 12, the 3602's paths (issue 18): a line, a full circle and a held-and-resumed line
// drawn by a real stepmodd as a 3602 with the product's default configuration (no guard key
// written), commanded through shared memory by the PLC-side library; scripts/bench runs it beside
// `stress-ng --cpu 2`. From the VCD: the path rebuilt at every step edge (both step/direction
// trains merged in time order) against the ideal path — for a line the minor axis' offset from
// the line at each step point (the manual's +/- 1 step), for an arc the radial distance — and
// each axis' step train against the planner's plan of the same path (bench/path_plan.hpp):
// compressed intervals, pauses beyond the guard's rule without a fault, the end in time, exact
// counts and end points.
#include "bench/path_slip.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "bench/daemon_log.hpp"
#include "bench/path_plan.hpp"
#include "bench/slip_judge.hpp"
#include "ipc/client.hpp"
#include "module_types/m3602/rules_3602.hpp"
#include "module_types/m3602/words_3602.hpp"
#include "module_types/m3602/plc_interp_3602.hpp"
#include "module_types/m3602/plc_3602.hpp"
#include "plc/shm_port.hpp"
#include "tests/planner/path_ideal.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/sim_config.hpp"
#include "tests/support/vcd_path.hpp"
#include "tests/support/vcd_reader.hpp"

namespace stepmod::bench {
namespace {

using Method = plc::PathMove3602::Method;
using Point = planner::test::PathPoint;  // a step of either axis and the (x, y) after it
using std::chrono::milliseconds;

constexpr std::int32_t kVs = 1'000;           // axis 1's starting speed: the path's Vs
constexpr std::int32_t kRate = 20;            // steps/ms/s: 0.5 s to 10,000 steps/s
constexpr milliseconds kRest{400};            // between moves (and in the hold)
constexpr milliseconds kHoldAfter{700};       // the held line's Hold after its start
constexpr std::int32_t kResumeSpeed = 8'000;  // the held line's Resume profile
constexpr double kOff = 1.0 + 1e-9;           // farther than one step from the ideal path

// A 3602 on the simulated machine with the product's guard: no late_limit_us, no
// lag_limit_steps.
std::string config_3602() {
  std::string config = testing::sim_module_tables("3602", "", "");
  for (unsigned a = 0; a < 2; ++a) {
    config += testing::sim_axis(testing::numbered_lines(10 * a + 1, {"step", "dir", "gpo", "home"}),
                                "cw_limit_at = 100000000\nccw_limit_at = -100000000\n", "");
  }
  return config;
}

struct PathCase {
  const char* name;
  plc::PathMove3602 move;
  bool held = false;
};

// What the wire showed of one case: monotonic times and the faults counted meanwhile.
struct Run {
  Nanos begin = 0, resume = 0, end = 0;  // resume: the held case's Resume write (else end)
  bool started = false, faulted = false;
  // The held case was resumed (else it faulted before: judged as the plain line it was then).
  bool resumed = false;
};

planner::Ramp ramp(std::int32_t rate) {
  return {static_cast<double>(rate) * static_cast<double>(module::m3602::kRules3602.accel_word_unit),
          planner::AccelShape::kConstant};
}

planner::PathSpec ideal(const plc::PathMove3602& m) {
  planner::PathSpec p;
  p.end_x = m.end_x;
  p.end_y = m.end_y;
  if (m.method != Method::kLinear) {  // the full circles here: centre method, end = start
    p.shape = planner::PathShape::kArc;
    p.centre_x = m.point_x;
    p.centre_y = m.point_y;
    p.sweep = (m.method == Method::kCentreCcw ? 2.0 : -2.0) * M_PI;
  }
  p.vs = kVs;
  p.vp = m.profile.speed;
  p.accel = ramp(m.profile.accel);
  p.decel = ramp(m.profile.decel);
  return p;
}

// A PLC's answer to a late-edge fault before the next move: Reset Errors on both axes (the
// positions stay invalid; the moves here are relative).
void reset_after_fault(plc::Plc3602& axes) {
  for (unsigned a = 0; a < 2; ++a) axes.reset_errors(a);
}

Run drive(plc::Interp3602& interp, plc::Plc3602& axes, ipc::Client& client, const PathCase& c) {
  Run r;
  const std::uint32_t before = client.read_health().late_faults;
  const auto faulted = [&] { return client.read_health().late_faults > before; };
  r.begin = monotonic_now();
  const plc::Outcome started = interp.move(c.move);
  r.started = started.ok;
  if (!r.started) std::printf("  %s refused: %s\n", c.name, started.message.c_str());
  if (r.started && c.held) {
    std::this_thread::sleep_for(kHoldAfter);
    if (!faulted()) interp.hold();  // (a Hold of a stopped axis is a Command Error)
    interp.wait_done(std::chrono::seconds(20));
    std::this_thread::sleep_for(kRest);
    r.resume = monotonic_now();
    plc::Profile p = c.move.profile;
    p.speed = kResumeSpeed;
    r.resumed = !faulted();
    if (r.resumed) interp.resume(p);
  }
  if (r.started) interp.wait_done(std::chrono::seconds(60));
  r.end = monotonic_now();
  if (!c.held) r.resume = r.end;
  r.faulted = faulted();
  std::this_thread::sleep_for(kRest);
  if (r.faulted) reset_after_fault(axes);
  return r;
}

// Distance of a step point from the ideal path, as the criterion measures it.
double off_path(const planner::PathSpec& p, double x, double y) {
  if (p.shape == planner::PathShape::kLine) {
    const auto ex = static_cast<double>(p.end_x), ey = static_cast<double>(p.end_y);
    return std::abs(ex) >= std::abs(ey) ? std::abs(y - x * ey / ex) : std::abs(x - y * ex / ey);
  }
  return std::abs(std::hypot(x - p.centre_x, y - p.centre_y) - std::hypot(p.centre_x, p.centre_y));
}

// Each axis' step times of the points in [from, to).
AxisSteps axis_times(const std::vector<Point>& pts, Nanos from, Nanos to) {
  AxisSteps s;
  for (const Point& p : pts) {
    if (p.t >= from && p.t < to) s[p.axis].push_back(p.t);
  }
  return s;
}

struct Totals {
  std::size_t compressed = 0, unfaulted = 0, off = 0, late_ends = 0, inexact = 0, faults = 0;
  double worst_off = 0;
};

// Judges one part (all of a case, or the held line's part before / after the hold).
void judge_part(const AxisSteps& wire, const AxisSteps& plan, bool faulted, Totals& t,
                SlipVerdict& v) {
  for (unsigned a = 0; a < 2; ++a) {
    const SlipVerdict w = judge_move(wire[a], plan[a], kVs, faulted);
    v.compressed += w.compressed;
    v.unfaulted += w.unfaulted;
    v.worst_pause = std::max(v.worst_pause, w.worst_pause);
    v.in_time = v.in_time && w.in_time;
    t.compressed += w.compressed;
    t.unfaulted += w.unfaulted;
  }
}

void report(const PathCase& c, const Run& r, const std::vector<Point>& all, Nanos origin,
            Totals& t) {
  const planner::PathSpec spec = ideal(c.move);
  const Nanos from = r.begin - origin, mid = r.resume - origin, to = r.end - origin;
  std::vector<Point> pts;
  std::int64_t x0 = 0, y0 = 0;
  for (const Point& p : all) {
    if (p.t < from) x0 = p.x, y0 = p.y;
    if (p.t >= from && p.t < to) pts.push_back({p.t, p.axis, p.x - x0, p.y - y0});
  }
  std::size_t off = 0;
  double worst = 0;
  for (const Point& p : pts) {
    const double d = off_path(spec, static_cast<double>(p.x), static_cast<double>(p.y));
    off += d > kOff ? 1 : 0;
    worst = std::max(worst, d);
  }
  SlipVerdict v;
  std::size_t planned = 0;
  if (c.held && r.resumed) {
    const AxisSteps before = axis_times(pts, from, mid), after = axis_times(pts, mid, to);
    const HeldPlan plan = plan_held_path(spec, spec.decel, {kResumeSpeed, spec.accel, spec.decel},
                                         before[0].size() + before[1].size());
    judge_part(before, plan.held, r.faulted, t, v);
    judge_part(after, plan.resumed, r.faulted, t, v);
    for (unsigned a = 0; a < 2; ++a) planned += plan.held[a].size() + plan.resumed[a].size();
  } else {
    const AxisSteps plan = plan_path(spec);
    judge_part(axis_times(pts, from, to), plan, r.faulted, t, v);
    planned = plan[0].size() + plan[1].size();
  }
  const bool at_end = !pts.empty() && pts.back().x == spec.end_x && pts.back().y == spec.end_y;
  const bool exact = r.faulted ? pts.size() < planned : (pts.size() == planned && at_end);
  t.off += off;
  t.worst_off = std::max(t.worst_off, worst);
  t.late_ends += (!r.faulted && !v.in_time) ? 1 : 0;
  t.inexact += exact ? 0 : 1;
  t.faults += r.faulted ? 1 : 0;
  std::printf(
      "slip 3602 %-11s: %zu of %zu planned steps, %s, compressed %zu, unfaulted pauses %zu, "
      "worst pause %.1f us, points off the path %zu (farthest %.3f steps)%s; VCD #%lld..#%lld\n",
      c.name, pts.size(), planned,
      !r.started  ? "NOT STARTED"
      : r.faulted ? "FAULTED"
                  : "complete",
      v.compressed, v.unfaulted, static_cast<double>(v.worst_pause) / 1e3, off, worst,
      exact ? "" : ", INEXACT", static_cast<long long>(from), static_cast<long long>(to));
}

plc::PathMove3602 path(Method method, std::int32_t ex, std::int32_t ey) {
  plc::PathMove3602 m;
  m.method = method;
  m.end_x = ex;
  m.end_y = ey;
  m.profile = {.speed = 10'000, .accel = kRate, .decel = kRate};
  return m;
}

std::vector<PathCase> cases(int runs) {
  plc::PathMove3602 circle = path(Method::kCentreCcw, 0, 0);  // end = start: a full circle
  circle.point_x = 2'000;
  circle.point_y = 0;
  std::vector<PathCase> out;
  for (int r = 0; r < runs; ++r) {
    out.push_back({"line", path(Method::kLinear, 12'000, -7'000)});
    out.push_back({"circle", circle});
    out.push_back({"held line", path(Method::kLinear, 16'000, 9'000), true});
  }
  return out;
}

}  // namespace

int path_slip(int argc, char** argv) {
  const std::string exe = arg(argc, argv, "--stepmodd", "build/bench/daemon/stepmodd");
  const std::vector<PathCase> list = cases(std::atoi(arg(argc, argv, "--runs", "2")));
  std::vector<Run> runs;
  testing::DaemonProcess d(config_3602(), testing::DaemonOptions{.trace = true, .exe = exe});
  if (!d.wait_ready()) throw std::runtime_error("stepmodd did not start: " + d.log());
  {
    ipc::Client client(d.name());
    plc::ShmPort port(client, milliseconds(2000));
    plc::Plc3602 axes(port, milliseconds(2000));
    for (unsigned a = 0; a < 2; ++a) {
      if (!axes.configure(a, words::m3602::cfg_msw::kStepDirOutput, 0x1F, kVs).ok)
        throw std::runtime_error("3602 configuration refused");
    }
    plc::Interp3602 interp(port);
    for (const PathCase& c : list) runs.push_back(drive(interp, axes, client, c));
  }
  d.terminate(60'000);  // the trace is complete after it
  print_fault_lines(d.log());
  if (const char* keep = arg(argc, argv, "--keep-trace", nullptr)) {
    std::filesystem::copy_file(d.trace_path(), keep,
                               std::filesystem::copy_options::overwrite_existing);
    std::printf("trace kept: %s\n", keep);
  }
  const Nanos origin = trace_origin(d.log());
  if (origin < 0) throw std::runtime_error("no trace origin in the daemon's log");
  const std::vector<Point> all = testing::rebuild_from_vcd(testing::read_vcd(d.trace_path()));
  Totals t;
  for (std::size_t i = 0; i < list.size(); ++i) report(list[i], runs[i], all, origin, t);
  std::printf(
      "RESULT bench=slip3602 moves=%zu compressed=%zu unfaulted_pauses=%zu off_path=%zu "
      "worst_off=%.3f late_ends=%zu inexact=%zu faults_path10000=%zu/%zu\n",
      list.size(), t.compressed, t.unfaulted, t.off, t.worst_off, t.late_ends, t.inexact, t.faults,
      list.size());
  return 0;
}

}  // namespace stepmod::bench
