// stepmodd --check looks at this machine as a start would (tools/stepmodd.cpp): an [rt] cpu the
// machine has not is a configuration error (exit 2), and with the gpiod backend a chip that is
// not there is refused (exit 1) listing the chips there are and naming gpiodetect. Before, both
// passed --check: the first ran unpinned after a warning, the second failed only at start. (The
// gpio-sim VM's check_hardware_* cases run the same against a real kernel chip.)
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "tests/support/ctl_run.hpp"
#include "tests/support/daemon_process.hpp"

namespace {

std::string replaced(std::string t, const std::string& from, const std::string& to) {
  const auto at = t.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) t.replace(at, from.size(), to);
  return t;
}

struct CheckRun {
  int status;
  std::string err;
};

CheckRun check(const std::string& toml) {
  const std::string path = "/tmp/stepmod-check-machine-" + std::to_string(::getpid()) + ".toml";
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::fputs(toml.c_str(), f);
  std::fclose(f);
  CheckRun r{};
  r.status = stepmod::testing::DaemonProcess::run_to_exit("--check --config " + path, &r.err);
  std::remove(path.c_str());
  return r;
}

const std::string kSim =
    stepmod::testing::slurp_file(std::string(STEPMOD_SOURCE_DIR) + "/examples/3601-sim.toml");

TEST(DaemonCheckMachine, AnRtCpuBeyondTheOnlineOnesIsRefused) {
  ASSERT_EQ(check(kSim).status, 0);
  const CheckRun r = check(replaced(kSim, "\ncpu = -1", "\ncpu = 1000"));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("rt.cpu"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("CPU 1000 is not online"), std::string::npos) << r.err;
}

TEST(DaemonCheckMachine, AMissingChipIsRefusedWithTheChipsThereAreAndGpiodetect) {
  const std::string board =
      stepmod::testing::slurp_file(std::string(STEPMOD_SOURCE_DIR) + "/examples/3601-board.toml");
  const std::string chip_line = board.substr(board.find("\nchip = ") + 1);
  const CheckRun r =
      check(replaced(board, chip_line.substr(0, chip_line.find('\n')), "chip = \"no-such-chip\""));
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("GPIO chip 'no-such-chip' not found"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("gpiodetect"), std::string::npos) << r.err;
}

}  // namespace
