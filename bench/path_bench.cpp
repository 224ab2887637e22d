// Benchmark 11 (issue 11): the planner's interpolated path.
//   path_bench [Google Benchmark flags]      throughput: edges planned per second of one core,
//                                            both axes of a line or a full circle through
//                                            planner::Planner (items_per_second = edges/s)
//   path_bench error [--moves N] [--seed S]  path error: N random lines and arcs (seeded), the
//                                            largest distance of any step point (the two axes'
//                                            counts after each step, in time order) from the
//                                            ideal path, in steps; RESULT lines
// Virtual time, as planner_bench: `now` follows the planned edges, nothing sleeps.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/spsc_ring.hpp"
#include "planner/planner.hpp"
#include "rt/axis_feedback.hpp"
#include "rt/edge.hpp"
#include "tests/planner/path_ideal.hpp"

namespace {

using namespace stepmod;
using planner::PathCoordinate;
using planner::PathShape;
using planner::PathSpec;
constexpr double kPi = std::numbers::pi;

// Both axes of one planner; `drain` is called with each edge taken from the rings.
struct Rig {
  Rig() {
    for (unsigned i = 0; i < 2; ++i) {
      rings[i] = std::make_unique<SpscRing<rt::Edge>>(1u << 15);
      axes[i] = planner::PlannerAxis{rings[i].get(), &control[i], {}};
    }
    plan = std::make_unique<planner::Planner>(std::span<const planner::PlannerAxis>(axes));
  }
  void start(const PathSpec& p) {
    planner::Command c;
    c.group = ids.next(2);
    for (unsigned i = 0; i < 2; ++i) {
      c.axis = static_cast<std::uint8_t>(i);
      c.epoch = ++epoch[i];
      c.what = planner::PathStart{p, i == 0 ? PathCoordinate::kX : PathCoordinate::kY};
      plan->submit(c);
    }
  }
  // Runs the path to its end (both axes' kLast edges).
  template <class Drain>
  void run(Drain&& drain) {
    std::array<bool, 2> last{false, false};
    while (!last[0] || !last[1]) {
      plan->service(now);
      for (unsigned i = 0; i < 2; ++i) {
        rt::Edge e;
        while (rings[i]->try_pop(e)) {
          drain(i, e);
          now = std::max(now, e.t);
          last[i] = last[i] || (e.flags & rt::edge_flag::kLast) != 0;
        }
      }
      now += 10'000;  // an axis without edges for a while must not stall virtual time
    }
  }

  std::array<std::unique_ptr<SpscRing<rt::Edge>>, 2> rings;
  std::array<rt::AxisControl, 2> control;
  std::array<planner::PlannerAxis, 2> axes;
  std::unique_ptr<planner::Planner> plan;
  planner::GroupIds ids;
  std::array<std::uint32_t, 2> epoch{0, 0};
  Nanos now = 0;
};

PathSpec profile(PathSpec p, double vp) {
  p.vs = 1'000;
  p.vp = vp;
  p.accel = {2e6, planner::AccelShape::kConstant};
  p.decel = {2e6, planner::AccelShape::kConstant};
  return p;
}

PathSpec arc(double cx, double cy, double sweep) {
  PathSpec p;
  p.shape = PathShape::kArc;
  p.centre_x = cx;
  p.centre_y = cy;
  p.sweep = sweep;
  const double r = std::hypot(cx, cy);
  const double a = std::atan2(-cy, -cx) + sweep;
  p.end_x = std::llround(cx + r * std::cos(a));
  p.end_y = std::llround(cy + r * std::sin(a));
  // The sweep to the rounded end point (path_spec.hpp).
  p.sweep =
      sweep +
      std::remainder(
          std::atan2(static_cast<double>(p.end_y) - cy, static_cast<double>(p.end_x) - cx) - a,
          2 * kPi);
  return p;
}

void run_bench(benchmark::State& state, const PathSpec& p) {
  std::int64_t edges = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Rig rig;
    state.ResumeTiming();
    rig.start(p);
    rig.run([&](unsigned, const rt::Edge&) { ++edges; });
  }
  state.SetItemsProcessed(edges);
  state.counters["edges_per_path"] =
      benchmark::Counter(static_cast<double>(edges) / static_cast<double>(state.iterations()));
}

// A 700,000-step line at 1 Msteps/s vector speed, and an arc of 1.9 pi (~760,000 steps) of
// radius 100,000.3 at the same speed; its end point rounded to integers makes it a spiral (the
// module's integer world), the solver's costlier case.
void BM_Path_Line(benchmark::State& s) {
  PathSpec p;
  p.shape = PathShape::kLine;
  p.end_x = 400'000;
  p.end_y = -300'000;
  run_bench(s, profile(p, 1e6));
}
void BM_Path_Arc(benchmark::State& s) {
  run_bench(s, profile(arc(100'000.3, 0.0, 1.9 * kPi), 1e6));
}
BENCHMARK(BM_Path_Line)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Path_Arc)->Unit(benchmark::kMillisecond);

// --- path error ---

struct Err {
  double max = 0.0;
  std::int64_t points = 0;
  int exact_ends = 0;
  int moves = 0;
};

// One path: the two step trains merged by time (steps at one instant are one event), the
// distance of each point, and whether the counts end on the end point.
void measure(const PathSpec& p, Err& err) {
  const planner::test::IdealPath ideal(p);  // the path tests' reference, written from the contract
  Rig rig;
  rig.start(p);
  std::array<std::vector<rt::Edge>, 2> st;
  rig.run([&](unsigned i, const rt::Edge& e) {
    if (e.dpos != 0) st[i].push_back(e);
  });
  std::int64_t x = 0, y = 0;
  std::size_t i = 0, j = 0;
  while (i < st[0].size() || j < st[1].size()) {
    const Nanos t = std::min(i < st[0].size() ? st[0][i].t : INT64_MAX,
                             j < st[1].size() ? st[1][j].t : INT64_MAX);
    while (i < st[0].size() && st[0][i].t == t) x += st[0][i++].dpos;
    while (j < st[1].size() && st[1][j].t == t) y += st[1][j++].dpos;
    err.max = std::max(err.max, ideal.distance(static_cast<double>(x), static_cast<double>(y)));
    ++err.points;
  }
  err.exact_ends += x == p.end_x && y == p.end_y;
  ++err.moves;
}

int error_main(int moves, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  Err lines, arcs;
  for (int k = 0; k < moves; ++k) {
    // Sizes spread over four decades (10 .. 100,000 steps), speeds 10 k .. 500 k steps/s.
    const double size = std::pow(10.0, 1.0 + 4.0 * uni(rng));
    const double vp = 1e4 + 4.9e5 * uni(rng);
    if (k % 2 == 0) {
      PathSpec p;
      p.shape = PathShape::kLine;
      const double a = 2 * kPi * uni(rng);
      p.end_x = std::llround(size * std::cos(a));
      p.end_y = std::llround(size * std::sin(a));
      measure(profile(p, vp), lines);
    } else {
      const double rad = size / (2 * kPi) + 1.0;
      const double a0 = 2 * kPi * uni(rng);
      const double sweep = (uni(rng) < 0.5 ? -1.0 : 1.0) * 2 * kPi * std::max(0.01, uni(rng));
      measure(profile(arc(-rad * std::cos(a0), -rad * std::sin(a0), sweep), vp), arcs);
    }
  }
  for (const auto& [name, e] : {std::pair{"line", lines}, std::pair{"arc", arcs}}) {
    std::printf(
        "RESULT bench=path_error kind=%s moves=%d points=%lld exact_ends=%d max_err_steps=%.6f\n",
        name, e.moves, static_cast<long long>(e.points), e.exact_ends, e.max);
  }
  std::printf("RESULT bench=path_error_max moves=%d exact_ends=%d max_err_steps=%.6f\n",
              lines.moves + arcs.moves, lines.exact_ends + arcs.exact_ends,
              std::max(lines.max, arcs.max));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "error") == 0) {
    int moves = 1'000;
    std::uint64_t seed = 11;
    for (int i = 2; i + 1 < argc; i += 2) {
      if (std::strcmp(argv[i], "--moves") == 0) moves = std::atoi(argv[i + 1]);
      if (std::strcmp(argv[i], "--seed") == 0) seed = std::strtoull(argv[i + 1], nullptr, 10);
    }
    return error_main(moves, seed);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
