// Benchmark 3 of issue 5: planner throughput, edges planned per second of one core, through the
// planner's public API (planner::Planner: submit a move, service() as the planner thread does,
// drain the ring as the pulse thread does). Virtual time: `now` follows the planned edges, so the
// planner always has room and work; nothing sleeps.
//
//   planner_bench [Google Benchmark flags]   (items_per_second = edges/s)
#include <benchmark/benchmark.h>

#include <memory>

#include "core/spsc_ring.hpp"
#include "planner/planner.hpp"
#include "rt/axis_feedback.hpp"
#include "rt/edge.hpp"

namespace {

using namespace stepmod;
using planner::AccelShape;

struct Case {
  AccelShape shape;
  std::int64_t steps;
  double vs, vp, accel, decel;
};

// Fast moves (what the planner must keep up with): 1 Msteps/s peak, 2,000,000 steps/s^2 (the
// manuals' largest rate). 400,000 steps: trapezoids cruise, the triangles never reach vp.
constexpr Case kTrapezoid{AccelShape::kConstant, 400'000, 1'000, 1'000'000, 2e6, 2e6};
constexpr Case kTriangle{AccelShape::kConstant, 400'000, 1'000, 2'000'000, 2e6, 2e6};
constexpr Case kSTriangular{AccelShape::kTriangularS, 400'000, 1'000, 1'000'000, 2e6, 2e6};
constexpr Case kSTrapezoidal{AccelShape::kTrapezoidalS, 400'000, 1'000, 1'000'000, 2e6, 2e6};

void run(benchmark::State& state, const Case& k) {
  SpscRing<rt::Edge> ring(1u << 15);  // as the daemon's (tools::StackOptions::edge_ring)
  rt::AxisControl control;
  const planner::PlannerAxis axis{&ring, &control, {}};
  std::int64_t edges = 0;
  std::uint32_t epoch = 0;
  Nanos now = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto plan = std::make_unique<planner::Planner>(std::span(&axis, 1));
    state.ResumeTiming();
    planner::MoveSpec m;
    m.steps = k.steps;
    m.vs = k.vs;
    m.vp = k.vp;
    m.accel = {k.accel, k.shape};
    m.decel = {k.decel, k.shape};
    planner::Command c;
    c.epoch = ++epoch;
    c.what = m;
    plan->submit(c);
    bool last = false;
    while (!last) {
      plan->service(now);
      rt::Edge e;
      while (ring.try_pop(e)) {
        ++edges;
        now = e.t;
        last = last || (e.flags & rt::edge_flag::kLast) != 0;
      }
    }
  }
  state.SetItemsProcessed(edges);
  state.counters["edges_per_move"] =
      benchmark::Counter(static_cast<double>(edges) / static_cast<double>(state.iterations()));
}

void BM_Planner_Trapezoid(benchmark::State& s) {
  run(s, kTrapezoid);
}
void BM_Planner_Triangle(benchmark::State& s) {
  run(s, kTriangle);
}
void BM_Planner_SCurveTriangular(benchmark::State& s) {
  run(s, kSTriangular);
}
void BM_Planner_SCurveTrapezoidal(benchmark::State& s) {
  run(s, kSTrapezoidal);
}
BENCHMARK(BM_Planner_Trapezoid)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Planner_Triangle)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Planner_SCurveTriangular)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Planner_SCurveTrapezoidal)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
