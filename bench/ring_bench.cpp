// SpscRing costs: the one queue on the motion path (planner -> pulse thread).
#include <benchmark/benchmark.h>

#include <atomic>
#include <cstdint>
#include <thread>

#include "core/spsc_ring.hpp"
#include "rt/edge.hpp"

namespace {

using stepmod::SpscRing;
using stepmod::rt::Edge;

// Same thread, one push then one pop: the uncontended cost of both sides.
void BM_SpscRing_PushPop(benchmark::State& state) {
  SpscRing<Edge> ring(4096);
  Edge e{};
  for (auto _ : state) {
    e.t += 1;
    ring.try_push(e);
    Edge out;
    ring.try_pop(out);
    benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SpscRing_PushPop);

// Fill, then drain, `range(0)` edges: the planner's refill pattern.
void BM_SpscRing_Batch(benchmark::State& state) {
  const auto batch = static_cast<std::size_t>(state.range(0));
  SpscRing<Edge> ring(4096);
  Edge e{};
  for (auto _ : state) {
    for (std::size_t i = 0; i < batch; ++i) {
      e.t += 1;
      ring.try_push(e);
    }
    Edge out;
    while (ring.try_pop(out)) benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(batch));
}
BENCHMARK(BM_SpscRing_Batch)->Arg(16)->Arg(256)->Arg(4096);

// Producer and consumer on different threads (cache-line traffic between cores). On a loaded
// 2-core machine this measures the scheduler as much as the ring: read with care.
void BM_SpscRing_CrossThread(benchmark::State& state) {
  SpscRing<std::uint64_t> ring(1024);
  std::atomic<bool> stop{false};
  std::thread producer([&] {
    std::uint64_t i = 0;
    while (!stop.load(std::memory_order_relaxed)) {
      if (ring.try_push(i)) ++i;
    }
  });
  std::uint64_t got = 0;
  for (auto _ : state) {
    std::uint64_t v = 0;
    while (!ring.try_pop(v)) {
    }
    benchmark::DoNotOptimize(v);
    ++got;
  }
  stop.store(true);
  producer.join();
  state.SetItemsProcessed(static_cast<std::int64_t>(got));
}
BENCHMARK(BM_SpscRing_CrossThread)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
