#pragma once
// The daemon's whole motion stack, wired but without threads: the rack's modules (each its own
// edge rings, planner and personality: daemon/module_stack.hpp) and the one step output that
// drains every module's rings (rt/step_output.hpp; made by name, not started). A lone module is
// a rack of one. The daemon drives it with its threads (daemon.cpp); tests drive the very same
// objects in virtual time (tests/support/virtual_machine.hpp).
#include <memory>
#include <span>
#include <vector>

#include "core/spsc_ring.hpp"
#include "core/trace_record.hpp"
#include "daemon/module_stack.hpp"
#include "daemon/stack_options.hpp"
#include "gpio/backend.hpp"
#include "rt/step_output.hpp"

namespace stepmod::tools {

// One module of a rack: how its stack is built, and its own lines.
struct StackModule {
  StackOptions options;
  gpio::Backend* backend = nullptr;
};

class Stack {
 public:
  // A rack of `modules` (1 or more, in rack order); the step output's keys (late_limit_ns,
  // step_output) are the first module's. Each backend and `trace` (may be null) must outlive
  // the stack. The step output's axes are the modules' axes in rack order (first_axis()).
  Stack(std::span<const StackModule> modules, SpscRing<TraceRecord>* trace);
  // A rack of one module.
  Stack(const StackOptions& options, gpio::Backend& backend, SpscRing<TraceRecord>* trace)
      : Stack(std::span<const StackModule>(std::vector<StackModule>{{options, &backend}}), trace) {}
  ~Stack();
  Stack(const Stack&) = delete;
  Stack& operator=(const Stack&) = delete;

  unsigned modules() const noexcept { return static_cast<unsigned>(modules_.size()); }
  ModuleStack& module(unsigned k) noexcept { return *modules_[k]; }
  const ModuleStack& module(unsigned k) const noexcept { return *modules_[k]; }
  // The step output's number of module k's first axis.
  unsigned first_axis(unsigned k) const noexcept { return first_axis_[k]; }
  rt::StepOutput& output() noexcept { return *output_; }

 private:
  std::vector<std::unique_ptr<ModuleStack>> modules_;
  std::vector<unsigned> first_axis_;
  std::unique_ptr<gpio::Backend> rack_lines_;  // several modules: their lines as one backend
  // Last: destroyed (its thread stopped) before the rings and blocks it reads.
  std::unique_ptr<rt::StepOutput> output_;
};

}  // namespace stepmod::tools
