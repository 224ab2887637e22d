// Per-edge cost of the pulse thread's work (everything but the GPIO write itself and the wait):
// next_due() over N axes, execute_one() with feedback, history, trace and lateness.
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "gpio/backend.hpp"
#include "rt/lateness_stats.hpp"
#include "rt/pulse_engine.hpp"

namespace {

using namespace stepmod;
using namespace stepmod::rt;

class NullBackend : public gpio::Backend {
 public:
  unsigned axes() const noexcept override { return 4; }
  void write(unsigned, OutputLine, bool level, Nanos) noexcept override {
    benchmark::DoNotOptimize(level);
  }
  bool has_input(unsigned, InputLine) const noexcept override { return false; }
  bool has_output(unsigned, OutputLine) const noexcept override { return true; }
  bool read(unsigned, InputLine) override { return false; }
  std::size_t wait_events(std::span<gpio::InputEvent>, Nanos) override { return 0; }
  std::uint64_t lost_events() const noexcept override { return 0; }
  void idle_outputs() noexcept override {}
};

struct Axis {
  SpscRing<Edge> ring{4096};
  AxisFeedback feedback;
  AxisControl control;
  StepHistory history;
};

// n axes and the links the engine takes (the axes stay where they are: the engine keeps
// pointers).
struct Axes {
  explicit Axes(unsigned n) {
    for (unsigned i = 0; i < n; ++i) {
      axes.push_back(std::make_unique<Axis>());
      links.push_back({&axes[i]->ring, &axes[i]->feedback, &axes[i]->control, &axes[i]->history});
    }
  }
  std::vector<std::unique_ptr<Axis>> axes;
  std::vector<AxisLink> links;
};

// range(0) axes, range(1) != 0: with a trace ring (drained as we go, as the trace thread would).
void BM_PulseEngine_Edge(benchmark::State& state) {
  const auto n = static_cast<unsigned>(state.range(0));
  const bool traced = state.range(1) != 0;
  NullBackend backend;
  Axes rig(n);
  auto& axes = rig.axes;
  SpscRing<TraceRecord> trace(4096);
  PulseEngine engine(backend, rig.links, traced ? &trace : nullptr);
  Nanos t = 0;
  unsigned k = 0;
  for (auto _ : state) {
    // Keep every ring non-empty: one step edge (alternating leading/trailing) per iteration.
    Edge e{};
    e.t = t += 1000;
    e.epoch = 1;
    e.line = OutputLine::kStep;
    e.level = (k & 1) == 0 ? 1 : 0;
    e.dpos = (k & 1) == 0 ? 1 : 0;
    e.flags = edge_flag::kMotion;
    axes[k % n]->ring.try_push(e);
    ++k;
    const Nanos due = engine.next_due();
    engine.execute_one(due + 500);
    if (traced) {
      TraceRecord r;
      trace.try_pop(r);
    }
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PulseEngine_Edge)->ArgsProduct({{1, 2, 4}, {0, 1}});

// next_due() alone with nothing queued: the cost of one idle/spinning loop turn.
void BM_PulseEngine_NextDueIdle(benchmark::State& state) {
  const auto n = static_cast<unsigned>(state.range(0));
  NullBackend backend;
  Axes rig(n);
  PulseEngine engine(backend, rig.links, nullptr);
  for (auto _ : state) benchmark::DoNotOptimize(engine.next_due());
}
BENCHMARK(BM_PulseEngine_NextDueIdle)->Arg(1)->Arg(4);

void BM_LatenessStats_Record(benchmark::State& state) {
  auto stats = std::make_unique<LatenessStats>();
  Nanos v = 0;
  for (auto _ : state) stats->record(v = (v * 1103515245 + 12345) & 0xfffff);
}
BENCHMARK(BM_LatenessStats_Record);

void BM_MonotonicNow(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(monotonic_now());
}
BENCHMARK(BM_MonotonicNow);

}  // namespace

BENCHMARK_MAIN();
