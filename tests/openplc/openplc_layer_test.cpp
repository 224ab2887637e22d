// openplc/stepmod_hardware_layer.cpp, compiled against the stand-in of OpenPLC's ladder.h and
// driven as OpenPLC v3's main.cpp drives it (tests/openplc/openplc_runtime.hpp: start with the
// first updateBuffersIn/Out before mapUnusedIO(), scans under bufferLock, the stop with
// disableOutputs()): a PLC program written on %IW/%QW configures a real stepmodd's 3601 and runs
// a relative move; a runtime that stops stops the axis (heartbeat). On images without a daemon:
// the 3202 register split, %QW words the program does not declare (OpenPLC's Modbus registers
// behind them since mapUnusedIO()), a forced snapshot failure, and an image found at once.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "ipc/client.hpp"
#include "ipc/shm_image.hpp"
#include "ipc/sim_panel.hpp"
#include "tests/openplc/ladder.h"
#include "tests/openplc/layer_program.hpp"
#include "tests/openplc/openplc_runtime.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/sim_config.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::testing {
namespace {

namespace m = words::m3601;
using namespace m::status_msw;
using std::chrono::milliseconds;

// One OpenPLC scan, then the rest of the task's period.
template <typename Logic>
void scan(Logic&& logic) {
  openplc::scan(logic);
  std::this_thread::sleep_for(std::chrono::nanoseconds(common_ticktime__));
}

void put_split(IEC_UINT* qw, std::int32_t v) {
  const auto p = words::encode_3601(v);
  qw[0] = static_cast<IEC_UINT>(p.msw);
  qw[1] = static_cast<IEC_UINT>(p.lsw);
}

// The shipped OpenPLC example, named {NAME} for the harness.
std::string openplc_example() {
  std::ifstream f(std::string(STEPMOD_SOURCE_DIR) + "/examples/3601-openplc-sim.toml");
  std::stringstream ss;
  ss << f.rdbuf();
  std::string t = ss.str();
  const std::string from = "name = \"openplc\"";
  const auto at = t.find(from);
  if (at != std::string::npos) t.replace(at, from.size(), "name = \"{NAME}\"");
  // The late-edge guard's maximum, as in every end-to-end test that is not about it: a loaded
  // test machine must not cut the move (sim_config.hpp). The example's own values are the
  // product's defaults: the pause limit is added to [rt], the lag limit replaced by its key.
  const auto relax = [&t](const std::string& key_value, const char* relaxed) {
    const auto g = t.find(key_value);
    if (g == std::string::npos) throw std::runtime_error("example lacks '" + key_value + "'");
    t.replace(g, t.find('\n', g) + 1 - g, relaxed);
  };
  relax("[rt]", (std::string("[rt]\n") + kRelaxedLateLimit).c_str());
  relax("lag_limit_steps = 8", kRelaxedLagLimit);
  return t;
}

// A PLC program configures the 3601, runs a move and a long move; then the runtime stops.
void configure_move_and_stop(const std::string& config) {
  DaemonProcess daemon(config, false);
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  ::setenv("STEPMOD_NAME", daemon.name().c_str(), 1);
  Program prog;
  openplc::log().clear();
  openplc::start(prog.bind());
  EXPECT_NE(openplc::log().find("stepmod: found module image /dev/shm/stepmod." + daemon.name()),
            std::string::npos)
      << openplc::log();

  // The program: a step sequencer in the PLC's own terms.
  enum Step { kConfig, kCommandMode, kMove, kRelease, kDone, kLong, kLongRelease, kRunning };
  Step step = kConfig;
  std::int32_t target = 2500;
  auto logic = [&] {
    // %IW42: the layer's link bit. While it is 0 the words are not the module's (all 0): the
    // sequence waits (a loaded machine may hold up the test's daemon for 100 ms).
    if (prog.iw[42] != 1) return;
    const IEC_UINT status = prog.iw[0];
    IEC_UINT* qw = prog.qw;
    switch (step) {
      case kConfig:
        qw[0] = m::cfg_msw::kConfigMode | m::cfg_msw::kCaptureUsed | m::cfg_msw::kExternalUsed |
                m::cfg_msw::kHomeUsed | m::cfg_msw::kEStopUsed | m::cfg_msw::kCwLimitUsed |
                m::cfg_msw::kCcwLimitUsed | m::cfg_msw::kQuadratureEncoder |
                m::cfg_msw::kStepDirOutput;
        qw[1] = 0x3F;
        put_split(qw + 2, 1000);
        if (status & kConfigMode) step = kCommandMode;
        break;
      case kCommandMode:
        for (unsigned i = 0; i < 8; ++i) qw[i] = 0;
        if (!(status & kConfigMode)) step = kMove;
        break;
      case kMove:
      case kLong:
        qw[0] = m::cmd_msw::kRelativeMove;
        put_split(qw + 2, target);
        put_split(qw + 4, 10'000);
        qw[6] = 10;
        qw[7] = 10;
        if (status & (kMovingCw | kMovingCcw)) step = step == kMove ? kRelease : kLongRelease;
        break;
      case kRelease:
        qw[0] = 0;
        if ((status & kMoveComplete) && !(status & (kMovingCw | kMovingCcw))) step = kDone;
        break;
      case kLongRelease:
        qw[0] = 0;
        step = kRunning;
        break;
      case kDone:
      case kRunning:
        break;
    }
  };
  const std::int64_t start = ipc::SimPanelClient(daemon.name()).read(0).position;
  for (int i = 0; i < 2000 && step != kDone; ++i) scan(logic);
  ASSERT_EQ(step, kDone) << "status " << std::hex << prog.iw[0];
  EXPECT_EQ(words::decode_3601_report(static_cast<std::int16_t>(prog.iw[2]),
                                      static_cast<std::int16_t>(prog.iw[3])),
            start + 2500);
  EXPECT_EQ(ipc::SimPanelClient(daemon.name()).read(0).position, start + 2500);
  // Header registers through %IW32..: type, word size, word counts; a running scan counter.
  EXPECT_EQ(prog.iw[32], 3601);
  EXPECT_EQ(prog.iw[33], 2);
  EXPECT_EQ(prog.iw[34], 8);
  EXPECT_EQ(prog.iw[35], 8);
  const IEC_UINT scans = prog.iw[36];
  scan(logic);
  EXPECT_NE(prog.iw[36], scans);

  // A long move, then the runtime is stopped (main.cpp: disableOutputs(), updateBuffersOut(),
  // finalizeHardware()): the zeros stop nothing, the heartbeat that stops with it does.
  target = 400'000;
  step = kLong;
  for (int i = 0; i < 400 && step != kRunning; ++i) scan(logic);
  ASSERT_EQ(step, kRunning);
  for (int i = 0; i < 120; ++i) scan(logic);  // 0.6 s of scans: beyond the timeout, still moving
  ASSERT_NE(prog.iw[0] & (kMovingCw | kMovingCcw), 0);
  openplc::stop();
  ipc::Client watch(daemon.name());
  ImageWords in;
  const auto end = std::chrono::steady_clock::now() + milliseconds(3000);
  bool stopped = false;
  while (!stopped && std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(milliseconds(20));
    ASSERT_TRUE(watch.read_inputs(in));
    stopped = (in.w[0] & (kMovingCw | kMovingCcw)) == 0;
  }
  EXPECT_TRUE(stopped);
  EXPECT_NE(in.w[0] & kPositionInvalid, 0);
  EXPECT_EQ(daemon.terminate(), 0) << daemon.log();
}

TEST(OpenPlcLayer, ProgramConfiguresAndMovesA3601ThenAStoppedRuntimeStopsIt) {
  configure_move_and_stop(sim_3601_config("plc_timeout_ms = 300\n",
                                          "cw_limit_at = 1000000\nccw_limit_at = -1000000\n"));
}

// With the shipped example (plc_timeout_ms set), stopping the program in OpenPLC stops the axis.
TEST(OpenPlcLayer, ShippedExampleConfigStopsTheAxisWhenTheRuntimeStops) {
  const std::string config = openplc_example();
  ASSERT_NE(config.find("\nplc_timeout_ms = "), std::string::npos) << config;
  configure_move_and_stop(config);
}

TEST(OpenPlcLayer, NoDaemonMeansNoLinkAndZeroInputs) {
  ::setenv("STEPMOD_NAME", "openplc-absent", 1);
  Program prog;
  prog.iw[0] = 0x1234;
  prog.iw[42] = 7;
  openplc::log().clear();
  openplc::start(prog.bind());
  EXPECT_NE(openplc::log().find("no module image /dev/shm/stepmod.openplc-absent"),
            std::string::npos);
  EXPECT_EQ(prog.iw[0], 0);
  EXPECT_EQ(prog.iw[42], 0);
  openplc::scan([] {});
  openplc::stop();  // nothing to write to: must not fail
}

TEST(OpenPlcLayer, ThirtyTwoBitWordsOfA3202AreTwoRegistersHighHalfFirst) {
  const std::string name = "openplc-3202-" + std::to_string(::getpid());
  ipc::ShmImage image(name, shape_of(ModuleType::k3202));
  ImageWords in{};
  in.w[0] = 0x12345678;
  in.w[15] = -2;
  image.publish_inputs(in, ipc::Health{.flags = 0x00010002u, .late_faults = 3});
  ::setenv("STEPMOD_NAME", name.c_str(), 1);
  IEC_UINT iw[48] = {};
  IEC_UINT qw[32] = {};
  openplc::start([&] {
    for (unsigned i = 0; i < 48; ++i) int_input[i] = &iw[i];
    for (unsigned i = 0; i < 32; ++i) int_output[i] = &qw[i];
  });
  EXPECT_EQ(iw[42], 0) << "a count seen once is no sign of a module scanning";
  image.publish_inputs(in, ipc::Health{.flags = 0x00010002u, .late_faults = 3});
  openplc::scan([] {});
  EXPECT_EQ(iw[0], 0x1234);
  EXPECT_EQ(iw[1], 0x5678);
  EXPECT_EQ(iw[30], 0xFFFF);
  EXPECT_EQ(iw[31], 0xFFFE);
  EXPECT_EQ(iw[32], 3202);
  EXPECT_EQ(iw[33], 4);
  EXPECT_EQ(iw[34], 16);
  EXPECT_EQ(iw[36], 2);  // two publications
  EXPECT_EQ(iw[38], 2);  // health low
  EXPECT_EQ(iw[39], 1);  // health high
  EXPECT_EQ(iw[40], 3);  // late-edge faults
  EXPECT_EQ(iw[42], 1);
  qw[0] = 0x89AB;
  qw[1] = 0xCDEF;
  qw[31] = 0x0001;
  const std::uint64_t hb = image.heartbeat();
  updateBuffersOut();
  ImageWords out;
  ASSERT_TRUE(image.read_outputs(out));
  EXPECT_EQ(static_cast<std::uint32_t>(out.w[0]), 0x89ABCDEFu);
  EXPECT_EQ(out.w[15], 1);
  EXPECT_EQ(image.heartbeat(), hb + 1);
  finalizeHardware();
  openplc::reset();
}

// Real OpenPLC binds every %QW the program does not declare to its Modbus holding registers
// (mapUnusedIO()): a Modbus client of OpenPLC once put a 3601 into configuration mode through
// %QW0 of a program that never wrote it.
TEST(OpenPlcLayer, QwTheProgramDoesNotDeclareIsNeverDrivenFromOpenPlcsModbusRegisters) {
  ImageRig rig;
  ::setenv("STEPMOD_NAME", rig.name.c_str(), 1);
  rig.prog.qw_first = 2;  // declares %QW2..%QW7 only
  openplc::start(rig.prog.bind());
  pthread_mutex_lock(&bufferLock);  // as OpenPLC's Modbus slave thread writes
  mb_holding_regs[0] = m::cfg_msw::kConfigMode;
  mb_holding_regs[1] = 0x3F;
  pthread_mutex_unlock(&bufferLock);
  openplc::scan([&] { rig.prog.qw[2] = 1234; });
  ImageWords out;
  ASSERT_TRUE(rig.image.read_outputs(out));
  EXPECT_EQ(out.w[0], 0) << "%QW0 is not the program's: 0, not OpenPLC's holding register 0";
  EXPECT_EQ(out.w[1], 0);
  EXPECT_EQ(out.w[2], 1234);
  openplc::stop();
}

// A snapshot that fails (the module caught publishing on every try: here its sequence held odd
// while its scan counter goes on) keeps the last good words and the link; only failed tries for
// longer than the layer's 100 ms drop them. Counted from the first failed try: a runtime held up
// for longer than that between two scans (a loaded machine; here a 150 ms sleep) is not cut off
// by one failure after it.
TEST(OpenPlcLayer, FailedSnapshotKeepsTheLastGoodWordsAndTheLinkUntilARealLoss) {
  ImageRig rig;
  ::setenv("STEPMOD_NAME", rig.name.c_str(), 1);
  rig.publish(0x1234);
  openplc::start(rig.prog.bind());
  rig.scan();
  ASSERT_EQ(rig.prog.iw[0], 0x1234);
  ASSERT_EQ(rig.prog.iw[42], 1);
  std::this_thread::sleep_for(milliseconds(150));  // the runtime's scan thread held up
  const std::uint32_t seq = __atomic_load_n(&rig.raw().input_seq, __ATOMIC_ACQUIRE);
  __atomic_store_n(&rig.raw().input_seq, seq + 1, __ATOMIC_RELEASE);  // a writer "inside"
  rig.tick();
  openplc::scan([] {});
  EXPECT_EQ(rig.prog.iw[0], 0x1234) << "the last good words, not zeros";
  EXPECT_EQ(rig.prog.iw[42], 1) << "one failed snapshot is not a lost link";
  std::this_thread::sleep_for(milliseconds(150));
  rig.tick();
  openplc::scan([] {});
  EXPECT_EQ(rig.prog.iw[42], 0) << "no good snapshot for 150 ms: the link is lost";
  EXPECT_EQ(rig.prog.iw[0], 0);
  __atomic_store_n(&rig.raw().input_seq, seq + 2, __ATOMIC_RELEASE);
  rig.tick();
  openplc::scan([] {});
  EXPECT_EQ(rig.prog.iw[42], 1);
  EXPECT_EQ(rig.prog.iw[0], 0x1234);
  openplc::stop();
}

// The layer looks for the image on every scan: a daemon started after the runtime is found on
// the next scan, well inside any plc_timeout_ms (it was once a second), and linked as soon as
// its scan counter is seen to advance.
TEST(OpenPlcLayer, ImageCreatedAfterTheStartIsFoundOnTheNextScan) {
  const std::string name = "openplc-late-" + std::to_string(::getpid());
  ::setenv("STEPMOD_NAME", name.c_str(), 1);
  Program prog;
  openplc::start(prog.bind());
  EXPECT_EQ(prog.iw[42], 0);
  ipc::ShmImage image(name, shape_of(ModuleType::k3601));
  ImageWords in{};
  in.w[1] = 77;
  image.publish_inputs(in, ipc::Health{});
  const std::uint64_t hb = image.heartbeat();
  openplc::scan([] {});
  EXPECT_EQ(image.heartbeat(), hb + 1) << "its heartbeat from that scan on";
  image.publish_inputs(in, ipc::Health{});
  openplc::scan([] {});
  EXPECT_EQ(prog.iw[42], 1);
  EXPECT_EQ(prog.iw[1], 77);
  openplc::stop();
}

}  // namespace
}  // namespace stepmod::testing
