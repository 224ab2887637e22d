// End to end: the real stepmodd as a 3602 draws interpolated moves commanded through shared
// memory by the PLC-side library (module_types/m3602/plc_interp_3602): a line, a full circle by the centre method,
// an arc by the radius method (the longer arc, R < 0) and one by the via-point method (absolute
// coordinates). The path is read back from the VCD trace the way an outside checker would: the
// two step/direction trains merged in time order, (x, y) rebuilt at every step edge, and checked
// against an ideal path built here from the commanded geometry (not from the module's code):
// exact end points, exact per-axis step counts (|dx|, |dy| of a line; the integer crossings of an
// arc), every step point within one step of the ideal path, and progress along the path in the
// order of the steps (the interleaving). The checkers are tests/planner/path_test_util.hpp's.
//
// The trace holds the times the edges were written. On time, the step points lie within one
// step of the ideal path; an edge written late (a stalled pulse thread, or a planner that fell
// behind on a loaded machine: the other axis' edges go out meanwhile) moves its point along the
// path by up to speed x lateness. The daemon logs its largest lateness at exit, so the bound is
// one step plus what that lateness explains: exact on a quiet machine, never a flaky failure on
// a loaded one. Counts and end points are exact whatever the timing.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "ipc/client.hpp"
#include "module_types/m3602/plc_interp_3602.hpp"
#include "module_types/m3602/plc_3602.hpp"
#include "plc/shm_port.hpp"
#include "tests/planner/path_test_util.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/sim_config.hpp"
#include "tests/support/vcd_path.hpp"
#include "tests/support/vcd_reader.hpp"
#include "module_types/m3602/words_3602.hpp"

namespace stepmod::testing {
namespace {

namespace m = words::m3602;
namespace pt = planner::test;
using planner::PathShape;
using planner::PathSpec;
using Method = plc::PathMove3602::Method;
using std::chrono::milliseconds;

// Two axes (lines 1..4, 11..14), the limits far out.
std::string config_3602() {
  std::string axes;
  for (const unsigned first : {1u, 11u}) {
    axes += sim_axis(numbered_lines(first, {"step", "dir", "gpo", "home"}),
                     "cw_limit_at = 1000000\nccw_limit_at = -1000000\n");
  }
  return sim_module_tables("3602") + axes;
}

// The path's parameter at a point: the distance along a line, the angle swept along an arc.
double progress(const PathSpec& p, double x, double y) {
  if (p.shape == PathShape::kLine) {
    const double ex = static_cast<double>(p.end_x), ey = static_cast<double>(p.end_y);
    return (x * ex + y * ey) / std::hypot(ex, ey);
  }
  const double a0 = std::atan2(-p.centre_y, -p.centre_x);
  double d = (std::atan2(y - p.centre_y, x - p.centre_x) - a0) * (p.sweep > 0 ? 1 : -1);
  d = std::fmod(d, 2 * pt::kPi);
  return d < 0 ? d + 2 * pt::kPi : d;
}

// One commanded move and the checks of its part of the trace: `points` are the points of this
// move only, relative to its start.
// `slack`: the steps the measured lateness explains (see the top of the file).
void check_segment(const std::vector<pt::PathPoint>& points, const PathSpec& p, const char* what,
                   double slack_steps) {
  SCOPED_TRACE(what);
  ASSERT_FALSE(points.empty());
  EXPECT_EQ(points.back().x, p.end_x);
  EXPECT_EQ(points.back().y, p.end_y);
  std::int64_t nx = 0, ny = 0;
  for (const pt::PathPoint& q : points) (q.axis == 0 ? nx : ny) += 1;
  if (p.shape == PathShape::kLine) {
    EXPECT_EQ(nx, std::abs(p.end_x));
    EXPECT_EQ(ny, std::abs(p.end_y));
  } else {
    EXPECT_EQ(nx, pt::arc_crossings(p, false));
    EXPECT_EQ(ny, pt::arc_crossings(p, true));
  }
  const double error = pt::max_path_error(points, p);
  EXPECT_LT(error, 1.0 + slack_steps);
  std::cout << what << ": " << points.size() << " steps, largest distance from the ideal path "
            << error << " steps\n";
  // The interleaving: the steps come in the path's order. Along a line the projection never goes
  // back by a step; along an arc the angle never goes back by more than two steps' worth (a step
  // point may lie a little behind the ideal point), and on a full circle the last points are
  // past the start (the parameter wraps to 0 at the very end).
  const double radius = std::hypot(p.centre_x, p.centre_y);
  const double slack =
      p.shape == PathShape::kLine ? 1.0 + slack_steps : (2.0 + slack_steps) / radius;
  double reached = 0.0;
  std::size_t back = 0;
  const bool full = p.shape == PathShape::kArc && p.end_x == 0 && p.end_y == 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    double u = progress(p, static_cast<double>(points[i].x), static_cast<double>(points[i].y));
    if (full && i > points.size() / 2 && u < pt::kPi) u += 2 * pt::kPi;
    if (full && i < points.size() / 2 && u > pt::kPi) u -= 2 * pt::kPi;
    if (u < reached - slack) ++back;
    reached = std::max(reached, u);
  }
  EXPECT_EQ(back, 0u) << "steps out of the path's order";
}

// The points of consecutive moves, each made relative to its start; the counts of the ideal
// paths split the trace (a wrong count shows as a wrong end point of that move or the next).
std::vector<std::vector<pt::PathPoint>> split(const std::vector<pt::PathPoint>& all,
                                              const std::vector<PathSpec>& moves) {
  std::vector<std::vector<pt::PathPoint>> out;
  std::size_t at = 0;
  std::int64_t x0 = 0, y0 = 0;
  for (const PathSpec& p : moves) {
    const std::size_t n =
        p.shape == PathShape::kLine
            ? static_cast<std::size_t>(std::abs(p.end_x) + std::abs(p.end_y))
            : static_cast<std::size_t>(pt::arc_crossings(p, false) + pt::arc_crossings(p, true));
    std::vector<pt::PathPoint> seg;
    for (std::size_t i = at; i < std::min(all.size(), at + n); ++i) {
      pt::PathPoint q = all[i];
      q.x -= x0;
      q.y -= y0;
      seg.push_back(q);
    }
    at = std::min(all.size(), at + n);
    x0 += p.end_x;
    y0 += p.end_y;
    out.push_back(std::move(seg));
  }
  return out;
}

class Daemon3602Path : public ::testing::Test {
 protected:
  void SetUp() override {
    daemon_ = std::make_unique<DaemonProcess>(config_3602());
    ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
    client_ = std::make_unique<ipc::Client>(daemon_->name());
    port_ = std::make_unique<plc::ShmPort>(*client_, milliseconds(2000));
    plc::Plc3602 axes(*port_, milliseconds(2000));
    constexpr std::uint16_t kStepDir = m::cfg_msw::kStepDirOutput;
    ASSERT_TRUE(axes.configure(0, kStepDir, 0x1F, 1'000).ok);
    ASSERT_TRUE(axes.configure(1, kStepDir, 0x1F, 1'000).ok);
    // Valid positions (absolute coordinates need them, 3602-CE-07).
    ASSERT_TRUE(axes.preset_position(0, 0).ok);
    ASSERT_TRUE(axes.preset_position(1, 0).ok);
    interp_ = std::make_unique<plc::Interp3602>(*port_);
  }
  void run(const plc::PathMove3602& move) {
    const plc::Outcome started = interp_->move(move);
    ASSERT_TRUE(started.ok) << started.message;
    const plc::Outcome done = interp_->wait_done(std::chrono::seconds(20));
    ASSERT_TRUE(done.ok) << done.message << "\n" << daemon_->log();
  }
  std::vector<pt::PathPoint> stop_and_rebuild() {
    interp_.reset();
    port_.reset();
    client_.reset();
    EXPECT_EQ(daemon_->terminate(), 0) << daemon_->log();
    // "pulse thread: N edges written, lateness p50 .. ns, p99.9 .. ns, max L ns" (at exit).
    const std::string log = daemon_->log();
    const auto at = log.find(", max ", log.find("pulse thread: "));
    EXPECT_NE(at, std::string::npos) << log;
    const double late_s = at == std::string::npos ? 0.0 : std::stod(log.substr(at + 6)) * 1e-9;
    slack_ = kSpeed * late_s;
    std::cout << "largest lateness " << late_s * 1e6 << " us: bound " << 1.0 + slack_ << " steps\n";
    return rebuild_from_vcd(read_vcd(daemon_->trace_path()));
  }
  static constexpr std::int32_t kSpeed = 10'000;  // vector, steps/s: the circle takes 1.3 s
  static plc::PathMove3602 move(Method method, std::int32_t ex, std::int32_t ey) {
    plc::PathMove3602 m;
    m.method = method;
    m.end_x = ex;
    m.end_y = ey;
    m.profile = {.speed = kSpeed, .accel = 100, .decel = 100};  // rates in steps/ms/s
    return m;
  }
  std::unique_ptr<DaemonProcess> daemon_;
  std::unique_ptr<ipc::Client> client_;
  std::unique_ptr<plc::ShmPort> port_;
  std::unique_ptr<plc::Interp3602> interp_;
  double slack_ = 0.0;  // steps the largest lateness explains
};

TEST_F(Daemon3602Path, ALineAndAFullCircleByTheCentreAreDrawnStepByStep) {
  run(move(Method::kLinear, 3'000, -1'700));
  plc::PathMove3602 circle = move(Method::kCentreCcw, 0, 0);  // end = start: a full circle
  circle.point_x = 2'000;
  circle.point_y = 0;
  run(circle);
  const std::vector<PathSpec> ideal{pt::line(3'000, -1'700), arc_spec(2'000, 0, 0, 0, false)};
  const auto points = stop_and_rebuild();
  const auto parts = split(points, ideal);
  EXPECT_EQ(points.size(), 4'700u + 2 * 2 * 4'000u);  // a full circle: 4 r crossings per axis
  check_segment(parts[0], ideal[0], "line (3000, -1700)", slack_);
  check_segment(parts[1], ideal[1], "full circle CCW around (2000, 0)", slack_);
}

TEST_F(Daemon3602Path, ALongArcByTheRadiusAndAnAbsoluteViaPointArc) {
  // R < 0: the longer of the two CW arcs to (1500, 0) of radius 1250, around (750, 1000).
  plc::PathMove3602 by_radius = move(Method::kRadiusCw, 1'500, 0);
  by_radius.radius = -1'250;
  run(by_radius);
  // From (1500, 0) over (2500, 1000) to (3500, 0): the CW half circle around (2500, 0).
  plc::PathMove3602 via = move(Method::kViaPoint, 3'500, 0);
  via.absolute = true;
  via.point_x = 2'500;
  via.point_y = 1'000;
  run(via);
  const std::vector<PathSpec> ideal{arc_spec(750, 1'000, 1'500, 0, true),
                                    arc_spec(1'000, 0, 2'000, 0, true)};
  ASSERT_LT(ideal[0].sweep, -pt::kPi);  // the longer arc
  const auto points = stop_and_rebuild();
  const auto parts = split(points, ideal);
  EXPECT_EQ(points.size(),
            static_cast<std::size_t>(pt::arc_crossings(ideal[0], false) +
                                     pt::arc_crossings(ideal[0], true) + 2'000 + 2 * 1'000));
  check_segment(parts[0], ideal[0], "radius -1250 CW to (1500, 0)", slack_);
  check_segment(parts[1], ideal[1], "via (2500, 1000) to (3500, 0), absolute", slack_);
}

}  // namespace
}  // namespace stepmod::testing
