// openplc/stepmod_hardware_layer.cpp, compiled against the stand-in of OpenPLC's ladder.h and
// driven by OpenPLC's scan cycle (main.cpp: updateBuffersIn; lock; program; unlock;
// updateBuffersOut): a PLC program written on %IW/%QW configures a real stepmodd's 3601 and runs
// a relative move; a runtime that stops scanning stops the axis (heartbeat). The 3202 register
// split is checked on an image without a daemon.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "ipc/client.hpp"
#include "ipc/codec.hpp"
#include "ipc/shm_image.hpp"
#include "ipc/sim_panel.hpp"
#include "module/m3601/words_3601.hpp"
#include "tests/openplc/ladder.h"
#include "tests/support/daemon_process.hpp"
#include "tests/support/sim_config.hpp"

// ---- what OpenPLC's glueVars.cpp, main.cpp and utils.cpp define --------------------------------
IEC_BOOL* bool_input[BUFFER_SIZE][8];
IEC_BOOL* bool_output[BUFFER_SIZE][8];
IEC_BYTE* byte_input[BUFFER_SIZE];
IEC_BYTE* byte_output[BUFFER_SIZE];
IEC_UINT* int_input[BUFFER_SIZE];
IEC_UINT* int_output[BUFFER_SIZE];
IEC_UDINT* dint_input[BUFFER_SIZE];
IEC_UDINT* dint_output[BUFFER_SIZE];
IEC_ULINT* lint_input[BUFFER_SIZE];
IEC_ULINT* lint_output[BUFFER_SIZE];
IEC_UINT* int_memory[BUFFER_SIZE];
IEC_UDINT* dint_memory[BUFFER_SIZE];
IEC_ULINT* lint_memory[BUFFER_SIZE];
IEC_ULINT* special_functions[BUFFER_SIZE];
pthread_mutex_t bufferLock = PTHREAD_MUTEX_INITIALIZER;
unsigned long long common_ticktime__ = 5'000'000;  // 5 ms task

namespace {
std::string g_log;
}
extern "C" void openplc_log(char* logmsg) {
  g_log += logmsg;
}

namespace stepmod::testing {
namespace {

namespace m = module::m3601;
using namespace m::status_msw;
using std::chrono::milliseconds;

// The PLC program's located variables, bound as glueVars() binds them. Some addresses are left
// unbound (NULL) on purpose: the layer must skip them.
struct Program {
  IEC_UINT iw[48] = {};
  IEC_UINT qw[8] = {};
  Program() {
    for (auto& p : int_input) p = nullptr;
    for (auto& p : int_output) p = nullptr;
    for (unsigned i = 0; i < 6; ++i) int_input[i] = &iw[i];  // %IW6, %IW7 (capture): unused
    for (unsigned i = 32; i < 43; ++i) int_input[i] = &iw[i];
    for (unsigned i = 0; i < 8; ++i) int_output[i] = &qw[i];
  }
  ~Program() {
    for (auto& p : int_input) p = nullptr;
    for (auto& p : int_output) p = nullptr;
  }
};

// One OpenPLC scan, as main.cpp runs it.
template <typename Logic>
void scan(Logic&& logic) {
  updateBuffersIn();
  pthread_mutex_lock(&bufferLock);
  logic();
  pthread_mutex_unlock(&bufferLock);
  updateBuffersOut();
  std::this_thread::sleep_for(std::chrono::nanoseconds(common_ticktime__));
}

void put_split(IEC_UINT* qw, std::int32_t v) {
  const auto p = ipc::codec::encode_3601(v);
  qw[0] = static_cast<IEC_UINT>(p.msw);
  qw[1] = static_cast<IEC_UINT>(p.lsw);
}

TEST(OpenPlcLayer, ProgramConfiguresAndMovesA3601ThenAStoppedRuntimeStopsIt) {
  DaemonProcess daemon(
      sim_3601_config("plc_timeout_ms = 300\n", "cw_limit_at = 1000000\nccw_limit_at = -1000000\n"),
      false);
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();
  ::setenv("STEPMOD_NAME", daemon.name().c_str(), 1);
  Program prog;
  g_log.clear();
  initializeHardware();
  EXPECT_NE(g_log.find("stepmod: linked to /dev/shm/stepmod." + daemon.name()), std::string::npos)
      << g_log;

  // The program: a step sequencer in the PLC's own terms.
  enum Step { kConfig, kCommandMode, kMove, kRelease, kDone, kLong, kLongRelease, kRunning };
  Step step = kConfig;
  std::int32_t target = 2500;
  auto logic = [&] {
    const IEC_UINT status = prog.iw[0];
    IEC_UINT* qw = prog.qw;
    switch (step) {
      case kConfig:
        if (prog.iw[42] != 1) return;  // %IW42: the layer's link bit
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
  EXPECT_EQ(ipc::codec::decode_3601_report(static_cast<std::int16_t>(prog.iw[2]),
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

  // A long move, then the runtime stops calling the layer: the heartbeat stops with it.
  target = 400'000;
  step = kLong;
  for (int i = 0; i < 400 && step != kRunning; ++i) scan(logic);
  ASSERT_EQ(step, kRunning);
  for (int i = 0; i < 120; ++i) scan(logic);  // 0.6 s of scans: twice the timeout, still moving
  ASSERT_NE(prog.iw[0] & (kMovingCw | kMovingCcw), 0);
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
  finalizeHardware();
  EXPECT_EQ(daemon.terminate(), 0) << daemon.log();
}

TEST(OpenPlcLayer, NoDaemonMeansNoLinkAndZeroInputs) {
  ::setenv("STEPMOD_NAME", "openplc-absent", 1);
  Program prog;
  prog.iw[0] = 0x1234;
  prog.iw[42] = 7;
  g_log.clear();
  initializeHardware();
  EXPECT_NE(g_log.find("no module image /dev/shm/stepmod.openplc-absent"), std::string::npos);
  updateBuffersIn();
  EXPECT_EQ(prog.iw[0], 0);
  EXPECT_EQ(prog.iw[42], 0);
  updateBuffersOut();  // nothing to write to: must not fail
  finalizeHardware();
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
  for (unsigned i = 0; i < 48; ++i) int_input[i] = &iw[i];
  for (unsigned i = 0; i < 32; ++i) int_output[i] = &qw[i];
  initializeHardware();
  updateBuffersIn();
  EXPECT_EQ(iw[0], 0x1234);
  EXPECT_EQ(iw[1], 0x5678);
  EXPECT_EQ(iw[30], 0xFFFF);
  EXPECT_EQ(iw[31], 0xFFFE);
  EXPECT_EQ(iw[32], 3202);
  EXPECT_EQ(iw[33], 4);
  EXPECT_EQ(iw[34], 16);
  EXPECT_EQ(iw[36], 1);  // one publication
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
  for (auto& p : int_input) p = nullptr;
  for (auto& p : int_output) p = nullptr;
}

}  // namespace
}  // namespace stepmod::testing
