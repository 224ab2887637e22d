// End to end: the real stepmodd as a 3602 on the simulated machine, driven through shared memory
// by the PLC-side library (module_types/m3602/plc_3602), checked through the status words, the panel and the
// VCD trace: both axes at once with exact counts, the binary split at 50,800 and at a negative
// target, GPO edges, a CW input configured as an E-stop stopping its axis only, the GPO idle-low
// at SIGTERM, the homing timeout.
#include <gtest/gtest.h>

#include <time.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <thread>

#include "core/lines.hpp"
#include "ipc/client.hpp"
#include "ipc/sim_panel.hpp"
#include "module_types/m3602/plc_3602.hpp"
#include "plc/shm_port.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/sim_config.hpp"
#include "tests/support/vcd_reader.hpp"
#include "module_types/m3602/words_3602.hpp"

namespace stepmod::testing {
namespace {

namespace m = words::m3602;
using namespace m::status_msw;
using std::chrono::milliseconds;

// Two axes (lines 1..8, 11..18), the limits far out, a home switch at 5,000..5,100.
std::string config_3602() {
  std::string axes;
  for (const unsigned first : {1u, 11u}) {
    axes += sim_axis(numbered_lines(first, {"step", "dir", "gpo", "capture", "external", "home",
                                            "cw_limit", "ccw_limit"}),
                     "cw_limit_at = 1000000\nccw_limit_at = -1000000\nhome_from = 5000\n"
                     "home_to = 5100\n");
  }
  return sim_module_tables("3602") + axes;
}

// Home, capture and external enabled, CW/CCW inputs as limits, step/direction, active high.
constexpr std::uint16_t kLimits =
    m::cfg_msw::kCaptureEnabled | m::cfg_msw::kExternalEnabled | m::cfg_msw::kHomeEnabled |
    (m::cfg_msw::kFunctionLimit << m::cfg_msw::kCwFunctionShift) |
    (m::cfg_msw::kFunctionLimit << m::cfg_msw::kCcwFunctionShift) | m::cfg_msw::kStepDirOutput;
constexpr std::uint16_t kEStopCw =
    static_cast<std::uint16_t>((kLimits & ~m::cfg_msw::kCwFunction) |
                               (m::cfg_msw::kFunctionEStop << m::cfg_msw::kCwFunctionShift));

class Daemon3602 : public ::testing::Test {
 protected:
  void SetUp() override {
    daemon_ = std::make_unique<DaemonProcess>(config_3602());
    ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
    client_ = std::make_unique<ipc::Client>(daemon_->name());
    port_ = std::make_unique<plc::ShmPort>(*client_, milliseconds(2000));
    plc_ = std::make_unique<plc::Plc3602>(*port_, milliseconds(2000), kSeq);
  }
  plc::m3602::Status status(unsigned axis) const {
    ImageWords in;
    EXPECT_TRUE(port_->read_inputs(in));
    return plc::m3602::decode_status(in, axis);
  }
  Vcd stop_and_read_trace() {
    plc_.reset();
    port_.reset();
    client_.reset();
    EXPECT_EQ(daemon_->terminate(), 0) << daemon_->log();
    return read_vcd(daemon_->trace_path());
  }
  static constexpr plc::Sequencing kSeq{
      .hold_scans = 3, .release_scans = 2, .config_scans = 3, .release_stale_bits = false};
  static constexpr plc::Profile kProfile{.speed = 20'000, .accel = 100, .decel = 100};
  std::unique_ptr<DaemonProcess> daemon_;
  std::unique_ptr<ipc::Client> client_;
  std::unique_ptr<plc::ShmPort> port_;
  std::unique_ptr<plc::Plc3602> plc_;
};

TEST_F(Daemon3602, BothAxesAtOnceExactCountsBinarySplitAndGpoEdges) {
  ASSERT_TRUE(plc_->configure(0, kLimits, 0x1F, 1'000).ok);
  ASSERT_TRUE(plc_->configure(1, kLimits, 0x1F, 1'000).ok);
  ASSERT_TRUE(plc_->set_gpo(1, true).ok);
  ASSERT_TRUE(plc_->move(0, false, 50'800, kProfile).ok);  // 16#0000 / 16#C670
  EXPECT_EQ(port_->outputs().w[m::out_word::kTargetLsw], -14'736);
  ASSERT_TRUE(plc_->move(1, false, -33'333, kProfile).ok);
  ASSERT_TRUE(plc_->wait_idle(0, std::chrono::seconds(20)).ok);
  ASSERT_TRUE(plc_->wait_idle(1, std::chrono::seconds(20)).ok);
  EXPECT_EQ(status(0).position, 50'800);
  EXPECT_EQ(status(1).position, -33'333);
  EXPECT_TRUE(status(0).has(kMoveComplete));
  EXPECT_TRUE(status(1).has_lsw(m::status_lsw::kGpo));
  ASSERT_TRUE(plc_->set_gpo(1, false).ok);
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising("axis1.step").size(), 50'800u);
  EXPECT_EQ(vcd.rising("axis2.step").size(), 33'333u);
  EXPECT_EQ(vcd.rising("axis2.gpo").size(), 1u);
  EXPECT_EQ(vcd.final_level("axis2.gpo"), 0);
  EXPECT_EQ(vcd.rising("axis1.gpo").size(), 0u);
}

TEST_F(Daemon3602, CwInputConfiguredAsEStopStopsItsAxisOnly) {
  ASSERT_TRUE(plc_->configure(0, kEStopCw, 0x1F, 1'000).ok);
  ASSERT_TRUE(plc_->configure(1, kLimits, 0x1F, 1'000).ok);
  ASSERT_TRUE(plc_->move(0, false, -200'000, kProfile).ok);
  ASSERT_TRUE(plc_->move(1, false, 40'000, kProfile).ok);
  std::this_thread::sleep_for(milliseconds(300));
  ipc::SimPanelClient panel(daemon_->name());
  panel.force(0, static_cast<unsigned>(InputLine::kCwLimit), true);
  ASSERT_TRUE(plc_->wait_idle(0, std::chrono::seconds(2)).ok);
  EXPECT_TRUE(status(0).has(kInputError));
  EXPECT_TRUE(status(0).has(kPositionInvalid));
  EXPECT_TRUE(status(1).moving());
  ASSERT_TRUE(plc_->wait_idle(1, std::chrono::seconds(20)).ok);
  EXPECT_EQ(status(1).position, 40'000) << daemon_->log();
  EXPECT_FALSE(status(1).has(kInputError));
  panel.release(0, static_cast<unsigned>(InputLine::kCwLimit));
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising("axis2.step").size(), 40'000u);
  EXPECT_LT(vcd.rising("axis1.step").size(), 200'000u);
}

// The trace's time 0 in CLOCK_MONOTONIC ns, from the daemon's log line "trace: #0 is
// CLOCK_MONOTONIC <ns> ns".
std::int64_t trace_origin(const std::string& log) {
  const std::string key = "trace: #0 is CLOCK_MONOTONIC ";
  const auto p = log.find(key);
  return p == std::string::npos ? -1 : std::stoll(log.substr(p + key.size()));
}

std::int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

// docs/interface.md: at shutdown every output goes to its idle level before the lines are released.
// The GPO is on when SIGTERM arrives; the trace shows it falling after the signal, exit 0.
TEST_F(Daemon3602, GpoOnAtSigtermGoesLowAtShutdownExitZero) {
  ASSERT_TRUE(plc_->configure(0, kLimits, 0x1F, 1'000).ok);
  ASSERT_TRUE(plc_->set_gpo(0, true).ok);
  EXPECT_TRUE(status(0).has_lsw(m::status_lsw::kGpo));
  port_->pass(milliseconds(50));
  const std::int64_t t_term = monotonic_ns();
  const Vcd vcd = stop_and_read_trace();  // SIGTERM, exit status 0
  const std::int64_t origin = trace_origin(daemon_->log());
  ASSERT_GE(origin, 0) << daemon_->log();
  const auto& gpo = vcd.wires.at("axis1.gpo");
  // Initial 0, risen by the PLC's command, fallen at shutdown: nothing else lowered it.
  ASSERT_EQ(gpo.size(), 3u);
  EXPECT_EQ(gpo[1].level, 1);
  EXPECT_EQ(gpo[2].level, 0);
  EXPECT_LT(gpo[1].t + origin, t_term);
  EXPECT_GE(gpo[2].t + origin, t_term) << "the GPO fell before SIGTERM";
  EXPECT_EQ(vcd.final_level("axis2.gpo"), 0);
}

// 3602-HI-07 through the daemon (issue 10: "homing timeout"): a 1-s Homing Timeout ends a Find
// Home that cannot reach the switch in time (5,000 steps at 1,500 steps/s: 3.3 s) with Home
// Invalid and a controlled stop (A16: Position Invalid left as it was); the trace's pulses are the
// reported position, and they ran for at least the timeout.
TEST_F(Daemon3602, HI_07_HomingTimeoutEndsFindHomeWithHomeInvalid) {
  ASSERT_TRUE(plc_->configure(0, kLimits, 0x1F, 1'000, 1).ok);
  ASSERT_TRUE(plc_->preset_position(0, 0).ok);
  ASSERT_FALSE(status(0).has(kPositionInvalid));
  ASSERT_TRUE(plc_->pulse(0, m::cmd_msw::kFindHomeCw, 0, 0, 1'500, 10, 10).ok);
  ASSERT_TRUE(plc_->wait_idle(0, std::chrono::seconds(10)).ok);
  port_->wait_scans(3);
  const plc::m3602::Status s = status(0);
  EXPECT_TRUE(s.has(kHomeInvalid));
  EXPECT_FALSE(s.has(kAtHome));
  EXPECT_FALSE(s.has(kPositionInvalid));  // A16
  EXPECT_FALSE(s.has(kInputError));
  EXPECT_GT(s.position, 0);
  EXPECT_LT(s.position, 5'000);  // the switch was never reached
  const Vcd vcd = stop_and_read_trace();
  const auto steps = vcd.rising("axis1.step");
  ASSERT_EQ(steps.size(), static_cast<std::size_t>(s.position));
  // A late pulse thread only stretches the run; it cannot end before the timeout (less the
  // first step's delay after the command).
  EXPECT_GE(steps.back() - steps.front(), 900'000'000);
}

}  // namespace
}  // namespace stepmod::testing
