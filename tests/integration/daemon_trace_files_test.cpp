// stepmodd's --trace files against a hostile or full directory (docs/hardening.md): a link or
// FIFO under the trace's names stops the start with exit status 1 and touches nothing; links
// under the VCD's old temporary names change nothing; a full disk sets health bit 4 while
// running and ends with exit status 3 and the spools kept; a killed daemon's spools become a VCD
// with `stepmodctl trace recover`.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "ipc/client.hpp"
#include "ipc/sim_panel.hpp"
#include "tests/support/ctl_run.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/shm_plc_3601.hpp"
#include "tests/support/sim_config.hpp"
#include "tests/support/vcd_reader.hpp"

namespace stepmod::testing {
namespace {

namespace fs = std::filesystem;
namespace m = words::m3601;
using std::chrono::milliseconds;

constexpr const char* kSim = "cw_limit_at = 10000000\nccw_limit_at = -10000000\n";
constexpr unsigned kHomeInput = 2;  // capture, external, home, ... (the panel's order)

class DaemonTraceFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("stepmod_daemon_trace_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    daemon_.reset();
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
    fs::remove_all(dir_);
  }
  std::string at(const std::string& name) const { return (dir_ / name).string(); }
  void start() {
    daemon_ = std::make_unique<DaemonProcess>(sim_3601_config("", kSim), true, "", at("a.vcd"));
  }
  // Toggles the home input `n` times through the simulator panel: n input records.
  void toggle_home(int n) {
    ipc::SimPanelClient panel(daemon_->name());
    ipc::Client image(daemon_->name());
    for (int i = 0; i < n; ++i) {
      panel.force(0, kHomeInput, i % 2 == 0);
      // The daemon takes the panel in once per control loop: each force seen before the next.
      ASSERT_TRUE(image.wait_scans(3, milliseconds(5000)));
    }
    panel.release_all(0);
  }
  // The daemon creates its image before its trace spools: wait for the spools too.
  void wait_for_spools() {
    for (int i = 0; i < 1000 && !fs::exists(at("a.vcd.in.spool")); ++i) {
      std::this_thread::sleep_for(milliseconds(10));
    }
    ASSERT_TRUE(fs::exists(at("a.vcd.in.spool")));
  }
  static std::string slurp(const std::string& path) { return slurp_file(path); }

  fs::path dir_;
  bool mounted_ = false;
  std::unique_ptr<DaemonProcess> daemon_;
};

TEST_F(DaemonTraceFiles, SymlinkAtTheTracePathExitsOneAndTheTargetIsUntouched) {
  std::ofstream(at("victim")) << "precious\n";
  fs::create_symlink(at("victim"), at("a.vcd"));
  start();
  EXPECT_EQ(daemon_->wait_exit(10'000), 1) << daemon_->log();
  EXPECT_NE(daemon_->log().find("a symbolic link"), std::string::npos) << daemon_->log();
  EXPECT_EQ(slurp(at("victim")), "precious\n");
  EXPECT_FALSE(fs::exists("/dev/shm/stepmod." + daemon_->name()));
}

TEST_F(DaemonTraceFiles, FifoAtTheSpoolPathExitsOneAtOnceInsteadOfHanging) {
  ASSERT_EQ(::mkfifo(at("a.vcd.out.spool").c_str(), 0600), 0);
  start();
  EXPECT_EQ(daemon_->wait_exit(10'000), 1) << daemon_->log();
  EXPECT_NE(daemon_->log().find("a FIFO"), std::string::npos) << daemon_->log();
  EXPECT_FALSE(fs::exists("/dev/shm/stepmod." + daemon_->name()));
}

TEST_F(DaemonTraceFiles, FifoPlantedAtTheVcdPathWhileRunningDoesNotHoldUpSigterm) {
  start();
  ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
  toggle_home(4);
  ASSERT_EQ(::mkfifo(at("a.vcd").c_str(), 0600), 0);
  EXPECT_EQ(daemon_->terminate(10'000), 0) << daemon_->log();
  const Vcd vcd = read_vcd(at("a.vcd"));
  EXPECT_EQ(vcd.rising("axis1.home").size(), 2u);
  EXPECT_FALSE(fs::exists(at("a.vcd.out.spool")));
}

// Issue 29: the VCD's temporary name was "a.vcd.tmp.<pid>.<n>", and 100 names planted in the
// trace's directory made stepmodd give up the VCD and exit 3. Links planted under those names
// now neither fail the trace nor are followed.
TEST_F(DaemonTraceFiles, LinksPlantedUnderTheOldTemporaryNamesDoNotFailTheTrace) {
  std::ofstream(at("victim")) << "precious\n";
  start();
  ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
  const std::string old = at("a.vcd.tmp." + std::to_string(daemon_->pid()) + ".");
  for (int n = 0; n < 200; ++n) {
    ASSERT_EQ(::symlink(at("victim").c_str(), (old + std::to_string(n)).c_str()), 0);
  }
  toggle_home(2);
  EXPECT_EQ(daemon_->terminate(10'000), 0) << daemon_->log();
  ASSERT_TRUE(fs::exists(at("a.vcd"))) << daemon_->log();
  const Vcd vcd = read_vcd(at("a.vcd"));
  EXPECT_EQ(vcd.rising("axis1.home").size(), 1u);
  EXPECT_EQ(slurp(at("victim")), "precious\n");
}

TEST_F(DaemonTraceFiles, KilledDaemonsSpoolsAreRecoveredWithStepmodctl) {
  start();
  ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
  toggle_home(6);
  std::this_thread::sleep_for(milliseconds(400));  // > the spools' flush period
  daemon_->signal(SIGKILL);
  daemon_->wait_exit();
  ASSERT_TRUE(fs::exists(at("a.vcd.out.spool")));
  const CtlRun r = stepmodctl("trace recover --output " + at("a.vcd") + " " +
                              at("a.vcd.out.spool") + " " + at("a.vcd.in.spool"));
  ASSERT_EQ(r.exit_status, 0) << r.out << r.err;
  const Vcd vcd = read_vcd(at("a.vcd"));
  EXPECT_EQ(vcd.rising("axis1.home").size(), 3u);
  EXPECT_NE(slurp(at("a.vcd")).find("TRACE INCOMPLETE"), std::string::npos);
  EXPECT_FALSE(fs::exists(at("a.vcd.out.spool"))) << "removed once recovered";
  // And the trace path can be used again.
  start();
  ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
  EXPECT_EQ(daemon_->terminate(), 0) << daemon_->log();
}

TEST_F(DaemonTraceFiles, FullDiskSetsHealthBit4WhileRunningAndExitsThreeKeepingTheSpools) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to mount a 256 KiB tmpfs";
  if (::mount("tmpfs", dir_.c_str(), "tmpfs", 0, "size=256k") != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs: " << std::strerror(errno);
  }
  mounted_ = true;
  start();
  ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
  wait_for_spools();
  {
    std::ofstream f(at("filler"), std::ios::binary);
    const std::string chunk(4096, 'x');
    while (fs::space(dir_).available >= chunk.size()) f << chunk << std::flush;
    for (int i = 0; i < 4096 && f; ++i) f << 'x' << std::flush;  // the last partial page too
  }
  // A move of 5,000 steps: 10,000 output records, far more than the disk has room for.
  RawShmPlc plc(daemon_->name());
  plc.configure();
  plc.command(m::cmd_msw::kRelativeMove, 5'000, 20'000, 200, 200);
  ipc::Client& client = plc.client();
  bool bit4 = false;
  for (int i = 0; i < 300 && !bit4; ++i) {
    bit4 = (client.read_health().flags & STEPMOD_HEALTH_TRACE_LOST) != 0;
    std::this_thread::sleep_for(milliseconds(10));
  }
  EXPECT_TRUE(bit4) << "health bit 4 while the daemon runs";
  EXPECT_EQ(daemon_->terminate(), 3) << daemon_->log();
  EXPECT_NE(daemon_->log().find("are kept"), std::string::npos) << daemon_->log();
  EXPECT_TRUE(fs::exists(at("a.vcd.out.spool")));
  EXPECT_TRUE(fs::exists(at("a.vcd.in.spool")));
}

}  // namespace
}  // namespace stepmod::testing
