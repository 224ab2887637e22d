// End to end, the 3202 on the real daemon: both channels driven through shared memory with the
// PLC-side library (module_types/m3202/plc_3202.hpp), the blend message through the image's mailbox, checked
// through the status image and the VCD trace (exact pulse counts per channel).
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <iterator>

#include "ipc/client.hpp"
#include "ipc/sim_panel.hpp"
#include "module_types/m3202/plc_3202.hpp"
#include "plc/shm_port.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/sim_config.hpp"
#include "tests/support/vcd_reader.hpp"
#include "module_types/m3202/words_3202.hpp"

namespace stepmod::testing {
namespace {

namespace m = words::m3202;
namespace sb = m::status_bit;
using plc::m3202::decode_status;
using std::chrono::milliseconds;

// Two channels with every line wired (1..11, 12..22) and the same machine, with the simulated
// machine's default event FIFO (gpio::kDefaultSimEventRing: the tests run on loaded machines as
// the product does).
std::string config_3202() {
  const std::string sim =
      "cw_limit_at = 200000\nccw_limit_at = -200000\nhome_from = 5000\nhome_to = 5100\n"
      "encoder_ratio = 1.0\n";
  return sim_module_tables("3202") + sim_axis(every_axis_line(1), sim) +
         sim_axis(every_axis_line(12), sim);
}

constexpr std::uint32_t kBits = m::cfg_bit::kHomeUsed | m::cfg_bit::kCwLimitUsed |
                                m::cfg_bit::kCcwLimitUsed | m::cfg_bit::kQuadratureEncoder |
                                m::cfg_bit::kStepDirOutput | m::cfg_bit::kActiveLevels;
constexpr plc::Profile kProfile{.speed = 10'000, .accel = 50'000, .decel = 50'000};

class Daemon3202 : public ::testing::Test {
 protected:
  void SetUp() override {
    daemon_ = std::make_unique<DaemonProcess>(config_3202());
    ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
    client_ = std::make_unique<ipc::Client>(daemon_->name());
    port_ = std::make_unique<plc::ShmPort>(*client_, milliseconds(3000));
    plc_ = std::make_unique<plc::Plc3202>(*port_, milliseconds(3000));
    ASSERT_TRUE(plc_->configure(0, kBits, 1'000).ok);
    ASSERT_TRUE(plc_->configure(1, kBits, 1'000).ok);
  }
  plc::m3202::Status st(unsigned ch) { return decode_status(plc_->status(ch).in, ch); }
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
  std::unique_ptr<plc::Plc3202> plc_;
};

TEST_F(Daemon3202, BothChannelsMoveAtOnceWithExactPulseCounts) {
  ASSERT_TRUE(plc_->move(0, false, 25'000, kProfile).ok);
  ASSERT_TRUE(plc_->move(1, false, -17'000, kProfile).ok);
  EXPECT_TRUE(st(0).moving());
  EXPECT_TRUE(st(1).moving());
  // An error on channel 2 and its reset never touch channel 1, which keeps moving.
  EXPECT_FALSE(plc_->resume(1, std::nullopt).ok);
  EXPECT_TRUE(st(1).has(sb::kCommandError));
  ASSERT_TRUE(plc_->reset_errors(1).ok);
  EXPECT_FALSE(st(0).has(sb::kCommandError));
  EXPECT_TRUE(st(0).moving());
  ASSERT_TRUE(plc_->wait_idle(0, std::chrono::seconds(20)).ok);
  ASSERT_TRUE(plc_->wait_idle(1, std::chrono::seconds(20)).ok);
  EXPECT_EQ(st(0).position, 25'000);
  EXPECT_EQ(st(1).position, -17'000);
  EXPECT_TRUE(st(0).has(sb::kMoveComplete));
  EXPECT_TRUE(st(1).has(sb::kMoveComplete));
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising("axis1.step").size(), 25'000u);
  EXPECT_EQ(vcd.rising("axis2.step").size(), 17'000u);
  // Every record at its own time: the two channels' encoder edges reach the trace interleaved
  // out of time order, and were once written up to a few ms later than they happened (5-7 %).
  std::ifstream f(daemon_->trace_path());
  const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("; late records 0;"), std::string::npos)
      << text.substr(text.rfind("$comment"));
  EXPECT_GT(vcd.rising("axis2.enc_a").size(), 4'000u) << "the encoders' edges are traced";
}

TEST_F(Daemon3202, BlendMessageThroughTheMailboxRunsItsLength) {
  plc::BlendProfile b;
  b.segments = {{6'000, 5'000, 100'000}, {4'000, 2'000, 100'000}};
  b.final_decel = 100'000;
  // A message naming no channel is refused: IP on both channels (A23).
  const auto bad = plc::m3202::blend_message(3, b);
  EXPECT_EQ(client_->send_message(bad, milliseconds(3000)).value_or(-99), m::kMessageRefused);
  EXPECT_TRUE(st(0).has(sb::kInvalidProfile));
  EXPECT_TRUE(st(1).has(sb::kInvalidProfile));
  ASSERT_TRUE(plc_->reset_errors(1).ok);
  const auto good = plc::m3202::blend_message(2, b);
  ASSERT_EQ(client_->send_message(good, milliseconds(3000)).value_or(-99), m::kMessageAccepted);
  ASSERT_TRUE(plc_->blend_run(1, true).ok);
  ASSERT_TRUE(plc_->wait_idle(1, std::chrono::seconds(20)).ok);
  EXPECT_TRUE(st(1).has(sb::kMoveComplete));
  EXPECT_EQ(st(1).position, 10'000);
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising("axis2.step").size(), 10'000u);
  EXPECT_EQ(vcd.rising("axis1.step").size(), 0u);
}

TEST_F(Daemon3202, EStopOnOneChannelStopsOnlyThatChannel) {
  ASSERT_TRUE(plc_->configure(0, kBits | m::cfg_bit::kEStopUsed, 1'000).ok);
  ASSERT_TRUE(plc_->move(0, false, 150'000, kProfile).ok);
  ASSERT_TRUE(plc_->move(1, false, 30'000, kProfile).ok);
  port_->pass(milliseconds(500));
  ipc::SimPanelClient panel(daemon_->name());
  panel.force(0, 3, true);  // bit 3: E-stop, active high
  ASSERT_TRUE(plc_->wait_idle(0, std::chrono::seconds(5)).ok);
  EXPECT_TRUE(st(0).has(sb::kInputError));
  EXPECT_TRUE(st(0).has(sb::kPositionInvalid));
  EXPECT_TRUE(st(0).has(sb::kStopped));
  EXPECT_TRUE(st(1).moving());
  EXPECT_FALSE(st(1).has(sb::kInputError));
  ASSERT_TRUE(plc_->wait_idle(1, std::chrono::seconds(20)).ok);
  EXPECT_TRUE(st(1).has(sb::kMoveComplete));
  panel.release(0, 3);
  const Vcd vcd = stop_and_read_trace();
  EXPECT_LT(vcd.rising("axis1.step").size(), 150'000u);
  EXPECT_EQ(vcd.rising("axis2.step").size(), 30'000u);
}

TEST_F(Daemon3202, SigtermMidMoveStopsBothChannels) {
  ASSERT_TRUE(plc_->move(0, false, 150'000, kProfile).ok);
  ASSERT_TRUE(plc_->move(1, false, -150'000, kProfile).ok);
  port_->pass(milliseconds(300));
  const Vcd vcd = stop_and_read_trace();
  EXPECT_GT(vcd.rising("axis1.step").size(), 0u);
  EXPECT_LT(vcd.rising("axis1.step").size(), 150'000u);
  EXPECT_LT(vcd.rising("axis2.step").size(), 150'000u);
}

}  // namespace
}  // namespace stepmod::testing
