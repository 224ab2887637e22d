// Tests that start threads: the trace writer's own thread, and the sim backend's events arriving
// from another (pulse) thread while the control thread waits.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "gpio/sim_backend.hpp"
#include "gpio/vcd_trace.hpp"

namespace stepmod::gpio {
namespace {

TEST(GpioTraceWriterThread, WritesEverythingPushedWhileRunningAndOnStop) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("stepmod_gpio_thread_" + std::to_string(::getpid()) + ".vcd"))
                               .string();
  SpscRing<TraceRecord> outs(1024), ins(1024);
  const std::vector<TraceWire> wires = {{0, false, 0, false}, {0, true, 2, false}};
  const Nanos start = monotonic_now();
  TraceWriter w(path, wires, start, outs, ins, 1 * kNsPerMs);
  w.start();
  constexpr int kN = 2000;
  std::thread producer([&] {
    for (int i = 0; i < kN; ++i) {
      const TraceRecord r{start + 1000 + i * 1000, 0, 0, static_cast<std::uint8_t>(i % 2 == 0), 0};
      while (!outs.try_push(r)) std::this_thread::yield();
    }
  });
  for (int i = 0; i < 10; ++i) {
    const TraceRecord r{start + 1500 + i * 100'000, 0, 2, static_cast<std::uint8_t>(i % 2 == 0), 1};
    while (!ins.try_push(r)) std::this_thread::yield();
  }
  producer.join();
  w.stop();
  EXPECT_EQ(w.vcd().changes(), static_cast<std::uint64_t>(kN + 10));
  EXPECT_EQ(w.vcd().late(), 0u);

  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str();
  EXPECT_NE(text.find("$enddefinitions $end"), std::string::npos);
  // Times never decrease.
  std::istringstream in(text);
  std::string tok;
  long long last = -1;
  bool monotonic = true;
  while (in >> tok) {
    if (tok[0] == '#') {
      const long long t = std::stoll(tok.substr(1));
      if (t < last) monotonic = false;
      last = t;
    }
  }
  EXPECT_TRUE(monotonic);
  std::filesystem::remove(path);
}

TEST(GpioSimBackendThread, WaitEventsWakesForAnEdgeWrittenByAnotherThread) {
  SimAxisSetup s;
  s.lines.out[0] = 1;
  s.lines.out[1] = 2;
  s.lines.in[static_cast<unsigned>(InputLine::kCwLimit)] = 3;
  s.sim.cw_limit_at = 1;
  const std::vector<SimAxisSetup> axes = {s};
  SimBackend b(axes);
  Nanos written = 0;
  std::thread pulse([&] {
    sleep_until(monotonic_now() + 5 * kNsPerMs);
    b.write(0, OutputLine::kDir, true, monotonic_now());
    written = monotonic_now();
    b.write(0, OutputLine::kStep, true, written);
  });
  InputEvent ev[4];
  const std::size_t n = b.wait_events(ev, monotonic_now() + 2 * kNsPerSec);
  const Nanos woke = monotonic_now();
  pulse.join();
  ASSERT_EQ(n, 1u);
  EXPECT_EQ(ev[0].line, InputLine::kCwLimit);
  EXPECT_TRUE(ev[0].level);
  EXPECT_EQ(ev[0].t, written);
  EXPECT_LT(woke - written, 200 * kNsPerMs);  // polled in 50 us chunks; generous on a busy box
}

}  // namespace
}  // namespace stepmod::gpio
