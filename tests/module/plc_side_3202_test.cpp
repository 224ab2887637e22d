// The PLC side of the 3202 (module_types/m3202/plc_3202, module_types/m3202/plc_words_3202, module_types/m3202/plc_status_3202) against the module in
// virtual time: what stepmodctl does to a 3202, channel by channel.
#include "module_types/m3202/blend_message_3202.hpp"
#include "module_types/m3202/plc_3202.hpp"
#include "tests/module/plc_3202.hpp"
#include "tests/support/virtual_port.hpp"

namespace stepmod::testing {
namespace {

namespace sb = m2::status_bit;
using plc::AccelType;

constexpr plc::Sequencing kSeq{
    .hold_scans = 3, .release_scans = 1, .config_scans = 3, .release_stale_bits = true};
constexpr plc::Profile kProfile{.speed = 10'000, .accel = 100'000, .decel = 100'000};

class PlcSide3202 : public Plc3202 {
 protected:
  VirtualPort port_{vm_};
  plc::Plc3202 plc_{port_, std::chrono::milliseconds(2000), kSeq};
};

TEST_F(PlcSide3202, ConfigureMoveAndResetPerChannel) {
  ASSERT_TRUE(plc_.configure(0, kFull3202, 1'000).ok);
  ASSERT_TRUE(plc_.configure(1, kFull3202, 1'000).ok);
  const plc::Outcome bad = plc_.configure(1, m2::cfg_bit::kHomeUsed, 1'000);
  EXPECT_FALSE(bad.ok);
  EXPECT_NE(bad.message.find("Configuration Error"), std::string::npos);
  ASSERT_TRUE(plc_.configure(1, kFull3202, 1'000).ok);

  ASSERT_TRUE(plc_.move(0, false, 4'000, kProfile).ok);
  ASSERT_TRUE(
      plc_.move(
              1, false, -3'000,
              {.speed = 8'000, .accel = 50'000, .decel = 50'000, .type = AccelType::kTrapezoidalS})
          .ok);
  ASSERT_TRUE(plc_.wait_idle(0, std::chrono::seconds(10)).ok);
  ASSERT_TRUE(plc_.wait_idle(1, std::chrono::seconds(10)).ok);
  EXPECT_EQ(plc::m3202::decode_status(vm_.plc_in(), 0).position, 4'000);
  EXPECT_EQ(plc::m3202::decode_status(vm_.plc_in(), 1).position, -3'000);
  EXPECT_EQ(motor(0), 4'000);
  EXPECT_EQ(motor(1), -3'000);

  // An error on channel 2 and its reset never touch channel 1.
  EXPECT_FALSE(plc_.resume(1, std::nullopt).ok);
  EXPECT_TRUE(status(1, sb::kCommandError));
  EXPECT_FALSE(status(0, sb::kCommandError));
  ASSERT_TRUE(plc_.reset_errors(1).ok);
  EXPECT_FALSE(status(1, sb::kCommandError));
  ASSERT_TRUE(plc_.preset_position(0, 100).ok);
  ASSERT_TRUE(plc_.move(0, true, 0, kProfile).ok);
  ASSERT_TRUE(plc_.wait_idle(0, std::chrono::seconds(10)).ok);
  EXPECT_EQ(motor(0), 3'900);
}

// The jog's two halves, as a console's held button uses them: the Manual CW bit stays set (the
// channel keeps moving) until jog_release clears it; then the channel decelerates to a stop.
// The other channel's DINTs are never touched.
TEST_F(PlcSide3202, JogPressMovesUntilJogRelease) {
  ASSERT_TRUE(plc_.configure(0, kFull3202, 1'000).ok);
  ASSERT_TRUE(plc_.configure(1, kFull3202, 1'000).ok);
  const ImageWords before = port_.outputs();
  ASSERT_TRUE(plc_.jog_press(0, true, {.speed = 5'000, .accel = 100'000, .decel = 100'000}).ok);
  EXPECT_NE(port_.outputs().w[0] & static_cast<std::int32_t>(m2::cmd_bit::kManualCw), 0);
  port_.pass(std::chrono::milliseconds(300));
  const std::int64_t moved = motor(0);
  EXPECT_GT(moved, 500);
  EXPECT_TRUE(status(0, sb::kMovingCw));
  port_.pass(std::chrono::milliseconds(100));
  EXPECT_GT(motor(0), moved);  // still held: still moving
  ASSERT_TRUE(plc_.jog_release(0).ok);
  EXPECT_EQ(port_.outputs().w[0] & static_cast<std::int32_t>(m2::cmd_bit::kManualCw), 0);
  ASSERT_TRUE(plc_.wait_idle(0, std::chrono::seconds(5)).ok);
  const std::int64_t stopped = motor(0);
  port_.pass(std::chrono::milliseconds(200));
  EXPECT_EQ(motor(0), stopped);
  EXPECT_TRUE(status(0, sb::kStopped));
  EXPECT_EQ(motor(1), 0);
  for (unsigned i = 8; i < 16; ++i) EXPECT_EQ(port_.outputs().w[i], before.w[i]) << "word " << i;
}

TEST_F(PlcSide3202, BlendMessageWordsRunEndToEnd) {
  ASSERT_TRUE(plc_.configure(1, kFull3202, 1'000).ok);
  plc::BlendProfile b;
  b.segments = {{6'000, 5'000, 100'000, AccelType::kTriangularS},
                {4'000, 2'000, 100'000, AccelType::kConstant}};
  b.final_decel = 100'000;
  b.final_type = AccelType::kTrapezoidalS;
  const auto d = plc::m3202::blend_message(2, b);
  EXPECT_EQ(d[2], 0b0001);
  EXPECT_EQ(static_cast<std::uint32_t>(d[3]) >> 30, 0b11u);
  ASSERT_EQ(vm_.stack().personality().on_message(d, vm_.now()), m2::kMessageAccepted);
  ASSERT_TRUE(plc_.blend_run(1, false).ok);
  ASSERT_TRUE(plc_.wait_idle(1, std::chrono::seconds(10)).ok);
  EXPECT_EQ(motor(1), -10'000);
  EXPECT_TRUE(status(1, sb::kMoveComplete));
}

TEST_F(PlcSide3202, JogAndHomeOneChannel) {
  ASSERT_TRUE(plc_.configure(0, kFull3202, 1'000).ok);
  ASSERT_TRUE(plc_.jog(0, true, {.speed = 5'000, .accel = 100'000, .decel = 100'000},
                       std::chrono::milliseconds(200))
                  .ok);
  EXPECT_GT(motor(0), 0);
  EXPECT_TRUE(status(0, sb::kStopped));
  ASSERT_TRUE(plc_.home(0, true, kProfile).ok);
  ASSERT_TRUE(port_.wait_inputs(
      [](const ImageWords& in) { return plc::m3202::decode_status(in, 0).has(sb::kAtHome); },
      std::chrono::seconds(20)));
  EXPECT_EQ(motor(0), 5'000);
}

}  // namespace
}  // namespace stepmod::testing
