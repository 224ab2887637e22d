#pragma once
// One step output made by name (rt/step_output_factory.hpp) over a FakeBackend, with N axes'
// rings, feedback, control and history: the contract tests drive it through rt::StepOutput
// alone, so that every output in the factory's table is held to the same guarantees.
#include <memory>
#include <string_view>
#include <vector>

#include "rt/step_output.hpp"
#include "rt/step_output_factory.hpp"
#include "tests/rt/fake_backend.hpp"

namespace stepmod::rt::test {

struct OutputRig {
  struct Axis {
    SpscRing<Edge> ring{4096};
    AxisFeedback feedback;
    AxisControl control;
    StepHistory history;
  };

  OutputRig(std::string_view name, unsigned n) : backend(n) {
    for (unsigned i = 0; i < n; ++i) {
      axes.push_back(std::make_unique<Axis>());
      Axis& a = *axes.back();
      links.push_back(AxisLink{&a.ring, &a.feedback, &a.control, &a.history});
    }
    output = make_step_output(name, {backend, links, nullptr});
  }

  // Virtual time: executes the next change `lateness` after it is due; returns its due time.
  Nanos run_one(Nanos lateness = 0) {
    const Nanos t = output->next_due();
    if (t != kNever) output->execute_one(t + lateness);
    return t;
  }
  // Executes every queued change on time.
  std::size_t run_all() {
    std::size_t n = 0;
    while (run_one() != kNever) ++n;
    return n;
  }

  SpscRing<Edge>& ring(unsigned i) { return axes[i]->ring; }
  AxisFeedback& fb(unsigned i) { return axes[i]->feedback; }
  AxisControl& ctl(unsigned i) { return axes[i]->control; }
  StepHistory& history(unsigned i) { return axes[i]->history; }
  // The leading edges' write times of `axis` (rising step line).
  std::vector<Nanos> rises(unsigned axis) const {
    std::vector<Nanos> t;
    for (const Write& w : backend.writes()) {
      if (w.axis == axis && w.line == OutputLine::kStep && w.level) t.push_back(w.t);
    }
    return t;
  }

  FakeBackend backend;
  std::vector<std::unique_ptr<Axis>> axes;
  std::vector<AxisLink> links;
  std::unique_ptr<StepOutput> output;
};

}  // namespace stepmod::rt::test
