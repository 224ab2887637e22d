// `stepmodctl status --json` against its schema, docs/status.schema.json (docs/interface.md 1):
// the real stepmodd of each module type on the simulated machine, and the error object when the
// module cannot be read. Every member the program prints must be in the schema with its type,
// every required one present, nothing else; the schema's members are exactly the rows of
// interface.md's table. A member added or renamed in the program without the schema (or in the
// schema without the page) fails here.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "tests/support/ctl_run.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/json_schema.hpp"

namespace stepmod::testing {
namespace {

using nlohmann::json;

json status_schema() {
  return json::parse(slurp_file(std::string(STEPMOD_SOURCE_DIR) + "/docs/status.schema.json"));
}

std::string violations_of(const json& doc) {
  std::string out;
  for (const std::string& v : schema_violations(status_schema(), doc)) out += v + "\n";
  return out;
}

// The shipped example of `type` with the harness' name placeholder.
std::string example_config(const std::string& type) {
  std::string t = slurp_file(std::string(STEPMOD_SOURCE_DIR) + "/examples/" + type + "-sim.toml");
  const auto at = t.find("\nname = ");
  EXPECT_NE(at, std::string::npos) << type;
  if (at != std::string::npos)
    t.replace(at + 1, t.find('\n', at + 1) - at - 1, "name = \"{NAME}\"");
  return t;
}

// The "| `health.flags` | ..." rows of interface.md's table of status --json members.
std::set<std::string> documented_members() {
  const std::string doc = slurp_file(std::string(STEPMOD_SOURCE_DIR) + "/docs/interface.md");
  const std::string start = "<!-- status.schema.json members -->";
  const auto from = doc.find(start);
  EXPECT_NE(from, std::string::npos) << "interface.md has no " << start;
  std::set<std::string> members;
  for (auto at = doc.find("\n| `", from); at != std::string::npos && doc[at + 1] == '|';
       at = doc.find('\n', at + 1)) {
    const auto open = at + 4;
    members.insert(doc.substr(open, doc.find('`', open) - open));
  }
  return members;
}

TEST(StatusJsonSchema, RefusesAnAddedARenamedAMissingOrAMistypedMember) {
  const json good = json::parse(R"({"schema":1,"module":"m","type":3601,"scan":5,
      "health":{"flags":0,"names":[],"late_faults":0},
      "axes":[{"unit":1,"position":-3,"speed":0,"reason_seq":0,"reason_item":0,"state":"idle",
               "errors":["Command Error"],"reason":""}]})");
  ASSERT_EQ(violations_of(good), "");
  json added = good;
  added["axes"][0]["lease"] = "none";
  EXPECT_NE(violations_of(added).find("axes[0]: member 'lease' is not in the schema"),
            std::string::npos)
      << violations_of(added);
  json renamed = good;
  renamed["health"]["late_edge_faults"] = renamed["health"]["late_faults"];
  renamed["health"].erase("late_faults");
  EXPECT_NE(violations_of(renamed).find("member 'late_faults' missing"), std::string::npos);
  json joined = good;
  joined["axes"][0]["errors"] = "Command Error";
  EXPECT_NE(violations_of(joined).find("axes[0].errors: not of type array"), std::string::npos);
  json two_axes = good;
  two_axes["axes"].push_back(good["axes"][0]);
  EXPECT_NE(violations_of(two_axes).find("axes: 2 items, maxItems 1"), std::string::npos);
  EXPECT_NE(violations_of(json::parse(R"({"schema":1,"module":"m"})")), "");
}

TEST(StatusJsonSchema, InterfaceMdTablesExactlyTheSchemasMembers) {
  const std::vector<std::string> paths = schema_member_paths(status_schema());
  const std::set<std::string> schema(paths.begin(), paths.end());
  EXPECT_GE(schema.size(), 15u);
  EXPECT_EQ(documented_members(), schema);
}

class StatusJson : public ::testing::TestWithParam<const char*> {};

TEST_P(StatusJson, OfARunningModuleConformsToTheSchema) {
  DaemonProcess daemon(example_config(GetParam()), false);
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  if (std::string(GetParam()) == "3601") {
    // A refused move: an error bit set and a reason, so the lists and the reason are not empty.
    EXPECT_EQ(stepmodctl("-n " + daemon.name() + " move rel 100 -s 1000 -a 10 -d 10").exit_status,
              1);
  }
  const CtlRun r = stepmodctl("-n " + daemon.name() + " status --json");
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_EQ(r.out.find('\n'), r.out.size() - 1) << "not one line: " << r.out;
  const json doc = json::parse(r.out);
  EXPECT_EQ(violations_of(doc), "") << r.out;
  EXPECT_EQ(doc.value("type", 0), std::stoi(GetParam())) << r.out;
  EXPECT_EQ(doc.value("module", ""), daemon.name());
  if (std::string(GetParam()) == "3601") {
    const json& errors = doc["axes"][0]["errors"];
    EXPECT_NE(std::find(errors.begin(), errors.end(), "Command Error"), errors.end()) << r.out;
    EXPECT_NE(doc["axes"][0]["reason"], "") << r.out;
  }
}

INSTANTIATE_TEST_SUITE_P(EachModuleType, StatusJson, ::testing::Values("3601", "3602", "3202"));

TEST(StatusJsonError, NoModuleExit3WithTheErrorObject) {
  const CtlRun r =
      stepmodctl("-n status-json-none-" + std::to_string(::getpid()) + " status --json");
  EXPECT_EQ(r.exit_status, 3) << r.err;
  const json doc = json::parse(r.out);
  EXPECT_EQ(violations_of(doc), "") << r.out;
  EXPECT_TRUE(doc.contains("error")) << r.out;
}

TEST(StatusJsonError, AStoppedDaemonExit3WithTheErrorObject) {
  DaemonProcess daemon(example_config("3601"), false);
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  daemon.signal(SIGSTOP);
  const CtlRun r = stepmodctl("-n " + daemon.name() + " status --json");
  daemon.signal(SIGCONT);
  EXPECT_EQ(r.exit_status, 3) << r.err;
  const json doc = json::parse(r.out);
  EXPECT_EQ(violations_of(doc), "") << r.out;
  EXPECT_NE(doc.value("error", "").find("is not scanning"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace stepmod::testing
