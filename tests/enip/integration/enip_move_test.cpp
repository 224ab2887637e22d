// End to end over EtherNet/IP (docs/ethernetip-design.md, "Tests"): the real stepmodd with its
// adapter, driven by st-ethernet-ip's class 1 scanner (an npm package we did not write) as a
// Logix PLC would: exclusive owner at RPI 10 ms, every command through the I/O data alone
// (the suite's PLC programs over EnipPort), checked in the T→O data, the image and the VCD.
// Then the deadman: the scanner falls silent and the axes stop with Position Invalid and health
// bit 1 though plc_timeout_ms is 0; and a second owner is refused with 0x01/0x0106.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "ipc/sim_panel.hpp"
#include "module_types/m3202/plc_3202.hpp"
#include "module_types/m3601/plc_3601.hpp"
#include "tests/enip/integration/enip_daemon.hpp"
#include "tests/enip/integration/enip_port.hpp"
#include "tests/enip/integration/raw_socket.hpp"
#include "tests/enip/mutation_corpus.hpp"
#include "tests/support/vcd_reader.hpp"

namespace stepmod::testing {
namespace {

using std::chrono::milliseconds;
using Clock = std::chrono::steady_clock;
using Bytes = std::vector<std::uint8_t>;
namespace m1 = words::m3601;
namespace m2 = words::m3202;

constexpr const char* kSim = "cw_limit_at = 10000000\nccw_limit_at = -10000000\n";
constexpr std::uint16_t k3601Config = m1::cfg_msw::kCaptureUsed | m1::cfg_msw::kExternalUsed |
                                      m1::cfg_msw::kHomeUsed | m1::cfg_msw::kEStopUsed |
                                      m1::cfg_msw::kCwLimitUsed | m1::cfg_msw::kCcwLimitUsed |
                                      m1::cfg_msw::kQuadratureEncoder | m1::cfg_msw::kStepDirOutput;
constexpr std::uint32_t k3202Config = m2::cfg_bit::kHomeUsed | m2::cfg_bit::kCwLimitUsed |
                                      m2::cfg_bit::kCcwLimitUsed | m2::cfg_bit::kQuadratureEncoder |
                                      m2::cfg_bit::kStepDirOutput | m2::cfg_bit::kActiveLevels;
constexpr plc::Profile kProfile3601{.speed = 20'000, .accel = 100, .decel = 100};
constexpr plc::Profile kProfile3202{.speed = 20'000, .accel = 100'000, .decel = 100'000};

class EnipMove : public EnipDaemon {
 protected:
  void SetUp() override { REQUIRE_ENIP_PARTNERS(); }
  // Waits until `cond` holds for the image's inputs (observation only: no write).
  bool image_until(const std::function<bool(const ImageWords&)>& cond, milliseconds limit) {
    const auto end = Clock::now() + limit;
    for (;;) {
      ImageWords in;
      if (image_->read_inputs(in) && cond(in)) return true;
      if (Clock::now() > end) return false;
      std::this_thread::sleep_for(milliseconds(1));
    }
  }
  // A 3601 on the simulated machine (plc_timeout_ms 0: only the adapter's deadman can stop it)
  // and its owner, st-ethernet-ip's scanner at RPI 10 ms, its connection's timeout `multiplier`
  // RPIs; null when either did not start.
  std::unique_ptr<PartnerProcess> start_3601_owned(unsigned multiplier = kPatientMultiplier) {
    start(sim_3601_config("plc_timeout_ms = 0\n", kSim));
    return image_ ? connect_scanner(10, multiplier) : nullptr;
  }
  // Configured, and moving a long way (5,000,000 steps at 5,000 steps/s) through the I/O data.
  void start_long_move(plc::Plc3601& plc, const PartnerProcess& scanner) {
    const plc::Outcome cfg = plc.configure(k3601Config, 0x3F, 1'000);
    ASSERT_TRUE(cfg.ok) << cfg.message << "\n" << scanner.transcript() << daemon_->log();
    const plc::Profile slow{.speed = 5'000, .accel = 100, .decel = 100};
    const plc::Outcome mv = plc.move(false, 5'000'000, slow);
    ASSERT_TRUE(mv.ok) << mv.message << "\n" << scanner.transcript() << daemon_->log();
    ASSERT_TRUE(image_until(moving_3601, milliseconds(2000)));
  }
  static bool moving_3601(const ImageWords& w) { return plc::m3601::decode_status(w).moving(); }
  Vcd stop_and_read_trace() {
    image_.reset();
    EXPECT_EQ(daemon_->terminate(), 0) << daemon_->log();
    return read_vcd(daemon_->trace_path());
  }
};

TEST_F(EnipMove, A3601ConfiguredAndMovedThroughTheIoDataAlone) {
  auto scanner = start_3601_owned();
  ASSERT_TRUE(scanner) << "no scanner";
  EnipPort port(*scanner, *image_);
  plc::Plc3601 plc(port, milliseconds(3000));
  const plc::Outcome cfg = plc.configure(k3601Config, 0x3F, 1'000);
  ASSERT_TRUE(cfg.ok) << cfg.message << scanner->transcript();
  ASSERT_TRUE(plc.preset_position(0).ok);  // Position Invalid since power-up
  const plc::Outcome mv = plc.move(false, 10'000, kProfile3601);
  ASSERT_TRUE(mv.ok) << mv.message;
  const plc::Outcome idle = plc.wait_idle(std::chrono::seconds(20));
  ASSERT_TRUE(idle.ok) << idle.message;
  // Exact in T→O: the scanner's input words, as the adapter sent them.
  ImageWords to;
  ASSERT_TRUE(port.read_inputs(to));
  const plc::m3601::Status st = plc::m3601::decode_status(to);
  EXPECT_EQ(st.position, 10'000) << scanner->transcript() << daemon_->log();
  EXPECT_TRUE(st.has(m1::status_msw::kMoveComplete));
  EXPECT_FALSE(st.has(m1::status_msw::kPositionInvalid));
  // ... and in the image: the same words.
  ImageWords in;
  ASSERT_TRUE(image_->read_inputs(in));
  EXPECT_EQ(plc::m3601::decode_status(in).position, 10'000);
  EXPECT_EQ(port.lost_writes(), 0u);
  EXPECT_EQ(image_->read_health().flags, 0u) << "no PLC loss while the scanner ran";
  scanner.reset();
  EXPECT_EQ(stop_and_read_trace().rising("axis1.step").size(), 10'000u);
}

TEST_F(EnipMove, ASecondOwnerIsRefusedWith0x0106) {
  auto owner = start_3601_owned();
  ASSERT_TRUE(owner) << "no scanner";
  PartnerProcess second({"open-once", scanner_config(other_ip_, 10, 16)});
  const auto r = second.line_with("opened", std::chrono::seconds(10));
  ASSERT_TRUE(r.has_value()) << second.transcript();
  EXPECT_EQ(json_field(*r, "opened"), "false") << *r;
  EXPECT_EQ(json_field(*r, "general"), "1") << *r;
  EXPECT_NE(r->find("\"extended\":[262]"), std::string::npos) << *r << " (0x0106 = 262)";
  // The owner is untouched: its T→O keeps coming.
  const auto a = owner->ask("get");
  std::this_thread::sleep_for(milliseconds(100));
  const auto b = owner->ask("get");
  ASSERT_TRUE(a && b);
  EXPECT_GT(std::stoul(json_field(*b, "seq")), std::stoul(json_field(*a, "seq")));
}

TEST_F(EnipMove, BothChannelsOfA3202ThroughTheIoDataAlone) {
  start(sim_module_tables("3202") + sim_axis(every_axis_line(1), kSim) +
        sim_axis(every_axis_line(12), kSim));
  auto scanner = connect_scanner(10);
  ASSERT_TRUE(scanner);
  EnipPort port(*scanner, *image_);
  plc::Plc3202 plc(port, milliseconds(3000));
  for (unsigned ch : {0u, 1u}) {
    const plc::Outcome cfg = plc.configure(ch, k3202Config, 1'000);
    ASSERT_TRUE(cfg.ok) << ch << ": " << cfg.message << scanner->transcript();
    ASSERT_TRUE(plc.preset_position(ch, 0).ok);
  }
  ASSERT_TRUE(plc.move(0, false, 10'000, kProfile3202).ok);
  ASSERT_TRUE(plc.move(1, false, -10'000, kProfile3202).ok);
  for (unsigned ch : {0u, 1u}) ASSERT_TRUE(plc.wait_idle(ch, std::chrono::seconds(20)).ok);
  ImageWords to;
  ASSERT_TRUE(port.read_inputs(to));
  ImageWords in;
  ASSERT_TRUE(image_->read_inputs(in));
  EXPECT_EQ(plc::m3202::decode_status(to, 0).position, 10'000);
  EXPECT_EQ(plc::m3202::decode_status(to, 1).position, -10'000);
  EXPECT_TRUE(plc::m3202::decode_status(to, 1).has(m2::status_bit::kMoveComplete));
  EXPECT_EQ(plc::m3202::decode_status(in, 0).position, 10'000);
  EXPECT_EQ(plc::m3202::decode_status(in, 1).position, -10'000);
  EXPECT_EQ(port.lost_writes(), 0u);
  scanner.reset();
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising("axis1.step").size(), 10'000u);
  EXPECT_EQ(vcd.rising("axis2.step").size(), 10'000u);
}

// plc_timeout_ms = 0 (the sim config's default): only the adapter's deadman can stop the axis.
TEST_F(EnipMove, TheScannerFallsSilentAndTheAxisStopsWithinTheTimeout) {
  auto scanner = start_3601_owned(kLibraryMultiplier);
  ASSERT_TRUE(scanner) << "no scanner";
  EnipPort port(*scanner, *image_);
  plc::Plc3601 plc(port, milliseconds(3000));
  ASSERT_NO_FATAL_FAILURE(start_long_move(plc, *scanner));
  port.pass(milliseconds(300));  // still moving while the scanner runs
  ASSERT_TRUE(image_until(moving_3601, milliseconds(0)));
  scanner->ask("silent");
  const auto silent = Clock::now();
  // The timeout: RPI 10 ms x 32 (st-ethernet-ip's multiplier) = 320 ms; the bound is generous
  // for a loaded machine.
  ASSERT_TRUE(image_until([&](const ImageWords& w) { return !moving_3601(w); }, milliseconds(5000)))
      << daemon_->log();
  const auto took = std::chrono::duration_cast<milliseconds>(Clock::now() - silent).count();
  EXPECT_GE(took, 250) << "stopped before the connection's timeout";
  EXPECT_LE(took, 3000);
  ImageWords in;
  ASSERT_TRUE(image_->read_inputs(in));
  EXPECT_TRUE(plc::m3601::decode_status(in).has(m1::status_msw::kPositionInvalid));
  EXPECT_NE(image_->read_health().flags & STEPMOD_HEALTH_PLC_STALE, 0u);
  ipc::SimPanelClient panel(daemon_->name());
  const std::int64_t stopped_at = panel.read(0).position;
  std::this_thread::sleep_for(milliseconds(200));
  EXPECT_EQ(panel.read(0).position, stopped_at) << "the motor still turns";
  EXPECT_NE(daemon_->log().find("EtherNet/IP: the owner PLC left Run"), std::string::npos)
      << daemon_->log();
  std::cout << "stopped " << took << " ms after the scanner fell silent\n";
}

// Idle in the run/idle header is the PLC leaving Run at once (no timeout to wait for), and the
// next Run packet brings it back. st-ethernet-ip always sends Run, so the Idle and the Run after
// it are sent from the scanner's address with its O→T connection id and newer sequences.
TEST_F(EnipMove, AnIdlePacketStopsAtOnceAndTheNextRunPacketClearsIt) {
  auto scanner = start_3601_owned(kLibraryMultiplier);
  ASSERT_TRUE(scanner) << "no scanner";
  const std::string connected = scanner->transcript();
  const auto ot = static_cast<std::uint32_t>(std::stoul(json_field(connected, "ot")));
  EnipPort port(*scanner, *image_);
  plc::Plc3601 plc(port, milliseconds(3000));
  ASSERT_NO_FATAL_FAILURE(start_long_move(plc, *scanner));
  // O→T as the scanner sends it (tests/enip/io_packet_test.cpp), sequence far ahead of its own.
  const auto packet = [&](std::uint32_t seq, bool run) {
    Bytes b = enip::test::hex("0200 0280 0800 00000000 00000000 b100 1600 0000 00000000");
    for (int i = 0; i < 4; ++i) {
      b[6 + i] = static_cast<std::uint8_t>(ot >> (8 * i));
      b[10 + i] = static_cast<std::uint8_t>(seq >> (8 * i));
    }
    b[18] = static_cast<std::uint8_t>(seq);  // a new CIP count: new data
    b[20] = run ? 1 : 0;
    b.resize(b.size() + 16, 0);  // the words: all 0 (no command)
    const int fd = bound_socket(SOCK_DGRAM, scanner_ip_);
    const sockaddr_in to = ipv4(target_, 2222);
    ::sendto(fd, b.data(), b.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
    ::close(fd);
  };
  scanner->ask("silent");  // its own packets would be older than ours anyway
  const auto idle_at = Clock::now();
  packet(0x40000000u, false);
  ASSERT_TRUE(
      image_until([&](const ImageWords& w) { return !moving_3601(w); }, milliseconds(3000)));
  const auto took = std::chrono::duration_cast<milliseconds>(Clock::now() - idle_at).count();
  EXPECT_LT(took, 250) << "Idle waited for the timeout";
  ImageWords in;
  ASSERT_TRUE(image_->read_inputs(in));
  EXPECT_TRUE(plc::m3601::decode_status(in).has(m1::status_msw::kPositionInvalid));
  EXPECT_NE(image_->read_health().flags & STEPMOD_HEALTH_PLC_STALE, 0u);
  packet(0x40000001u, true);  // Run again, before the connection's timeout
  const auto end = Clock::now() + milliseconds(2000);
  while ((image_->read_health().flags & STEPMOD_HEALTH_PLC_STALE) != 0 && Clock::now() < end) {
    std::this_thread::sleep_for(milliseconds(1));
  }
  EXPECT_EQ(image_->read_health().flags & STEPMOD_HEALTH_PLC_STALE, 0u)
      << "the Run packet did not clear the deadman\n"
      << daemon_->log();
  std::cout << "stopped " << took << " ms after the Idle packet\n";
}

}  // namespace
}  // namespace stepmod::testing
