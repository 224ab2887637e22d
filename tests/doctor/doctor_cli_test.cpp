// `stepmodctl doctor` on this machine: every section printed and a safe rate; usage and config
// errors exit 2; `stepmodctl isolate` through the program.
#include <gtest/gtest.h>

#include <regex>

#include "fake_root.hpp"
#include "tests/support/ctl_run.hpp"

namespace stepmod::testing {
namespace {

TEST(DoctorCli, PrintsEverySectionAndASafeRate) {
  FakeRoot r;
  r.write("/m.toml",
          "[module]\ntype = \"3602\"\nname = \"doc\"\n[gpio]\nbackend = \"sim\"\n[rt]\n"
          "priority = 80\n[[axis]]\nstep = 1\ndir = 2\n[[axis]]\nstep = 3\ndir = 4\n"
          "lag_limit_steps = 16\n");
  const CtlRun run = stepmodctl("doctor --seconds 1 --config " + r.path("/m.toml"));
  ASSERT_TRUE(run.exit_status == 0 || run.exit_status == 1) << run.out << run.err;
  for (const char* section : {"kernel:", "cpus:", "pulse cpu:", "rt throttling:", "cpu governor:",
                              "rtprio:", "gpio chips:", "gpio lines:", "wake-up:", "safe rate:",
                              "verdict:", "to raise it:"}) {
    EXPECT_NE(run.out.find(std::string("\n") + section), std::string::npos)
        << section << " missing in:\n" << run.out;
  }
  const std::regex rate(R"(axis 2: lag_limit_steps 16 -> safe up to ([0-9]+) steps/s)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(run.out, m, rate)) << run.out;
  EXPECT_GT(std::stol(m[1]), 0);
}

TEST(DoctorCli, NotFitForAnImpossibleSpeed) {
  const CtlRun run = stepmodctl("doctor --seconds 0.2 --speed 1e12");
  EXPECT_EQ(run.exit_status, 1) << run.out << run.err;
  EXPECT_NE(run.out.find("verdict: NOT FIT"), std::string::npos) << run.out;
}

TEST(DoctorCli, ABadConfigOrOptionIsAUsageError) {
  FakeRoot r;
  r.write("/bad.toml", "[module]\ntype = \"9999\"\n");
  EXPECT_EQ(stepmodctl("doctor --seconds 0.1 --config " + r.path("/bad.toml")).exit_status, 2);
  EXPECT_EQ(stepmodctl("doctor --seconds 0").exit_status, 2);
  EXPECT_EQ(stepmodctl("isolate").exit_status, 2);
}

TEST(DoctorCli, IsolateThroughTheProgramInARoot) {
  FakeRoot r;
  r.write("/sys/devices/system/cpu/online", "0-1\n");
  const CtlRun on = stepmodctl("isolate --cpu 1 --root " + r.dir());
  ASSERT_EQ(on.exit_status, 0) << on.err;
  EXPECT_NE(r.read("/etc/systemd/system/stepmodd@.service.d/50-cpu.conf").find("CPUAffinity=0\n"),
            std::string::npos);
  EXPECT_EQ(stepmodctl("isolate --off --root " + r.dir()).exit_status, 0);
  EXPECT_FALSE(r.exists("/etc/sysctl.d/50-stepmod.conf"));
  EXPECT_EQ(stepmodctl("isolate --cpu 5 --root " + r.dir()).exit_status, 2);
}

}  // namespace
}  // namespace stepmod::testing
