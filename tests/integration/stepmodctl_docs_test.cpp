// The examples people copy: every `stepmodctl` line of docs/stepmodctl.md's example blocks and
// every example line of `stepmodctl --help` runs against the real daemon configured with the
// module's shipped example (examples/<module>-sim.toml), with the exit status the text promises
// (0, or the `# exit N` at the end of the line).
#include <gtest/gtest.h>

#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/ctl_run.hpp"
#include "tests/support/daemon_process.hpp"

namespace stepmod::testing {
namespace {

struct Example {
  std::string args;  // after "stepmodctl "
  int exit_status = 0;
};

// The example's configuration with the harness' name and the late-edge limit of a loaded VM.
std::string example_config(const std::string& module) {
  std::string t = slurp_file(std::string(STEPMOD_SOURCE_DIR) + "/examples/" + module + "-sim.toml");
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"name = \"stepmod\"", "name = \"{NAME}\""},
        {"[rt]", "[rt]\nlate_limit_us = 1000000"}}) {
    const auto at = t.find(from);
    EXPECT_NE(at, std::string::npos) << module << ": " << from;
    if (at != std::string::npos) t.replace(at, t.find('\n', at) - at, to);
  }
  // The guard at its loosest: a loaded, shared VM (tests/support/sim_config.hpp says why).
  for (std::size_t at = t.find("lag_limit_steps = "); at != std::string::npos;
       at = t.find("lag_limit_steps = ", at + 1)) {
    t.replace(at, t.find('\n', at) - at, "lag_limit_steps = 1000000");
  }
  return t;
}

Example parse_line(std::string line) {
  Example e;
  const auto hash = line.find("  # exit ");
  if (hash != std::string::npos) {
    e.exit_status = std::stoi(line.substr(hash + 9));
    line.erase(hash);
  }
  const auto c = line.find("  #");
  if (c != std::string::npos) line.erase(c);
  e.args = line.substr(std::string("stepmodctl ").size());
  return e;
}

// The ```sh blocks of docs/stepmodctl.md whose first line is "# <module> (".
std::vector<Example> doc_examples(const std::string& module) {
  std::istringstream in(slurp_file(std::string(STEPMOD_SOURCE_DIR) + "/docs/stepmodctl.md"));
  std::vector<Example> out;
  std::string line;
  bool in_block = false;
  bool ours = false;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) {
      in_block = !in_block;
      ours = false;
      continue;
    }
    if (!in_block) continue;
    if (line.rfind("# ", 0) == 0) ours = line.rfind("# " + module + " (", 0) == 0;
    if (ours && line.rfind("stepmodctl ", 0) == 0) out.push_back(parse_line(line));
  }
  return out;
}

void run_all(const std::string& module, const std::vector<Example>& examples) {
  DaemonProcess daemon(example_config(module), false);
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  for (const Example& e : examples) {
    const CtlRun r = stepmodctl("-n " + daemon.name() + " " + e.args);
    EXPECT_EQ(r.exit_status, e.exit_status) << "stepmodctl " << e.args << "\n" << r.err;
  }
}

TEST(StepmodctlDocs, Every3601ExampleRuns) {
  const auto examples = doc_examples("3601");
  ASSERT_GE(examples.size(), 10u);
  run_all("3601", examples);
}

TEST(StepmodctlDocs, Every3602ExampleRuns) {
  const auto examples = doc_examples("3602");
  ASSERT_GE(examples.size(), 10u);
  run_all("3602", examples);
}

TEST(StepmodctlDocs, Every3202ExampleRuns) {
  const auto examples = doc_examples("3202");
  ASSERT_GE(examples.size(), 10u);
  run_all("3202", examples);
}

// The help's examples ("  stepmodctl ..." lines) on a configured 3601.
TEST(StepmodctlDocs, EveryHelpExampleRuns) {
  const CtlRun help = stepmodctl("--help");
  ASSERT_EQ(help.exit_status, 0);
  std::istringstream in(help.out);
  std::vector<Example> examples{{"configure --home --cw-limit --ccw-limit", 0}};
  std::string line;
  while (std::getline(in, line)) {
    const auto at = line.find("stepmodctl ");
    if (line.rfind("  stepmodctl ", 0) != 0) continue;
    examples.push_back(parse_line(line.substr(at)));
    examples.push_back({"wait-idle", 0});  // a move while one runs is a Command Error
  }
  ASSERT_GE(examples.size(), 5u) << help.out;
  run_all("3601", examples);
}

}  // namespace
}  // namespace stepmod::testing
