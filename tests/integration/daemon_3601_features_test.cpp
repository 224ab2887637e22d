// End to end, the 3601 features of issue #3 on the real daemon: driven through shared memory
// with the PLC-side library stepmodctl uses (module_types/m3601/plc_3601.hpp) and through the simulator
// panel, checked through the status image, the panel's motor position and the VCD trace.
#include <gtest/gtest.h>

#include <chrono>

#include "ipc/client.hpp"
#include "ipc/sim_panel.hpp"
#include "module_types/m3601/plc_3601.hpp"
#include "plc/shm_port.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/sim_config.hpp"
#include "tests/support/vcd_reader.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::testing {
namespace {

namespace m = words::m3601;
using namespace m::status_msw;
using plc::Profile;
using plc::m3601::decode_status;
using std::chrono::milliseconds;

constexpr const char* kSim = R"(start_position = -3000
cw_limit_at = 200000
ccw_limit_at = -200000
home_from = 5000
home_to = 5100
encoder_ratio = 1.0
marker_every = 4000
)";

constexpr std::uint16_t kConfigBits = m::cfg_msw::kCaptureUsed | m::cfg_msw::kExternalUsed |
                                      m::cfg_msw::kHomeUsed | m::cfg_msw::kEStopUsed |
                                      m::cfg_msw::kCwLimitUsed | m::cfg_msw::kCcwLimitUsed |
                                      m::cfg_msw::kQuadratureEncoder | m::cfg_msw::kStepDirOutput;

class Daemon3601Features : public ::testing::Test {
 protected:
  void SetUp() override {
    daemon_ = std::make_unique<DaemonProcess>(sim_3601_config("", kSim));
    ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
    client_ = std::make_unique<ipc::Client>(daemon_->name());
    port_ = std::make_unique<plc::ShmPort>(*client_, milliseconds(3000));
    plc_ = std::make_unique<plc::Plc3601>(*port_, milliseconds(3000));
    ASSERT_TRUE(plc_->configure(kConfigBits, 0x3F, 1'000).ok);
  }
  std::uint16_t msw() { return decode_status(plc_->status().in).msw; }
  std::uint16_t lsw() { return decode_status(plc_->status().in).lsw; }
  // Waits (as the PLC, heartbeat included) until one of `msw_bits` is set, or not, at most 20 s.
  void wait_msw(std::uint16_t msw_bits, bool set) {
    port_->wait_inputs([&](const ImageWords& in) { return decode_status(in).has(msw_bits) == set; },
                       std::chrono::seconds(20));
  }
  Vcd stop_and_read_trace() {
    plc_.reset();
    port_.reset();
    client_.reset();
    EXPECT_EQ(daemon_->terminate(), 0) << daemon_->log();
    return read_vcd(daemon_->trace_path());
  }

  std::unique_ptr<DaemonProcess> daemon_;
  std::unique_ptr<ipc::Client> client_;
  std::unique_ptr<plc::ShmPort> port_;
  std::unique_ptr<plc::Plc3601> plc_;
};

TEST_F(Daemon3601Features, AH_01_FindHomeThroughSharedMemory) {
  // Home switch 5,000..5,100, motor at -3,000: search +, decelerate, 2 s, back off, 2 s, creep.
  ASSERT_TRUE(plc_->home(true, Profile{10'000, 50, 50}).ok);
  // As a PLC does: the moving bits are clear during the 2-s pauses, so wait for the outcome.
  wait_msw(kAtHome | kHomeInvalid | kInputError, true);
  EXPECT_TRUE(msw() & kAtHome);
  EXPECT_FALSE(msw() & kPositionInvalid);
  EXPECT_FALSE(msw() & kHomeInvalid);
  EXPECT_EQ(decode_status(plc_->status().in).position, 0);
  EXPECT_EQ(decode_status(plc_->status().in).encoder, 0);
  ipc::SimPanelClient panel(daemon_->name());
  // The creep approaches the switch from below: the motor stops on its lower edge. The stop is
  // the control thread's answer to the home edge; at the creep speed (Vs = 1,000 steps/s) an
  // answer later than 1 ms, which a loaded two-core VM gives now and then, lets one more step
  // out. The module's zero is where the motor came to rest either way (position 0 above).
  EXPECT_GE(panel.read(0).position, 5'000);
  EXPECT_LE(panel.read(0).position, 5'001);
  stop_and_read_trace();
}

TEST_F(Daemon3601Features, MC_01_BlendProgrammedWithTheHandshakeRunsItsLength) {
  plc::BlendProfile b;
  b.segments = {{10'000, 5'000, 10}, {10'000, 8'000, 10}};  // blend, 3601 manual ch. 4-5
  b.final_decel = 10;
  ASSERT_TRUE(plc_->blend_program(b).ok);
  ASSERT_TRUE(plc_->preset_position(0).ok);
  ASSERT_TRUE(plc_->blend_run(false).ok);
  EXPECT_TRUE(lsw() & m::status_lsw::kBlendRunning);
  ASSERT_TRUE(plc_->wait_idle(milliseconds(20'000)).ok);
  EXPECT_TRUE(msw() & kMoveComplete);
  EXPECT_EQ(decode_status(plc_->status().in).position, -20'000);
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising("axis1.step").size(), 20'000u);
}

TEST_F(Daemon3601Features, Registration_PanelExternalEdgeGivesExactlyTheCount) {
  ASSERT_TRUE(plc_->preset_position(0).ok);
  // Manual + with a registration count of 3,000 (>= the 1,200 steps needed to stop from 5,000).
  port_->write_outputs(plc::m3601::command_words(m::cmd_msw::kManualCw, 0, 3'000, 5'000, 10, 10));
  port_->pass(milliseconds(700));
  ipc::SimPanelClient panel(daemon_->name());
  panel.force(0, 1, true);  // bit 1: External, active high
  port_->wait_inputs([](const ImageWords& in) { return !decode_status(in).moving(); },
                     std::chrono::seconds(10));
  port_->update_outputs([](ImageWords& o) { o.w[m::out_word::kMsw] = 0; });
  EXPECT_TRUE(msw() & kStopped);
  EXPECT_FALSE(msw() & (kCommandError | kInvalidProfile | kPositionInvalid));
  panel.release(0, 1);
  const Vcd vcd = stop_and_read_trace();
  // Exactly 3,000 steps after the External edge (as the kernel/sim stamped it in the trace).
  const auto& ext = vcd.wires.at("axis1.external");
  std::int64_t edge = -1;
  for (const VcdChange& c : ext) {
    if (c.level == 1) {
      edge = c.t;
      break;
    }
  }
  ASSERT_GE(edge, 0);
  std::size_t after = 0;
  for (std::int64_t t : vcd.rising("axis1.step")) after += t > edge ? 1 : 0;
  EXPECT_EQ(after, 3'000u);
}

}  // namespace
}  // namespace stepmod::testing
