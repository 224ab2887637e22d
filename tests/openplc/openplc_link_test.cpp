// The layer's link word %IW42 (openplc/README.md): 1 only while a stepmodd is scanning the image
// -- it has published it at least once and its scan counter advanced within the last 100 ms --,
// else 0 with every %IW at its link-down value 0. Found with the real OpenPLC v3 (issue 29): at
// every stepmodd start the program saw link 1 with all-zero words (the image exists, magic and
// all, before the first publication), and a SIGSTOPped or SIGKILLed stepmodd left link 1 with
// frozen words. Also: the error reasons' item codes reach %IW43..%IW46, as Modbus serves them.
#include <gtest/gtest.h>
#include <signal.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>

#include "ipc/modbus_map.hpp"
#include "tests/openplc/layer_program.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/sim_config.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::testing {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;
constexpr std::uint16_t kModuleOk = words::m3601::status_msw::kModuleOk;

// The layer's rule, and what this test allows on top of it for its own scans coming late on a
// loaded machine (the lower bound is the layer's own and exact; see FrozenScanCounter...).
constexpr milliseconds kLinkLoss{100};
constexpr milliseconds kSlack{400};

std::string sim_config() {
  return sim_3601_config("", "cw_limit_at = 1000000\nccw_limit_at = -1000000\n");
}

long ms_between(Clock::time_point a, Clock::time_point b) {
  return static_cast<long>(std::chrono::duration_cast<milliseconds>(b - a).count());
}

// Scans the runtime about every millisecond (a 1 ms task) until its link is `want`: the
// milliseconds that took, or -1 if not within `limit`.
long scan_until(const Program& prog, bool want, milliseconds limit) {
  const Clock::time_point start = Clock::now();
  for (;;) {
    openplc::scan([] {});
    if (prog.linked() == want) return ms_between(start, Clock::now());
    if (Clock::now() - start > limit) return -1;
    std::this_thread::sleep_for(milliseconds(1));
  }
}

// The link-down values: every %IW the program reads is 0 but the link word's own.
void expect_link_down_values(const Program& prog) {
  EXPECT_EQ(prog.iw[42], 0);
  for (unsigned i : {0u, 1u, 2u, 3u, 32u, 33u, 36u, 38u, 43u, 44u}) {
    EXPECT_EQ(prog.iw[i], 0) << "%IW" << i;
  }
}

// ---- on an image without a daemon (the test publishes) ----------------------------------------

// stepmodd creates its image, magic and header included, before its first scan publishes it.
TEST(OpenPlcLink, AnImageNotYetPublishedIsNoLink) {
  ImageRig rig;
  ::setenv("STEPMOD_NAME", rig.name.c_str(), 1);
  rig.prog.iw[42] = 7;
  openplc::start(rig.prog.bind());
  for (int i = 0; i < 20; ++i) {
    openplc::scan([] {});
    expect_link_down_values(rig.prog);
    std::this_thread::sleep_for(milliseconds(1));
  }
  rig.in.w[0] = kModuleOk;
  rig.scan();
  EXPECT_EQ(rig.prog.iw[42], 1) << "the first publication links";
  EXPECT_EQ(rig.prog.iw[0], kModuleOk);
  EXPECT_EQ(rig.prog.iw[32], 3601);
  EXPECT_EQ(rig.prog.iw[36], 1);
  openplc::stop();
}

// A module that stops scanning (the words stay, the counter freezes) is no link 100 ms after the
// layer last saw its counter advance -- never sooner -- and linked again on its next scan.
TEST(OpenPlcLink, FrozenScanCounterIsNoLinkAfter100msAndTheNextScanLinksAgain) {
  ImageRig rig;
  ::setenv("STEPMOD_NAME", rig.name.c_str(), 1);
  rig.in.w[0] = 0x4321;
  openplc::start(rig.prog.bind());
  rig.scan();
  ASSERT_EQ(rig.prog.iw[42], 1);
  const Clock::time_point before = Clock::now();
  rig.scan();  // the last advance the layer sees, between `before` and `after`
  const Clock::time_point after = Clock::now();
  ASSERT_EQ(rig.prog.iw[42], 1);
  ASSERT_EQ(rig.prog.iw[0], 0x4321);
  EXPECT_GE(scan_until(rig.prog, false, milliseconds(3000)), 0);
  const Clock::time_point down = Clock::now();
  EXPECT_GE(ms_between(before, down), kLinkLoss.count()) << "not before 100 ms";
  EXPECT_LE(ms_between(after, down), (kLinkLoss + kSlack).count());
  expect_link_down_values(rig.prog);
  rig.scan();
  EXPECT_EQ(rig.prog.iw[42], 1);
  EXPECT_EQ(rig.prog.iw[0], 0x4321);
  openplc::stop();
}

// %IW43..%IW46 hold what Modbus serves at input registers 1016..1019 (docs/interface.md 3.4, 6):
// the item codes of axis 1 and 2, high half first.
TEST(OpenPlcLink, ReasonItemCodesReachIw43To46AsModbusServesThem) {
  ImageRig rig(ModuleType::k3602, "reasons");
  stepmod_reason_t r1{};
  r1.seq = 1;
  r1.item = 20205;  // 3602-CE-05
  std::strncpy(r1.text, "3602-CE-05: test", sizeof r1.text - 1);
  stepmod_reason_t r2 = r1;
  r2.item = 0x00012345;  // not a real code: shows the high half goes to its own register
  rig.image.set_reason(0, r1);
  rig.image.set_reason(1, r2);
  ::setenv("STEPMOD_NAME", rig.name.c_str(), 1);
  openplc::start(rig.prog.bind());
  rig.scan();
  ASSERT_EQ(rig.prog.iw[42], 1);
  EXPECT_EQ(rig.prog.iw[43], 0);
  EXPECT_EQ(rig.prog.iw[44], 20205);
  EXPECT_EQ(rig.prog.iw[45], 1);
  EXPECT_EQ(rig.prog.iw[46], 0x2345);
  EXPECT_EQ(rig.prog.iw[47], 0) << "reserved";
  ipc::ModbusMap map(rig.raw(), false);
  const std::array<std::uint8_t, 5> pdu{ipc::modbus_fc::kReadInput, 1016 >> 8, 1016 & 0xFF, 0, 4};
  const ipc::ModbusResult r = map.handle(pdu);
  ASSERT_EQ(r.exception, ipc::ModbusException::kNone);
  for (unsigned i = 0; i < 4; ++i) EXPECT_EQ(rig.prog.iw[43 + i], r.values[i]) << i;
  openplc::stop();
}

// ---- with a real stepmodd ---------------------------------------------------------------------

// A runtime polling hard while stepmodd starts never sees link 1 before the module's first
// publication: when it does, Module OK is set and the scan counter is past 0. Several starts.
TEST(OpenPlcLink, StartingDaemonIsNoLinkBeforeItsFirstPublication) {
  for (int round = 0; round < 3; ++round) {
    const std::string name =
        "openplc-start-" + std::to_string(::getpid()) + "-" + std::to_string(round);
    ::setenv("STEPMOD_NAME", name.c_str(), 1);
    Program prog;
    openplc::start(prog.bind());
    DaemonProcess daemon(sim_config(), DaemonOptions{false, name});
    int linked_scans = 0;
    int bad = 0;
    const Clock::time_point end = Clock::now() + milliseconds(10'000);
    while (linked_scans < 50 && Clock::now() < end) {
      openplc::scan([] {});
      if (prog.linked()) {
        ++linked_scans;
        const bool counted = prog.iw[36] != 0 || prog.iw[37] != 0;
        if ((prog.iw[0] & kModuleOk) == 0 || !counted) ++bad;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    EXPECT_EQ(linked_scans, 50) << "round " << round << ": " << daemon.log();
    EXPECT_EQ(bad, 0) << "round " << round << ": link 1 with words not yet published";
    openplc::stop();
    EXPECT_EQ(daemon.terminate(), 0) << daemon.log();
  }
}

// A stopped daemon (SIGSTOP: a debugger, a frozen machine) is no link within 100 ms, and its
// link is back when it runs again (SIGCONT).
TEST(OpenPlcLink, StoppedDaemonIsNoLinkWithin100msAndLinkedAgainWhenItContinues) {
  DaemonProcess daemon(sim_config(), false);
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  ::setenv("STEPMOD_NAME", daemon.name().c_str(), 1);
  Program prog;
  openplc::start(prog.bind());
  ASSERT_GE(scan_until(prog, true, milliseconds(5000)), 0);
  daemon.signal(SIGSTOP);
  const long down_ms = scan_until(prog, false, milliseconds(3000));
  ::testing::Test::RecordProperty("link_down_ms", static_cast<int>(down_ms));
  EXPECT_GE(down_ms, 0) << "a stopped daemon still reads as linked";
  EXPECT_LE(down_ms, (kLinkLoss + kSlack).count());
  expect_link_down_values(prog);
  daemon.signal(SIGCONT);
  EXPECT_GE(scan_until(prog, true, milliseconds(3000)), 0) << "the link comes back";
  EXPECT_NE(prog.iw[0] & kModuleOk, 0);
  openplc::stop();
  EXPECT_EQ(daemon.terminate(), 0) << daemon.log();
}

// A killed daemon (SIGKILL: its image stays until a new daemon replaces it) is no link within
// 100 ms; the daemon started in its place is linked.
TEST(OpenPlcLink, KilledDaemonIsNoLinkWithin100msAndItsReplacementIsLinked) {
  DaemonProcess first(sim_config(), false);
  const std::string name = first.name();
  ASSERT_TRUE(first.wait_ready()) << first.log();
  ::setenv("STEPMOD_NAME", name.c_str(), 1);
  Program prog;
  openplc::start(prog.bind());
  ASSERT_GE(scan_until(prog, true, milliseconds(5000)), 0);
  first.signal(SIGKILL);
  const long down_ms = scan_until(prog, false, milliseconds(3000));
  ::testing::Test::RecordProperty("link_down_ms", static_cast<int>(down_ms));
  EXPECT_GE(down_ms, 0) << "a killed daemon's image still reads as linked";
  EXPECT_LE(down_ms, (kLinkLoss + kSlack).count());
  expect_link_down_values(prog);
  first.wait_exit();
  EXPECT_TRUE(std::filesystem::exists("/dev/shm/stepmod." + name)) << "the dead daemon's image";
  DaemonProcess second(sim_config(), DaemonOptions{false, name});
  ASSERT_TRUE(second.wait_ready()) << second.log();
  EXPECT_GE(scan_until(prog, true, milliseconds(3000)), 0) << "linked to the new daemon";
  EXPECT_NE(prog.iw[0] & kModuleOk, 0);
  openplc::stop();
  EXPECT_EQ(second.terminate(), 0) << second.log();
}

}  // namespace
}  // namespace stepmod::testing
