#pragma once
// A Backend that records the line writes, for driving PulseEngine in tests. Storage is reserved
// up front so that write() does not allocate (it may run in the pulse thread).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/spsc_ring.hpp"
#include "gpio/backend.hpp"
#include "rt/pulse_engine.hpp"

namespace stepmod::rt::test {

struct Write {
  unsigned axis = 0;
  OutputLine line = OutputLine::kStep;
  bool level = false;
  Nanos t = 0;       // the time the engine stamped the write with
  Nanos real_t = 0;  // CLOCK_MONOTONIC when write() actually ran
};

class FakeBackend : public gpio::Backend {
 public:
  explicit FakeBackend(unsigned axes, std::size_t capacity = 1 << 16) : axes_(axes) {
    writes_.reserve(capacity);
  }

  unsigned axes() const noexcept override { return axes_; }
  void write(unsigned axis, OutputLine line, bool level, Nanos t) noexcept override {
    if (writes_.size() < writes_.capacity()) {
      writes_.push_back(Write{axis, line, level, t, monotonic_now()});
    } else {
      ++overflow_;
    }
  }
  bool has_input(unsigned, InputLine) const noexcept override { return false; }
  bool has_output(unsigned, OutputLine) const noexcept override { return true; }
  bool read(unsigned, InputLine) override { return false; }
  std::size_t wait_events(std::span<gpio::InputEvent>, Nanos) override { return 0; }
  std::uint64_t lost_events() const noexcept override { return 0; }
  void idle_outputs() noexcept override {}

  // Only while the pulse thread is stopped (or in single-threaded tests).
  const std::vector<Write>& writes() const { return writes_; }
  std::size_t overflow() const { return overflow_; }
  void clear() { writes_.clear(); }

 private:
  unsigned axes_;
  std::vector<Write> writes_;
  std::size_t overflow_ = 0;
};

inline Edge make_edge(Nanos t, std::uint32_t epoch, OutputLine line, bool level, int dpos,
                      std::uint8_t flags) {
  Edge e;
  e.t = t;
  e.epoch = epoch;
  e.line = line;
  e.level = level ? 1 : 0;
  e.dpos = static_cast<std::int8_t>(dpos);
  e.flags = flags;
  return e;
}

// One step pulse of a motion: leading edge at t (counts `dpos`), trailing edge at t + width.
inline void push_step(SpscRing<Edge>& ring, Nanos t, Nanos width, std::uint32_t epoch, int dpos = 1,
                      std::uint8_t extra_flags = 0, bool last = false,
                      OutputLine line = OutputLine::kStep) {
  const std::uint8_t f = static_cast<std::uint8_t>(edge_flag::kMotion | extra_flags);
  ring.try_push(make_edge(t, epoch, line, true, dpos, f));
  ring.try_push(make_edge(t + width, epoch, line, false, 0,
                          static_cast<std::uint8_t>(f | (last ? edge_flag::kLast : 0))));
}

}  // namespace stepmod::rt::test

namespace stepmod::rt::test {

// N axes' worth of rings, feedback, control and history wired to a PulseEngine over a
// FakeBackend. Heap-allocated parts because StepHistory is 64 KB per axis.
struct Rig {
  struct Axis {
    SpscRing<Edge> ring{4096};
    AxisFeedback feedback;
    AxisControl control;
    StepHistory history;
  };

  explicit Rig(unsigned n, SpscRing<TraceRecord>* trace = nullptr) : backend(n) {
    for (unsigned i = 0; i < n; ++i) {
      axes.push_back(std::make_unique<Axis>());
      links.push_back(AxisLink{&axes.back()->ring, &axes.back()->feedback, &axes.back()->control,
                               &axes.back()->history});
    }
    engine = std::make_unique<PulseEngine>(backend, links, trace);
  }

  // Virtual time: executes every queued edge exactly `lateness` after its time.
  std::size_t run_all(Nanos lateness = 0) {
    std::size_t n = 0;
    for (Nanos t = engine->next_due(); t != kNever; t = engine->next_due()) {
      engine->execute_one(t + lateness);
      ++n;
    }
    return n;
  }

  SpscRing<Edge>& ring(unsigned i) { return axes[i]->ring; }
  AxisFeedback& fb(unsigned i) { return axes[i]->feedback; }
  AxisControl& ctl(unsigned i) { return axes[i]->control; }
  StepHistory& history(unsigned i) { return axes[i]->history; }

  FakeBackend backend;
  std::vector<std::unique_ptr<Axis>> axes;
  std::vector<AxisLink> links;
  std::unique_ptr<PulseEngine> engine;
};

}  // namespace stepmod::rt::test
