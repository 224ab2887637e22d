#include "rt/step_output_factory.hpp"

#include <stdexcept>
#include <string>

#include "rt/pulse_thread_output.hpp"

namespace stepmod::rt {

namespace {

using Make = std::unique_ptr<StepOutput> (*)(const StepOutputWiring&);

template <typename Output>
std::unique_ptr<StepOutput> make(const StepOutputWiring& wiring) {
  return std::make_unique<Output>(wiring);
}

struct Row {
  std::string_view name;
  Make make;
};

// One row per step output.
constexpr Row kOutputs[] = {
    {kPulseThreadOutput, &make<PulseThreadOutput>},
};

}  // namespace

std::unique_ptr<StepOutput> make_step_output(std::string_view name,
                                             const StepOutputWiring& wiring) {
  for (const Row& row : kOutputs) {
    if (row.name == name) return row.make(wiring);
  }
  // Appended piece by piece: GCC 12 warns (-Wrestrict) on a chain of string concatenations.
  std::string what = "unknown step output \"";
  what.append(name).append("\" (known:");
  for (const Row& row : kOutputs) what.append(" \"").append(row.name).append("\"");
  what.append(")");
  throw std::invalid_argument(what);
}

std::vector<std::string_view> step_output_names() {
  std::vector<std::string_view> names;
  for (const Row& row : kOutputs) names.push_back(row.name);
  return names;
}

}  // namespace stepmod::rt
