#pragma once
// The one place a step output is made: by name, from a table (as LinuxCNC's stepgen makes a step
// type from a row of its table, or Klipper a kinematics from its name). A new output is one row
// in rt/step_output_factory.cpp (docs/ARCHITECTURE.md, "Adding a step output").
#include <memory>
#include <string_view>
#include <vector>

#include "rt/step_output.hpp"

namespace stepmod::rt {

// The pulse thread (rt/pulse_thread_output.hpp): what stepmodd runs.
inline constexpr std::string_view kPulseThreadOutput = "pulse_thread";

// Throws std::invalid_argument naming the known outputs when `name` is none of them.
std::unique_ptr<StepOutput> make_step_output(std::string_view name, const StepOutputWiring& wiring);

// Every name make_step_output() knows, in table order (the contract tests run each).
std::vector<std::string_view> step_output_names();

}  // namespace stepmod::rt
