// 3601 blend moves in virtual time: the programming handshake (command LSW bits 8/9, status LSW
// bit 9), the block checks (3601 checklist IP-04..07, IP-19..21, A21, A22) and Run Blend
// (CE-20..24, MC-01, STP-N1, IE-02, 3601 manual ch. 4-5).
#include <array>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "tests/module/plc_3601.hpp"

namespace stepmod::testing {
namespace {

using namespace m::status_msw;
namespace cmd = m::cmd_msw;

constexpr std::uint16_t kProgram = m::cmd_lsw::kProgramBlend;
constexpr std::uint16_t kTransmit = m::cmd_lsw::kBlendTransmit;
constexpr std::uint16_t kAck = m::status_lsw::kBlendAcknowledge;
constexpr std::uint16_t kRunning = m::status_lsw::kBlendRunning;

// Final-deceleration word (first block word 5): type in bits 15-14, value in bits 13-0.
constexpr std::int32_t kConstant = 0b00;
constexpr std::int32_t kTriangular = 0b01;
constexpr std::int32_t kInvalidType = 0b10;
constexpr std::int32_t kTrapezoidal = 0b11;
constexpr std::int32_t final_word(std::int32_t type, std::int32_t value) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>((type << 14) | value));
}

struct Seg {
  std::int32_t length;
  std::int32_t speed;
  std::int16_t rate;  // steps/ms/s
};

// A worked blend (3601 manual ch. 4-5; Vs = 1,000, rates 10 steps/ms/s = 10,000 steps/s^2): segment
// 1 needs 1,200 steps to reach 5,000, segment 2 needs 1,950 to reach 8,000 plus 3,150 of final
// deceleration; 20,000 steps in all.
const std::vector<Seg> kWorked = {{10'000, 5'000, 10}, {10'000, 8'000, 10}};
constexpr std::int64_t kWorkedLength = 20'000;

class Blend3601 : public Plc3601 {
 protected:
  void SetUp() override {
    configure();
    command(cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
    ASSERT_FALSE(status(kPositionInvalid));
  }

  // One programming block: words 2..7 with program + transmit, wait for the acknowledge, clear
  // transmit (program held), wait for the acknowledge to clear. Returns whether both happened.
  bool send_block(const std::array<std::int32_t, 6>& w, unsigned hold_scans = 1) {
    auto& o = vm_.plc_out().w;
    o = {};
    o[1] = kProgram | kTransmit;
    for (unsigned i = 0; i < 6; ++i) o[2 + i] = w[i];
    const bool acked = vm_.run_until_true([this] { return lsw_status(kAck); }, 20 * kNsPerMs);
    vm_.scans(hold_scans);
    o[1] = kProgram;
    const bool cleared = vm_.run_until_true([this] { return !lsw_status(kAck); }, 20 * kNsPerMs);
    return acked && cleared;
  }
  bool first_block(std::int32_t count, std::int32_t final_decel, std::int32_t pairs_1_8 = 0,
                   std::int32_t pairs_9_16 = 0) {
    return send_block({count, pairs_9_16, pairs_1_8, final_decel, 0, 0});
  }
  bool segment_block(const Seg& s) {
    const auto l = words::encode_3601(s.length);
    const auto v = words::encode_3601(s.speed);
    return send_block({l.msw, l.lsw, v.msw, v.lsw, s.rate, 0});
  }
  void end_programming() {
    auto& o = vm_.plc_out().w;
    o = {};
    vm_.scans(2);
  }
  // A whole cycle; true if every block was acknowledged.
  bool program(const std::vector<Seg>& segs, std::int32_t final_decel = final_word(kConstant, 10),
               std::int32_t pairs_1_8 = 0, std::int32_t pairs_9_16 = 0) {
    bool ok =
        first_block(static_cast<std::int32_t>(segs.size()), final_decel, pairs_1_8, pairs_9_16);
    for (const Seg& s : segs) ok = segment_block(s) && ok;
    end_programming();
    return ok;
  }
  void run_blend(bool cw = true) {
    command(cw ? cmd::kRunBlendCw : cmd::kRunBlendCcw,
            {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  }
  void reset_errors() {
    command(cmd::kResetErrors, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  }
  bool errors() const {
    return status(kCommandError) || status(kInvalidProfile) || status(kInputError) ||
           status(kHomeInvalid);
  }
  // Run Blend is refused and nothing moves (the profile is not stored).
  void expect_no_profile() {
    const std::int64_t before = motor();
    run_blend();
    EXPECT_TRUE(status(kCommandError));  // 3601-CE-20
    EXPECT_FALSE(lsw_status(kRunning));
    vm_.run_for(50 * kNsPerMs);
    EXPECT_EQ(motor(), before);
  }
  // Runs the stored profile to its end; returns the number of steps output.
  std::int64_t run_to_end(bool cw = true) {
    const std::int64_t before = motor();
    run_blend(cw);
    EXPECT_TRUE(lsw_status(kRunning));
    EXPECT_TRUE(wait_idle(60 * kNsPerSec));
    return std::abs(motor() - before);
  }
  // Period (ns) of the step after step index i (0-based) of the steps output since `from`.
  Nanos period_at(std::size_t from, std::size_t i) const {
    const auto& t = vm_.step_times(0);
    return t[from + i + 1] - t[from + i];
  }
};

// ---- Programming handshake ------------------------------------------------------------------

TEST_F(Blend3601, Handshake_AcknowledgeSetOnTransmitAndClearedWithIt) {
  auto& o = vm_.plc_out().w;
  // Transmit without the program bit is not a block: no acknowledge.
  o[1] = kTransmit;
  vm_.scans(3);
  EXPECT_FALSE(lsw_status(kAck));
  o[1] = 0;
  vm_.scans(2);

  // Step 1-2: first block with program + transmit -> acknowledge.
  o = {};
  o[1] = kProgram | kTransmit;
  o[2] = 2;
  o[5] = final_word(kConstant, 10);
  vm_.scans(2);
  EXPECT_TRUE(lsw_status(kAck));
  // The acknowledge stays while transmit is held; holding it reads no further block.
  vm_.scans(10);
  EXPECT_TRUE(lsw_status(kAck));
  // Step 3-4: transmit cleared, program held -> acknowledge cleared.
  o[1] = kProgram;
  vm_.scans(2);
  EXPECT_FALSE(lsw_status(kAck));
  // Step 5: each 0 -> 1 of transmit hands over the next block.
  for (const Seg& s : kWorked) {
    EXPECT_TRUE(segment_block(s));
  }
  EXPECT_FALSE(errors());
  // Step 6: program cleared -> the profile is complete and runs.
  end_programming();
  EXPECT_FALSE(lsw_status(kAck));
  EXPECT_EQ(run_to_end(), kWorkedLength);
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(errors());
}

TEST_F(Blend3601, Handshake_TransmitHeldForManyScansReadsOneBlock) {
  ASSERT_TRUE(send_block({2, 0, 0, final_word(kConstant, 10), 0, 0}, 20));
  for (const Seg& s : kWorked) {
    const auto l = words::encode_3601(s.length);
    const auto v = words::encode_3601(s.speed);
    ASSERT_TRUE(send_block({l.msw, l.lsw, v.msw, v.lsw, s.rate, 0}, 20));
  }
  end_programming();
  EXPECT_FALSE(errors());  // no "block beyond the count" (A21c)
  EXPECT_EQ(run_to_end(), kWorkedLength);
}

TEST_F(Blend3601, Handshake_NewCycleReplacesTheStoredProfile) {
  ASSERT_TRUE(program(kWorked));
  EXPECT_EQ(run_to_end(), kWorkedLength);
  ASSERT_TRUE(program({{3'000, 2'000, 10}, {3'000, 3'000, 10}}));
  EXPECT_FALSE(errors());
  EXPECT_EQ(run_to_end(), 6'000);
}

// ---- Run Blend: command errors --------------------------------------------------------------

TEST_F(Blend3601, CE_20_RunBlendWithNoProfileEverProgrammed) {
  run_blend();
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(status(kMoveComplete));
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
  EXPECT_TRUE(vm_.step_times(0).empty());
}

TEST_F(Blend3601, CE_20_ConfigurationErasesTheProfile) {
  ASSERT_TRUE(program(kWorked));
  EXPECT_EQ(run_to_end(), kWorkedLength);
  configure();
  EXPECT_FALSE(status(kCommandError));
  const auto steps = vm_.step_times(0).size();
  run_blend();
  EXPECT_TRUE(status(kCommandError));
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(vm_.step_times(0).size(), steps);
}

TEST_F(Blend3601, CE_21_RunBlendWithAnyNonZeroParameterWord) {
  ASSERT_TRUE(program(kWorked));
  for (unsigned w = 2; w <= 7; ++w) {
    SCOPED_TRACE(w);
    auto& o = vm_.plc_out().w;
    o = {};
    o[0] = cmd::kRunBlendCw;
    o[w] = 1;
    vm_.scans(3);
    o = {};
    vm_.scans(1);
    EXPECT_TRUE(status(kCommandError));
    EXPECT_FALSE(lsw_status(kRunning));
    EXPECT_FALSE(moving());
    reset_errors();
    ASSERT_FALSE(status(kCommandError));
  }
  EXPECT_EQ(motor(), 0);
  // With all of them 0 the same profile runs.
  EXPECT_EQ(run_to_end(), kWorkedLength);
}

TEST_F(Blend3601, CE_15_RunBlendWithNonZeroCommandLsw) {
  ASSERT_TRUE(program(kWorked));
  command(cmd::kRunBlendCcw, {.target = 0, .speed = 0, .accel = 0, .decel = 0, .lsw = 0x0001});
  EXPECT_TRUE(status(kCommandError));
  vm_.run_for(50 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
}

TEST_F(Blend3601, CE_03_RunBlendWhileAMoveRunsLeavesTheMove) {
  ASSERT_TRUE(program(kWorked));
  command(cmd::kRelativeMove, {.target = 10'000});
  run_blend();
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(lsw_status(kRunning));
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), 10'000);
  EXPECT_TRUE(status(kMoveComplete));
}

TEST_F(Blend3601, CE_22_ProgrammingDuringABlendStopsItWithTheFinalDeceleration) {
  // Final deceleration 4 steps/ms/s, segment rates 10: a stop from 5,000 to Vs = 1,000 takes
  // (5,000^2 - 1,000^2) / (2 * 4,000) = 3,000 steps and 1 s with the final deceleration
  // (1,200 steps and 0.4 s with the segment's rate).
  const std::vector<Seg> profile = {{10'000, 5'000, 10}, {10'000, 8'000, 10}};
  ASSERT_TRUE(program(profile, final_word(kConstant, 4)));
  run_blend();
  vm_.run_for(1'000 * kNsPerMs);  // segment 1 cruise at 5,000 steps/s
  ASSERT_TRUE(lsw_status(kRunning));
  const std::int64_t at_request = motor();
  const Nanos t_request = vm_.now();
  // A new programming cycle: first block with program + transmit.
  auto& o = vm_.plc_out().w;
  o = {};
  o[1] = kProgram | kTransmit;
  o[2] = 2;
  o[5] = final_word(kConstant, 10);
  vm_.scans(2);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(lsw_status(kAck));  // the block is still acknowledged
  EXPECT_TRUE(lsw_status(kRunning));
  ASSERT_TRUE(wait_idle());
  const std::int64_t stop_steps = motor() - at_request;
  EXPECT_NEAR(static_cast<double>(stop_steps), 3'000.0, 60.0);
  const auto& t = vm_.step_times(0);
  EXPECT_NEAR(static_cast<double>(t.back() - t_request) / 1e9, 1.0, 0.03);
  // Controlled: the last period is about 1/Vs.
  EXPECT_NEAR(static_cast<double>(t[t.size() - 1] - t[t.size() - 2]), 1e6, 0.1e6);
  EXPECT_LT(motor(), kWorkedLength);
  EXPECT_FALSE(lsw_status(kRunning));
  EXPECT_TRUE(status(kCommandError));      // does not clear by itself
  EXPECT_FALSE(status(kMoveComplete));     // 3601-MC-02
  EXPECT_FALSE(status(kStopped));          // 3601-STP-N1
  EXPECT_FALSE(status(kPositionInvalid));  // a controlled stop
  // The refused cycle stored nothing: the old profile still runs after Reset Errors.
  end_programming();
  reset_errors();
  ASSERT_FALSE(status(kCommandError));
  EXPECT_EQ(run_to_end(), kWorkedLength);
  EXPECT_TRUE(status(kMoveComplete));
}

TEST_F(Blend3601, CE_23_HoldDuringABlendSetsCeThatClearsAtTheEnd) {
  ASSERT_TRUE(program(kWorked));
  run_blend();
  vm_.run_for(800 * kNsPerMs);
  command(cmd::kHold);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(lsw_status(kRunning));
  vm_.run_for(500 * kNsPerMs);
  EXPECT_TRUE(status(kCommandError));  // set for the rest of the blend
  EXPECT_TRUE(moving());
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), kWorkedLength);    // the blend was not held
  EXPECT_FALSE(status(kCommandError));  // CE-L3: cleared by itself
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(status(kHoldState));
  EXPECT_FALSE(status(kStopped));
}

TEST_F(Blend3601, CE_23_ACommandErrorWithAnotherReasonDoesNotClearItself) {
  // Decision (blend_3601.cpp): only the Hold's CE clears at the blend's end. Here it is reset,
  // then a Run Blend during the blend raises CE-03, which must stay.
  ASSERT_TRUE(program(kWorked));
  run_blend();
  vm_.run_for(500 * kNsPerMs);
  command(cmd::kHold);
  ASSERT_TRUE(status(kCommandError));
  reset_errors();
  ASSERT_FALSE(status(kCommandError));
  run_blend();  // 3601-CE-03
  EXPECT_TRUE(status(kCommandError));
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), kWorkedLength);
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_TRUE(status(kCommandError));
}

// ---- Programming errors ---------------------------------------------------------------------

TEST_F(Blend3601, CE_24_IP_07_FirstBlockWithoutFinalDecelerationValue) {
  ASSERT_TRUE(first_block(2, final_word(kTrapezoidal, 0)));  // acknowledged (A21d)
  EXPECT_TRUE(status(kCommandError));                        // 3601-CE-24
  EXPECT_TRUE(status(kInvalidProfile));                      // 3601-IP-07 (A21a: both)
  for (const Seg& s : kWorked) EXPECT_TRUE(segment_block(s));
  end_programming();
  reset_errors();
  expect_no_profile();
}

TEST_F(Blend3601, IP_04_SegmentCountOutside2To16) {
  for (const std::int32_t count : {1, 17, 0, -2}) {
    SCOPED_TRACE(count);
    EXPECT_TRUE(first_block(count, final_word(kConstant, 10)));
    EXPECT_TRUE(status(kInvalidProfile));
    EXPECT_FALSE(status(kCommandError));
    for (const Seg& s : kWorked) EXPECT_TRUE(segment_block(s));
    end_programming();
    expect_no_profile();
    reset_errors();
    ASSERT_FALSE(errors());
  }
  // 16 segments is the maximum and is accepted.
  std::vector<Seg> segs;
  for (int i = 0; i < 16; ++i) segs.push_back({500, i % 2 == 0 ? 2'000 : 1'500, 20});
  segs.back().length = 1'000;
  ASSERT_TRUE(program(segs, final_word(kConstant, 20)));
  EXPECT_FALSE(errors());
  EXPECT_EQ(run_to_end(), 15 * 500 + 1'000);
}

TEST_F(Blend3601, IP_05_WorkedCheckSegmentTooShortToReachItsSpeed) {
  // 3601 manual ch. 4-5: segment 1 shortened to 1,000 cannot reach 5,000 (it needs 1,200).
  ASSERT_TRUE(first_block(2, final_word(kConstant, 10)));
  ASSERT_TRUE(segment_block({1'000, 5'000, 10}));
  EXPECT_TRUE(status(kInvalidProfile));  // reported with the segment's own block
  EXPECT_TRUE(segment_block(kWorked[1]));
  end_programming();
  expect_no_profile();
  // 1,200 is exactly enough.
  reset_errors();
  ASSERT_TRUE(program({{1'200, 5'000, 10}, kWorked[1]}));
  EXPECT_FALSE(errors());
  EXPECT_EQ(run_to_end(), 11'200);
}

TEST_F(Blend3601, IP_05_A21_LastSegmentMustHoldTheFinalDeceleration) {
  // Segment 2 needs 1,950 steps to reach 8,000 and 3,150 to decelerate to Vs: 5,100.
  ASSERT_TRUE(program({kWorked[0], {5'099, 8'000, 10}}));
  EXPECT_TRUE(status(kInvalidProfile));
  expect_no_profile();
  reset_errors();
  ASSERT_TRUE(program({kWorked[0], {5'100, 8'000, 10}}));
  EXPECT_FALSE(errors());
  EXPECT_EQ(run_to_end(), 15'100);
  EXPECT_TRUE(status(kMoveComplete));
}

TEST_F(Blend3601, IP_05_DecelerationSegmentTooShort) {
  // Segment 2 decelerates 8,000 -> 3,000 at 10,000 steps/s^2: 2,750 steps, plus the final
  // deceleration 3,000 -> 1,000 at 20,000: 200 steps.
  ASSERT_TRUE(program({{10'000, 8'000, 10}, {2'949, 3'000, 10}}, final_word(kConstant, 20)));
  EXPECT_TRUE(status(kInvalidProfile));
  reset_errors();
  ASSERT_TRUE(program({{10'000, 8'000, 10}, {2'950, 3'000, 10}}, final_word(kConstant, 20)));
  EXPECT_FALSE(errors());
  EXPECT_EQ(run_to_end(false), 12'950);
  EXPECT_EQ(motor(), -12'950);
}

TEST_F(Blend3601, IP_05_TypePairsOfSegments9To16InWord3) {
  // Ten segments, 1,000 steps/s apart. Segment 10 (10,000 -> 11,000 at 10,000 steps/s^2) needs
  // 1,050 steps constant, 1,400 trapezoidal S, 2,100 triangular S, plus 3,000 of final
  // deceleration (11,000 -> 1,000 at 20,000): 4,500 holds every type but triangular S.
  std::vector<Seg> segs;
  for (int i = 1; i <= 10; ++i) segs.push_back({4'500, 1'000 + 1'000 * i, 10});
  const std::int32_t seg10 = 2 * (10 - 9);  // bit of segment 10's pair in word 3
  ASSERT_TRUE(program(segs, final_word(kConstant, 20), 0, 0b01 << seg10));
  EXPECT_TRUE(status(kInvalidProfile));  // triangular S: does not fit
  reset_errors();
  ASSERT_TRUE(program(segs, final_word(kConstant, 20), 0, 0b11 << seg10));
  EXPECT_FALSE(errors());  // trapezoidal S fits
  ASSERT_TRUE(program(segs, final_word(kConstant, 20), 0b01 << 2, 0));
  EXPECT_FALSE(errors());  // word 4 bits 3:2 are segment 2's, not segment 10's
  EXPECT_EQ(run_to_end(), 45'000);
}

TEST_F(Blend3601, IP_06_ConsecutiveSegmentsWithTheSameSpeed) {
  // 3601 manual ch. 4-5: segment 2's speed changed to 5,000 = segment 1's.
  ASSERT_TRUE(first_block(2, final_word(kConstant, 10)));
  ASSERT_TRUE(segment_block(kWorked[0]));
  EXPECT_FALSE(status(kInvalidProfile));
  ASSERT_TRUE(segment_block({10'000, 5'000, 10}));
  EXPECT_TRUE(status(kInvalidProfile));
  end_programming();
  expect_no_profile();
}

TEST_F(Blend3601, IP_19_FinalDecelerationTypeBinary10IsInvalid) {
  ASSERT_TRUE(program(kWorked, final_word(kInvalidType, 10)));
  EXPECT_TRUE(status(kInvalidProfile));
  EXPECT_FALSE(status(kCommandError));
  reset_errors();
  expect_no_profile();
  // 00, 01 and 11 are valid types.
  for (const std::int32_t type : {kConstant, kTriangular, kTrapezoidal}) {
    reset_errors();
    ASSERT_TRUE(program(kWorked, final_word(type, 10)));
    EXPECT_FALSE(errors());
  }
  EXPECT_EQ(run_to_end(), kWorkedLength);
}

TEST_F(Blend3601, IP_20_SegmentLengthRestrictions) {
  struct Case {
    const char* what;
    std::int32_t msw, lsw;  // segment 1 length words
  };
  for (const Case& c : {Case{"zero", 0, 0}, Case{"negative", -1, 0}, Case{"negative LSW", 0, -5},
                        Case{"LSW 1000", 10, 1'000}}) {
    SCOPED_TRACE(c.what);
    ASSERT_TRUE(first_block(2, final_word(kConstant, 10)));
    const auto v = words::encode_3601(5'000);
    ASSERT_TRUE(send_block({c.msw, c.lsw, v.msw, v.lsw, 10, 0}));  // acknowledged (A21d)
    EXPECT_TRUE(status(kInvalidProfile));
    ASSERT_TRUE(segment_block(kWorked[1]));
    end_programming();
    expect_no_profile();
    reset_errors();
    ASSERT_FALSE(errors());
  }
  // Sum of the lengths: 8,388,607 is the maximum.
  ASSERT_TRUE(program({{4'194'304, 5'000, 10}, {4'194'304, 8'000, 10}}));
  EXPECT_TRUE(status(kInvalidProfile));
  expect_no_profile();
  reset_errors();
  ASSERT_TRUE(program({{4'194'304, 5'000, 10}, {4'194'303, 8'000, 10}}));
  EXPECT_FALSE(errors());
  run_blend();
  EXPECT_FALSE(status(kCommandError));
  EXPECT_TRUE(lsw_status(kRunning));
  command(cmd::kImmediateStop);
  EXPECT_TRUE(wait_idle(100 * kNsPerMs));
}

TEST_F(Blend3601, IP_21_AcknowledgeIsGivenForABlockWithAnError) {
  ASSERT_TRUE(first_block(3, final_word(kConstant, 10)));
  ASSERT_TRUE(segment_block(kWorked[0]));
  EXPECT_FALSE(status(kInvalidProfile));
  // Segment 2 with a rate of 0: out of range. Still acknowledged, IP set.
  EXPECT_TRUE(segment_block({10'000, 8'000, 0}));
  EXPECT_TRUE(status(kInvalidProfile));
  EXPECT_FALSE(status(kCommandError));
  // The rest of the cycle is acknowledged too; nothing is stored.
  EXPECT_TRUE(segment_block({10'000, 3'000, 10}));
  end_programming();
  expect_no_profile();
}

TEST_F(Blend3601, IP_02_SegmentSpeedAndRateRanges) {
  const std::vector<std::vector<Seg>> bad = {
      {{10'000, 5'000, 2'001}, kWorked[1]},      // rate above 2,000
      {{10'000, 5'000, -3}, kWorked[1]},         // negative rate
      {kWorked[0], {20'000, 1'000'001, 2'000}},  // speed above 1,000,000
  };
  for (const auto& segs : bad) {
    ASSERT_TRUE(program(segs));
    EXPECT_TRUE(status(kInvalidProfile));
    expect_no_profile();
    reset_errors();
  }
  // 1,000,000 is the maximum speed (at 2,000,000 steps/s^2: 250,000 steps up, 250,000 down).
  ASSERT_TRUE(program({kWorked[0], {600'000, 1'000'000, 2'000}}, final_word(kConstant, 2'000)));
  EXPECT_FALSE(errors());
}

TEST_F(Blend3601, CE_05_IP_01_SegmentSpeedBelowStartingSpeed) {
  ASSERT_TRUE(program({{10'000, 999, 10}, kWorked[1]}));
  EXPECT_TRUE(status(kInvalidProfile));
  EXPECT_TRUE(status(kCommandError));
  reset_errors();
  expect_no_profile();
  // Vs itself is allowed for segment 1 (no transition).
  reset_errors();
  ASSERT_TRUE(program({{2'000, 1'000, 10}, kWorked[1]}));
  EXPECT_FALSE(errors());
  EXPECT_EQ(run_to_end(), 12'000);
}

TEST_F(Blend3601, A21_FewerSegmentBlocksThanDeclaredIsNotAProfile) {
  ASSERT_TRUE(first_block(3, final_word(kConstant, 10)));
  for (const Seg& s : kWorked) ASSERT_TRUE(segment_block(s));
  end_programming();
  EXPECT_FALSE(status(kInvalidProfile));
  expect_no_profile();  // Run Blend -> CE
}

TEST_F(Blend3601, A21_ASegmentBlockBeyondTheCountIsAnError) {
  ASSERT_TRUE(first_block(2, final_word(kConstant, 10)));
  for (const Seg& s : kWorked) ASSERT_TRUE(segment_block(s));
  EXPECT_FALSE(status(kInvalidProfile));
  EXPECT_TRUE(segment_block({10'000, 3'000, 10}));
  EXPECT_TRUE(status(kInvalidProfile));
  end_programming();
  expect_no_profile();
}

TEST_F(Blend3601, A21_ProgrammingStartsOnlyWithCommandErrorCleared) {
  run_blend();  // CE-20: CE set
  ASSERT_TRUE(status(kCommandError));
  // 3601-CE-L1: the cycle is refused (acknowledged, IP), nothing stored.
  ASSERT_TRUE(program(kWorked));
  EXPECT_TRUE(status(kInvalidProfile));
  reset_errors();
  expect_no_profile();
}

TEST_F(Blend3601, A22_SegmentPairBinary10IsConstant) {
  // The same profile with constant, "10" and triangular S pairs on both segments.
  const auto run_with = [this](std::int32_t pairs) {
    EXPECT_TRUE(program(kWorked, final_word(kConstant, 10), pairs));
    EXPECT_FALSE(errors());
    const std::size_t from = vm_.step_times(0).size();
    EXPECT_EQ(run_to_end(), kWorkedLength);
    const auto& t = vm_.step_times(0);
    std::vector<Nanos> rel;
    for (std::size_t i = from; i < t.size(); ++i) rel.push_back(t[i] - t[from]);
    command(cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
    return rel;
  };
  const auto constant = run_with(0b0000);
  const auto ten = run_with(0b1010);
  const auto triangular = run_with(0b0101);
  ASSERT_EQ(constant.size(), static_cast<std::size_t>(kWorkedLength));
  ASSERT_EQ(ten.size(), constant.size());
  ASSERT_EQ(triangular.size(), constant.size());
  EXPECT_EQ(ten, constant);
  EXPECT_NE(triangular, constant);
  // Segment 1's ramp takes 0.4 s constant and 0.8 s triangular S: step 1,200 is reached later.
  EXPECT_GT(triangular[1'200], constant[1'200] + 100 * kNsPerMs);
}

// ---- Running a blend ------------------------------------------------------------------------

TEST_F(Blend3601, MC_01_BlendRunsExactlyTheSumOfTheLengthsBothWays) {
  ASSERT_TRUE(program(kWorked));
  EXPECT_EQ(run_to_end(true), kWorkedLength);
  EXPECT_EQ(motor(), kWorkedLength);
  EXPECT_EQ(position(), kWorkedLength);
  EXPECT_EQ(vm_.step_times(0).size(), static_cast<std::size_t>(kWorkedLength));
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(errors());

  run_blend(false);
  EXPECT_FALSE(status(kMoveComplete));  // 3601-MC-03: cleared at the start
  EXPECT_TRUE(status(kMovingCcw));
  ASSERT_TRUE(wait_idle(60 * kNsPerSec));
  EXPECT_EQ(motor(), 0);
  EXPECT_EQ(position(), 0);
  EXPECT_EQ(vm_.step_times(0).size(), static_cast<std::size_t>(2 * kWorkedLength));
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(errors());
}

TEST_F(Blend3601, MC_01_PositionNeedNotBeValid) {
  configure();  // position invalid
  ASSERT_TRUE(status(kPositionInvalid));
  ASSERT_TRUE(program(kWorked));
  EXPECT_EQ(run_to_end(false), kWorkedLength);
  EXPECT_EQ(position(), -kWorkedLength);
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_TRUE(status(kPositionInvalid));  // a blend does not validate it
  EXPECT_FALSE(status(kCommandError));
}

TEST_F(Blend3601, MC_01_EachSegmentReachesItsSpeed) {
  ASSERT_TRUE(program(kWorked));
  const std::size_t from = vm_.step_times(0).size();
  ASSERT_EQ(run_to_end(), kWorkedLength);
  // Segment 1 cruises at 5,000 steps/s from step 1,200 to 10,000.
  for (std::size_t i : {1'500u, 5'000u, 9'900u}) {
    EXPECT_NEAR(static_cast<double>(period_at(from, i)), 1e9 / 5'000, 1'000.0) << i;
  }
  // Segment 2 cruises at 8,000 steps/s from step 11,950 to 16,850.
  for (std::size_t i : {12'000u, 14'000u, 16'800u}) {
    EXPECT_NEAR(static_cast<double>(period_at(from, i)), 1e9 / 8'000, 1'000.0) << i;
  }
  // In the ramps the speed lies between the two segment speeds.
  EXPECT_GT(period_at(from, 10'900), 1e9 / 8'000 + 1'000);
  EXPECT_LT(period_at(from, 10'900), 1e9 / 5'000 - 1'000);
  // The final deceleration ends at Vs: the last period is about 1 ms.
  EXPECT_NEAR(static_cast<double>(period_at(from, kWorkedLength - 2)), 1e6, 0.1e6);
  // Total time: 0.4 + 1.76 + 0.3 + 0.6125 + 0.7 = 3.7725 s.
  const auto& t = vm_.step_times(0);
  EXPECT_NEAR(static_cast<double>(t.back() - t[from]) / 1e9, 3.7725, 0.01);
}

TEST_F(Blend3601, LSW_01_BlendRunningBitForTheWholeMove) {
  ASSERT_TRUE(program(kWorked));
  EXPECT_FALSE(lsw_status(kRunning));
  run_blend();
  bool saw_decel = false;
  while (moving()) {
    EXPECT_TRUE(lsw_status(kRunning));
    saw_decel |= status(kDecelerating);
    vm_.scans(20);
  }
  EXPECT_TRUE(saw_decel);
  EXPECT_FALSE(lsw_status(kRunning));
  EXPECT_EQ(motor(), kWorkedLength);
}

TEST_F(Blend3601, STP_N1_StoppedNotSetAfterABlend) {
  ASSERT_TRUE(program(kWorked));
  EXPECT_EQ(run_to_end(), kWorkedLength);
  EXPECT_FALSE(status(kStopped));
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(status(kHoldState));
}

TEST_F(Blend3601, ProfileRunsAnyNumberOfTimesWithOtherMovesBetween) {
  ASSERT_TRUE(program(kWorked));
  EXPECT_EQ(run_to_end(), kWorkedLength);
  EXPECT_EQ(run_to_end(), kWorkedLength);
  command(cmd::kRelativeMove, {.target = -5'000});
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(run_to_end(false), kWorkedLength);
  EXPECT_EQ(position(), 2 * kWorkedLength - 5'000 - kWorkedLength);
  EXPECT_EQ(motor(), position());
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(errors());
}

TEST_F(Blend3601, IE_02_EitherLimitStopsABlendImmediately) {
  ASSERT_TRUE(program(kWorked));
  for (const InputLine limit : {InputLine::kCcwLimit, InputLine::kCwLimit}) {
    SCOPED_TRACE(static_cast<int>(limit));
    run_blend();  // CW: the CCW limit lies behind it, still a stop (either limit)
    vm_.run_for(1'000 * kNsPerMs);
    ASSERT_TRUE(lsw_status(kRunning));
    const std::int64_t at = motor();
    force(limit, true);
    ASSERT_TRUE(wait_idle(20 * kNsPerMs));
    EXPECT_LE(motor() - at, 5);  // no deceleration ramp (5,000 steps/s: 1,200 steps)
    EXPECT_TRUE(status(kInputError));
    EXPECT_TRUE(status(kPositionInvalid));
    EXPECT_TRUE(status(kStopped));  // 3601-STP-04
    EXPECT_FALSE(status(kMoveComplete));
    EXPECT_FALSE(lsw_status(kRunning));
    release(limit);
    reset_errors();
    command(cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  }
}

TEST_F(Blend3601, IE_02_LimitSwitchReachedDuringABlend) {
  // The machine's CW limit is at +100,000: a blend of 120,000 steps from 0 runs into it.
  ASSERT_TRUE(program({{60'000, 5'000, 10}, {60'000, 8'000, 10}}));
  run_blend();
  ASSERT_TRUE(wait_idle(60 * kNsPerSec));
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_FALSE(status(kMoveComplete));
  EXPECT_NEAR(static_cast<double>(motor()), 100'000.0, 5.0);
}

TEST_F(Blend3601, IE_01_EStopStopsABlendImmediately) {
  ASSERT_TRUE(program(kWorked));
  run_blend(false);
  vm_.run_for(1'000 * kNsPerMs);
  const std::int64_t at = motor();
  force(InputLine::kEStop, true);
  ASSERT_TRUE(wait_idle(20 * kNsPerMs));
  EXPECT_GE(motor() - at, -5);
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(status(kMoveComplete));
}

TEST_F(Blend3601, A15_RunBlendWithEStopOrLimitAheadActive) {
  ASSERT_TRUE(program(kWorked));
  force(InputLine::kEStop, true);
  vm_.scans(2);
  run_blend();
  EXPECT_TRUE(status(kInputError));
  EXPECT_FALSE(status(kCommandError));
  vm_.run_for(50 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
  release(InputLine::kEStop);
  force(InputLine::kCwLimit, true);
  vm_.scans(2);
  run_blend(true);  // toward the active limit: refused
  EXPECT_TRUE(status(kInputError));
  vm_.run_for(50 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
  EXPECT_EQ(run_to_end(false), kWorkedLength);  // away from it: runs, and clears IE
  EXPECT_FALSE(status(kInputError));
  EXPECT_TRUE(status(kMoveComplete));
}

TEST_F(Blend3601, ExternalInputIsIgnoredDuringABlend) {
  ASSERT_TRUE(program(kWorked));
  run_blend();
  vm_.run_for(1'000 * kNsPerMs);
  force(InputLine::kExternal, true);
  vm_.run_for(500 * kNsPerMs);
  ASSERT_TRUE(lsw_status(kRunning));
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), kWorkedLength);
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(status(kHoldState));
  EXPECT_FALSE(status(kStopped));
  // Active at the start too: no one-step hold as for absolute/relative moves.
  EXPECT_EQ(run_to_end(false), kWorkedLength);
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(status(kHoldState));
}

}  // namespace
}  // namespace stepmod::testing
