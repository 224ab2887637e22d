// The PLC-side 3601 dialect (module_types/m3601/plc_3601) over the shared-memory port, against a scripted fake
// 3601 that scans the image in its own thread: edges, releases, handshakes, error reporting.
#include "module_types/m3601/plc_3601.hpp"

#include <unistd.h>

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

#include "ipc/shm_image.hpp"
#include "plc/shm_port.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::plc {
namespace {

namespace m = words::m3601;
using namespace std::chrono_literals;

constexpr ModuleShape k3601{ModuleType::k3601, 1, 2, 8, 8};

std::string test_name(const char* tag) {
  return std::string("c-") + tag + "-" + std::to_string(::getpid());
}

// Scans every 200 us. Records the output image at each 0->1 edge of a command-word bit and at
// each rising blend transmit; answers the blend handshake; mirrors configuration mode. Raises
// Command Error for a move with speed words 0, Configuration Error for reserved config bits.
class FakeModule {
 public:
  explicit FakeModule(const std::string& name) : img_(name, k3601) {
    thread_ = std::thread([this] { run(); });
  }
  ~FakeModule() {
    stop_ = true;
    thread_.join();
  }
  std::vector<ImageWords> edges() {
    std::lock_guard<std::mutex> l(mu_);
    return edges_;
  }
  std::vector<ImageWords> blocks() {
    std::lock_guard<std::mutex> l(mu_);
    return blocks_;
  }
  std::vector<ImageWords> configs() {
    std::lock_guard<std::mutex> l(mu_);
    return configs_;
  }
  int releases() const { return releases_.load(); }

 private:
  void run() {
    ImageWords prev;
    std::uint16_t msw_status = m::status_msw::kModuleOk;
    std::uint16_t lsw_status = 0;
    while (!stop_) {
      ImageWords out = prev;
      img_.read_outputs(out);
      const auto w0 = static_cast<std::uint16_t>(out.w[0]);
      const auto w1 = static_cast<std::uint16_t>(out.w[1]);
      const auto p0 = static_cast<std::uint16_t>(prev.w[0]);
      const auto p1 = static_cast<std::uint16_t>(prev.w[1]);
      ImageWords in;
      if (w0 & m::cfg_msw::kConfigMode) {
        if (!(p0 & m::cfg_msw::kConfigMode)) {
          std::lock_guard<std::mutex> l(mu_);
          configs_.push_back(out);
        }
        const bool bad = (w0 & m::cfg_msw::kReserved) != 0;
        in.w[0] = static_cast<std::int16_t>((w0 & 0x1FFF) | m::status_msw::kModuleOk |
                                            m::status_msw::kConfigMode |
                                            (bad ? m::status_msw::kConfigurationError : 0));
        in.w[1] = out.w[1];
        in.w[2] = out.w[2];
        in.w[3] = out.w[3];
        in.w[6] = m::kFirmwareMajor;
        in.w[7] = m::kFirmwareMinor;
        msw_status = static_cast<std::uint16_t>(m::status_msw::kModuleOk |
                                                (bad ? m::status_msw::kConfigurationError : 0));
      } else {
        const std::uint16_t rising = w0 & ~p0 & m::cmd_msw::kCommandMask;
        const std::uint16_t falling = p0 & ~w0 & m::cmd_msw::kCommandMask;
        if (falling) ++releases_;
        if (rising) {
          std::lock_guard<std::mutex> l(mu_);
          edges_.push_back(out);
          if ((rising & (m::cmd_msw::kAbsoluteMove | m::cmd_msw::kRelativeMove)) && out.w[4] == 0 &&
              out.w[5] == 0) {
            msw_status |= m::status_msw::kCommandError;
          }
          if (rising & m::cmd_msw::kResetErrors) msw_status &= ~m::status_msw::kCommandError;
        }
        // Manual move bits are levels: "moving" while held.
        msw_status &= ~(m::status_msw::kMovingCw | m::status_msw::kMovingCcw);
        if (w0 & m::cmd_msw::kManualCw) msw_status |= m::status_msw::kMovingCw;
        if (w0 & m::cmd_msw::kManualCcw) msw_status |= m::status_msw::kMovingCcw;
        // Blend handshake (3601 manual ch. 4-5).
        if ((w1 & m::cmd_lsw::kProgramBlend) && (w1 & m::cmd_lsw::kBlendTransmit) &&
            !(p1 & m::cmd_lsw::kBlendTransmit)) {
          std::lock_guard<std::mutex> l(mu_);
          blocks_.push_back(out);
          lsw_status |= m::status_lsw::kBlendAcknowledge;
        }
        if (!(w1 & m::cmd_lsw::kBlendTransmit)) lsw_status &= ~m::status_lsw::kBlendAcknowledge;
        in.w[0] = static_cast<std::int16_t>(msw_status);
        in.w[1] = static_cast<std::int16_t>(lsw_status);
        in.w[2] = -12;
        in.w[3] = -345;
      }
      img_.publish_inputs(in);
      prev = out;
      std::this_thread::sleep_for(200us);
    }
  }

  ipc::ShmImage img_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<int> releases_{0};
  std::mutex mu_;
  std::vector<ImageWords> edges_;
  std::vector<ImageWords> blocks_;
  std::vector<ImageWords> configs_;
};

ImageWords words(std::initializer_list<std::int32_t> v) {
  ImageWords w;
  unsigned i = 0;
  for (std::int32_t x : v) w.w[i++] = x;
  return w;
}

// A PLC's side of the fake module above: the dialect over the shared-memory port, each test on an
// image of its own.
class CtlCommands : public ::testing::Test {
 protected:
  static std::string unique_name() {
    static int counter = 0;
    return test_name(std::to_string(counter++).c_str());
  }
  const std::string n = unique_name();
  FakeModule fake{n};
  ipc::Client c{n};
  ShmPort port{c};
  Plc3601 plc{port};
};

ImageWords outputs_of(ipc::Client& c) {
  ImageWords w;
  c.read_outputs(w);
  return w;
}

TEST_F(CtlCommands, MoveWritesDecimalSplitWithEdgeThenReleases) {
  const Outcome o = plc.move(true, -12'345, {1'500, 10, 20, AccelType::kTrapezoidalS});
  EXPECT_TRUE(o.ok) << o.message;
  ASSERT_EQ(fake.edges().size(), 1u);
  EXPECT_EQ(fake.edges()[0], words({1, 3, -12, -345, 1, 500, 10, 20}));
  EXPECT_EQ(outputs_of(c), words({0, 3, -12, -345, 1, 500, 10, 20}))
      << "command bit released, parameters kept as a PLC leaves them";
  EXPECT_EQ(fake.releases(), 1);
  EXPECT_EQ(static_cast<std::int16_t>(o.in.w[3]), -345);
}

TEST_F(CtlCommands, RelativeEncoderMoveAndScurveBits) {
  EXPECT_TRUE(plc.move(false, 500, {2'000, 1, 1, AccelType::kTriangularS}, true).ok);
  ASSERT_EQ(fake.edges().size(), 1u);
  EXPECT_EQ(fake.edges()[0], words({2, 1 | 4, 0, 500, 2, 0, 1, 1}));
}

TEST_F(CtlCommands, CommandErrorReportedAndResetClearsIt) {
  const Outcome bad = plc.move(true, 100, {0, 10, 10});
  EXPECT_FALSE(bad.ok);
  EXPECT_FALSE(bad.timed_out);
  EXPECT_NE(bad.message.find("Command Error"), std::string::npos) << bad.message;
  const Outcome r = plc.reset_errors();
  EXPECT_TRUE(r.ok) << r.message;
  EXPECT_EQ(fake.edges().back().w[0], m::cmd_msw::kResetErrors);
  EXPECT_EQ(fake.edges().back().w[1], 0) << "LSW must be 0 with Reset Errors";
}

TEST_F(CtlCommands, StaleCommandBitIsReleasedBeforeTheNewEdge) {
  // A PLC left the bit of a valid move at 1.
  c.write_outputs(words({m::cmd_msw::kAbsoluteMove, 0, 0, 0, 1, 0, 1, 1}));
  ASSERT_TRUE(c.wait_scans(3, 2s));
  const auto before = fake.edges().size();
  EXPECT_TRUE(plc.move(true, 1, {1'000, 1, 1}).ok);
  ASSERT_EQ(fake.edges().size(), before + 1) << "the module saw a new 0->1 edge";
}

TEST_F(CtlCommands, PresetAndStopWordLayouts) {
  EXPECT_TRUE(plc.move(true, 7, {3'000, 5, 6}).ok);
  EXPECT_TRUE(plc.preset_position(-1'000).ok);
  EXPECT_EQ(fake.edges().back(), words({m::cmd_msw::kPresetPosition, 0, -1, 0, 0, 0, 0, 0}))
      << "LSW and words 4..7 must be 0 with Preset";
  EXPECT_TRUE(plc.preset_encoder(2'500).ok);
  EXPECT_EQ(fake.edges().back(), words({m::cmd_msw::kPresetEncoder, 0, 2, 500, 0, 0, 0, 0}));
  EXPECT_TRUE(plc.immediate_stop().ok);
  EXPECT_EQ(fake.edges().back().w[0], m::cmd_msw::kImmediateStop);
  EXPECT_TRUE(plc.hold().ok);
  EXPECT_EQ(fake.edges().back().w[0], m::cmd_msw::kHold);
  EXPECT_TRUE(plc.resume(std::nullopt).ok);
  EXPECT_EQ(fake.edges().back().w[0], m::cmd_msw::kResume);
  EXPECT_TRUE(plc.resume(Profile{4'000, 7, 8, AccelType::kTriangularS}).ok);
  EXPECT_EQ(fake.edges().back(), words({m::cmd_msw::kResume, 1, 2, 500, 4, 0, 7, 8}));
  EXPECT_TRUE(plc.blend_run(false).ok);
  EXPECT_EQ(fake.edges().back(), words({m::cmd_msw::kRunBlendCcw, 0, 0, 0, 0, 0, 0, 0}));
}

TEST_F(CtlCommands, HomeKeepsProximityBitAndZeroTarget) {
  c.write_word(1, m::cmd_lsw::kBackplaneProximity | m::cmd_lsw::kSCurve);
  c.write_word(2, 5);
  EXPECT_TRUE(plc.home(false, {1'000, 2, 3}).ok);
  EXPECT_EQ(fake.edges().back(),
            words({m::cmd_msw::kFindHomeCcw, m::cmd_lsw::kBackplaneProximity, 0, 0, 1, 0, 2, 3}));
}

TEST_F(CtlCommands, ConfigureEntersConfigModeAndReturns) {
  const std::uint16_t cfg = m::cfg_msw::kHomeUsed | m::cfg_msw::kCwLimitUsed |
                            m::cfg_msw::kCcwLimitUsed | m::cfg_msw::kStepDirOutput;
  const Outcome o = plc.configure(cfg, 0x3F, 1'500);
  EXPECT_TRUE(o.ok) << o.message;
  ASSERT_EQ(fake.configs().size(), 1u);
  EXPECT_EQ(fake.configs()[0],
            words({static_cast<std::int16_t>(cfg | 0x8000), 0x3F, 1, 500, 0, 0, 0, 0}));
  EXPECT_EQ(outputs_of(c), ImageWords{}) << "back in command mode";
  const Outcome bad = plc.configure(cfg | m::cfg_msw::kReserved, 0x3F, 1'500);
  EXPECT_FALSE(bad.ok);
  EXPECT_NE(bad.message.find("Configuration Error"), std::string::npos) << bad.message;
}

TEST_F(CtlCommands, BlendProgramHandshakeOneBlockPerSegment) {
  BlendProfile b;
  b.segments = {{10'000, 5'000, 10, AccelType::kConstant},
                {12'345, 8'000, 20, AccelType::kTrapezoidalS}};
  b.final_decel = 30;
  b.final_type = AccelType::kTriangularS;
  const Outcome o = plc.blend_program(b);
  EXPECT_TRUE(o.ok) << o.message;
  const auto blocks = fake.blocks();
  ASSERT_EQ(blocks.size(), 3u);
  const std::int32_t pt = m::cmd_lsw::kProgramBlend | m::cmd_lsw::kBlendTransmit;
  // Segment 2 trapezoidal: pair bits 3:2 = 11; final decel type tri = 01 in bits 15..14.
  EXPECT_EQ(blocks[0], words({0, pt, 2, 0, 0b1100, (1 << 14) | 30, 0, 0}));
  EXPECT_EQ(blocks[1], words({0, pt, 10, 0, 5, 0, 10, 0}));
  EXPECT_EQ(blocks[2], words({0, pt, 12, 345, 8, 0, 20, 0}));
  EXPECT_EQ(outputs_of(c), ImageWords{}) << "program bit cleared at the end";
}

TEST_F(CtlCommands, JogHoldsLevelThenReleasesAndWaitsIdle) {
  const auto t0 = std::chrono::steady_clock::now();
  const Outcome o = plc.jog(true, {500, 1, 1}, 50ms);
  EXPECT_GE(std::chrono::steady_clock::now() - t0, 50ms);
  EXPECT_TRUE(o.ok) << o.message;
  ASSERT_EQ(fake.edges().size(), 1u);
  EXPECT_EQ(fake.edges()[0], words({m::cmd_msw::kManualCw, 0, 0, 0, 0, 500, 1, 1}));
  EXPECT_EQ(outputs_of(c).w[0], 0);
  EXPECT_EQ(o.in.w[0] & (m::status_msw::kMovingCw | m::status_msw::kMovingCcw), 0);
}

TEST(CtlPort, TimeoutWithoutModuleScanning) {
  const std::string n = test_name("dead");
  ipc::ShmImage img(n, k3601);  // an image nobody scans
  ipc::Client c(n);
  ShmPort port(c, 30ms);
  Plc3601 plc(port, 30ms);
  const Outcome o = plc.move(true, 1, {1'000, 1, 1});
  EXPECT_FALSE(o.ok);
  EXPECT_TRUE(o.timed_out);
  EXPECT_NE(o.message.find("no answer"), std::string::npos);
}

TEST(CtlPort, OnlyFor3601) {
  const std::string n = test_name("3202");
  ipc::ShmImage img(n, {ModuleType::k3202, 2, 4, 16, 16});
  ipc::Client c(n);
  ShmPort port(c);
  EXPECT_EQ(port.type(), ModuleType::k3202) << "the dialect is chosen from the image header";
  EXPECT_THROW(Plc3601{port}, std::invalid_argument);
}

}  // namespace
}  // namespace stepmod::plc
