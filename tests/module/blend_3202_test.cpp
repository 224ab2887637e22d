// 3202 blend profiles by message (3202 manual Ch.5 "Blend Move Programming", Ch.4 "Blend Move";
// checklist items IP-11..17, CE-17..20): the 52-DINT message as the daemon hands it over from the
// mailbox (Personality::on_message), checked, stored or refused with nothing stored, then run.
#include <array>
#include <vector>

#include "module_types/m3202/blend_message_3202.hpp"
#include "tests/module/plc_3202.hpp"

namespace stepmod::testing {
namespace {

namespace sb = m2::status_bit;
namespace cb = m2::cmd_bit;

struct Segment {
  std::int32_t length;
  std::int32_t speed;
  std::int32_t rate;
};

// The 52 DINTs of a message (3202 manual ch. 5). `final_type` in bits 31-30 of DINT 3.
std::array<std::int32_t, 52> message(std::int32_t channel, const std::vector<Segment>& segs,
                                     std::int32_t final_decel = 100'000,
                                     std::uint32_t final_type = 0, std::uint32_t pairs = 0,
                                     std::int32_t count = -1) {
  std::array<std::int32_t, 52> d{};
  d[0] = channel;
  d[1] = count >= 0 ? count : static_cast<std::int32_t>(segs.size());
  d[2] = static_cast<std::int32_t>(pairs);
  d[3] = static_cast<std::int32_t>((final_type << 30) | static_cast<std::uint32_t>(final_decel));
  for (std::size_t n = 0; n < segs.size() && n < 16; ++n) {
    d[4 + 3 * n] = segs[n].length;
    d[5 + 3 * n] = segs[n].speed;
    d[6 + 3 * n] = segs[n].rate;
  }
  return d;
}

const std::vector<Segment> kTwo = {{10'000, 5'000, 100'000}, {10'000, 2'000, 100'000}};
constexpr Move3202 kZero{.target = 0, .speed = 0, .accel = 0, .decel = 0};

class Blend3202 : public Plc3202 {
 protected:
  void SetUp() override {
    configure(0);
    configure(1);
  }
  std::int32_t send(const std::array<std::int32_t, 52>& d) {
    const std::int32_t r = vm_.stack().personality().on_message(d, vm_.now());
    vm_.scans(2);
    return r;
  }
  // The message was refused: IP on `ch`, and Run Blend then finds no profile (CE-17).
  void expect_refused_and_nothing_stored(unsigned ch, std::int32_t result) {
    EXPECT_EQ(result, m2::kMessageRefused);
    EXPECT_TRUE(status(ch, sb::kInvalidProfile));
    command(ch, cb::kResetErrors, kZero);
    EXPECT_FALSE(status(ch, sb::kInvalidProfile));
    command(ch, cb::kRunBlendCw, kZero);
    vm_.run_for(50 * kNsPerMs);
    EXPECT_TRUE(status(ch, sb::kCommandError));
    EXPECT_EQ(motor(ch), 0);
  }
};

TEST_F(Blend3202, RunBlendPlusAndMinusOutputTheSumOfTheSegments) {
  ASSERT_EQ(send(message(2, kTwo)), m2::kMessageAccepted);
  EXPECT_FALSE(status(1, sb::kInvalidProfile | sb::kCommandError));
  command(1, cb::kRunBlendCw, kZero);
  EXPECT_TRUE(status(1, sb::kBlendRunning));
  ASSERT_TRUE(wait_idle(1));
  vm_.scans(2);
  EXPECT_EQ(motor(1), 20'000);
  EXPECT_TRUE(status(1, sb::kMoveComplete));
  EXPECT_FALSE(status(1, sb::kBlendRunning | sb::kStopped));
  command(1, cb::kRunBlendCcw, kZero);
  ASSERT_TRUE(wait_idle(1));
  EXPECT_EQ(motor(1), 0);
  EXPECT_EQ(motor(0), 0);  // channel 1 untouched
  EXPECT_FALSE(status(0, sb::kInvalidProfile | sb::kCommandError));
}

TEST_F(Blend3202, IP_11_A23_ChannelNotOneOrTwo) {
  for (std::int32_t ch : {0, 3, -1}) {
    EXPECT_EQ(send(message(ch, kTwo)), m2::kMessageRefused);
    EXPECT_TRUE(status(0, sb::kInvalidProfile));
    EXPECT_TRUE(status(1, sb::kInvalidProfile));
    command(0, cb::kResetErrors, kZero);
    command(1, cb::kResetErrors, kZero);
  }
  expect_refused_and_nothing_stored(0, send(message(7, kTwo)));
}

TEST_F(Blend3202, IP_12_SegmentCountOutOfRange) {
  expect_refused_and_nothing_stored(0, send(message(1, {{10'000, 5'000, 100'000}})));
  std::vector<Segment> many;
  for (int i = 0; i < 16; ++i) many.push_back({1'000, i % 2 ? 2'000 : 3'000, 100'000});
  expect_refused_and_nothing_stored(0, send(message(1, many, 100'000, 0, 0, 17)));
  // 16 segments are fine.
  EXPECT_EQ(send(message(1, many)), m2::kMessageAccepted);
}

TEST_F(Blend3202, IP_13_SegmentTooShortToReachItsSpeed) {
  // From Vs 1,000 to 5,000 at 100,000 steps/s^2 needs 120 steps.
  expect_refused_and_nothing_stored(0, send(message(1, {{119, 5'000, 100'000}, kTwo[1]})));
}

TEST_F(Blend3202, IP_14_SameSpeedAsTheSegmentBefore) {
  expect_refused_and_nothing_stored(
      0, send(message(1, {{10'000, 5'000, 100'000}, {10'000, 5'000, 100'000}})));
}

TEST_F(Blend3202, IP_16_SumOfLengthsBeyondTheLimit) {
  expect_refused_and_nothing_stored(
      1, send(message(2, {{4'194'304, 5'000, 100'000}, {4'194'304, 2'000, 100'000}})));
  // Exactly 8,388,607 is accepted.
  EXPECT_EQ(send(message(2, {{4'194'304, 5'000, 100'000}, {4'194'303, 2'000, 100'000}})),
            m2::kMessageAccepted);
}

TEST_F(Blend3202, IP_17_ZeroLengthFinalDecelRangeAndType10) {
  expect_refused_and_nothing_stored(0, send(message(1, {{0, 5'000, 100'000}, kTwo[1]})));
  expect_refused_and_nothing_stored(0, send(message(1, kTwo, 999)));
  expect_refused_and_nothing_stored(0, send(message(1, kTwo, 2'000'001)));
  expect_refused_and_nothing_stored(0, send(message(1, kTwo, 100'000, 0b10)));
  // A garbage segment rate.
  expect_refused_and_nothing_stored(0, send(message(1, {{10'000, 5'000, -7}, kTwo[1]})));
  EXPECT_EQ(send(message(1, kTwo, 100'000, 0b11, 0b0101)), m2::kMessageAccepted);
}

TEST_F(Blend3202, CE_19_MessageWhileTheBlendRunsBringsItDown) {
  ASSERT_EQ(send(message(1, {{200'000, 20'000, 100'000}, {10'000, 2'000, 100'000}})),
            m2::kMessageAccepted);
  command(0, cb::kRunBlendCw, kZero);
  vm_.run_for(500 * kNsPerMs);
  ASSERT_TRUE(status(0, sb::kBlendRunning));
  EXPECT_EQ(send(message(1, kTwo)), m2::kMessageRefused);
  EXPECT_TRUE(status(0, sb::kCommandError));
  ASSERT_TRUE(wait_idle(0, 2 * kNsPerSec));
  EXPECT_LT(motor(0), 210'000);
  EXPECT_FALSE(status(0, sb::kMoveComplete));
  EXPECT_TRUE(status(0, sb::kCommandError));
}

TEST_F(Blend3202, CE_20_HoldDuringABlendClearsAtItsEnd) {
  ASSERT_EQ(send(message(1, kTwo)), m2::kMessageAccepted);
  command(0, cb::kRunBlendCw, kZero);
  command(0, cb::kHold);
  EXPECT_TRUE(status(0, sb::kCommandError));
  ASSERT_TRUE(wait_idle(0));
  vm_.scans(2);
  EXPECT_FALSE(status(0, sb::kCommandError));
  EXPECT_EQ(motor(0), 20'000);
  EXPECT_TRUE(status(0, sb::kMoveComplete));
}

TEST_F(Blend3202, ANewConfigurationErasesTheProfile) {
  ASSERT_EQ(send(message(1, kTwo)), m2::kMessageAccepted);
  ASSERT_EQ(send(message(2, kTwo)), m2::kMessageAccepted);
  configure(0);
  command(0, cb::kRunBlendCw, kZero);
  vm_.run_for(50 * kNsPerMs);
  EXPECT_TRUE(status(0, sb::kCommandError));
  EXPECT_EQ(motor(0), 0);
  // The other channel's profile is kept.
  command(1, cb::kRunBlendCw, kZero);
  ASSERT_TRUE(wait_idle(1));
  EXPECT_EQ(motor(1), 20'000);
}

class Blend3202Unconfigured : public Plc3202 {};

TEST_F(Blend3202Unconfigured, IP_15_MessageBeforeTheChannelIsConfigured) {
  configure(1);
  const auto d = message(1, kTwo);
  EXPECT_EQ(vm_.stack().personality().on_message(d, vm_.now()), m2::kMessageRefused);
  vm_.scans(2);
  EXPECT_TRUE(status(0, sb::kInvalidProfile));
  EXPECT_FALSE(status(1, sb::kInvalidProfile));
}

}  // namespace
}  // namespace stepmod::testing
