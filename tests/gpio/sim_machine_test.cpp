// The simulated axis: motor position from the pulse outputs, switches, encoder, panel forcing.
#include "gpio/sim_machine.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace stepmod::gpio {
namespace {

constexpr std::uint16_t kAllInputs = (1u << kInputLinesPerAxis) - 1;

std::vector<InputEvent> drain(SimMachine& m) {
  std::vector<InputEvent> all;
  InputEvent buf[8];
  for (;;) {
    const std::size_t n = m.poll(buf);
    if (n == 0) return all;
    all.insert(all.end(), buf, buf + n);
  }
}

std::vector<InputEvent> only(const std::vector<InputEvent>& ev, InputLine line) {
  std::vector<InputEvent> r;
  for (const auto& e : ev) {
    if (e.line == line) r.push_back(e);
  }
  return r;
}

// One step pulse (rising then falling edge) at time t.
void pulse(SimMachine& m, OutputLine line, Nanos t) {
  m.write(line, true, t);
  m.write(line, false, t + 1000);
}

// n step/dir steps starting at t0, 10 us apart; positive n = dir high (CW).
Nanos steps(SimMachine& m, int n, Nanos t0) {
  m.write(OutputLine::kDir, n > 0, t0);
  Nanos t = t0 + 5000;
  for (int i = 0; i < (n > 0 ? n : -n); ++i, t += 10'000) pulse(m, OutputLine::kStep, t);
  return t;
}

SimAxisParams no_encoder() {
  SimAxisParams p;
  p.encoder_ratio = 0;
  return p;
}

TEST(GpioSimMachine, StepDirRisingStepMovesByDirLevel) {
  SimMachine m(0, no_encoder(), kAllInputs);
  EXPECT_EQ(m.position(), 0);
  m.write(OutputLine::kDir, true, 10);
  EXPECT_EQ(m.position(), 0) << "dir alone never moves";
  m.write(OutputLine::kStep, true, 20);
  EXPECT_EQ(m.position(), 1);
  m.write(OutputLine::kStep, true, 30);
  EXPECT_EQ(m.position(), 1) << "writing the same level is no edge";
  m.write(OutputLine::kStep, false, 40);
  EXPECT_EQ(m.position(), 1) << "falling edges do not step";
  pulse(m, OutputLine::kStep, 50);
  EXPECT_EQ(m.position(), 2);
  m.write(OutputLine::kDir, false, 100);
  pulse(m, OutputLine::kStep, 200);
  pulse(m, OutputLine::kStep, 300);
  pulse(m, OutputLine::kStep, 400);
  EXPECT_EQ(m.position(), -1);
  m.write(OutputLine::kGpo, true, 500);
  EXPECT_EQ(m.position(), -1);
}

TEST(GpioSimMachine, CwCcwFormatStepLineIsCwDirLineIsCcw) {
  SimAxisParams p = no_encoder();
  p.start_position = 10;
  SimMachine m(0, p, kAllInputs);
  m.set_pulse_format(PulseFormat::kCwCcw);
  EXPECT_EQ(m.position(), 10);
  pulse(m, OutputLine::kStep, 100);
  pulse(m, OutputLine::kStep, 200);
  EXPECT_EQ(m.position(), 12);
  pulse(m, OutputLine::kDir, 300);
  EXPECT_EQ(m.position(), 11);
  m.write(OutputLine::kDir, true, 400);  // a held CCW line is one pulse only
  m.write(OutputLine::kDir, true, 500);
  EXPECT_EQ(m.position(), 10);
  m.set_pulse_format(PulseFormat::kStepDir);
  pulse(m, OutputLine::kStep, 600);  // dir is high: CW in step/dir format
  EXPECT_EQ(m.position(), 11);
}

TEST(GpioSimMachine, OutputLevelsArePublished) {
  SimMachine m(0, no_encoder(), kAllInputs);
  EXPECT_EQ(m.output_levels(), 0u);
  m.write(OutputLine::kStep, true, 1);
  EXPECT_EQ(m.output_levels(), 1u);
  m.write(OutputLine::kDir, true, 2);
  m.write(OutputLine::kGpo, true, 3);
  EXPECT_EQ(m.output_levels(), 7u);
  m.write(OutputLine::kStep, false, 4);
  EXPECT_EQ(m.output_levels(), 6u);
}

SimAxisParams switches(bool nc) {
  SimAxisParams p = no_encoder();
  p.cw_limit_at = 3;
  p.ccw_limit_at = -2;
  p.home_from = 1;
  p.home_to = 2;
  p.contacts_nc = nc;
  return p;
}

TEST(GpioSimMachine, NormallyOpenSwitchesGoHighWhileActuatedWithEventsAtTheStepTime) {
  SimMachine m(0, switches(false), kAllInputs);
  EXPECT_FALSE(m.read(InputLine::kHome));
  EXPECT_FALSE(m.read(InputLine::kCwLimit));
  EXPECT_FALSE(m.read(InputLine::kCcwLimit));
  EXPECT_FALSE(m.read(InputLine::kEStop));
  m.write(OutputLine::kDir, true, 0);
  m.write(OutputLine::kStep, true, 1000);  // -> 1: home
  auto ev = drain(m);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].line, InputLine::kHome);
  EXPECT_TRUE(ev[0].level);
  EXPECT_EQ(ev[0].t, 1000);
  EXPECT_TRUE(m.read(InputLine::kHome));

  m.write(OutputLine::kStep, false, 1500);
  m.write(OutputLine::kStep, true, 2000);  // -> 2: still home
  EXPECT_TRUE(drain(m).empty());
  m.write(OutputLine::kStep, false, 2500);
  m.write(OutputLine::kStep, true, 3000);  // -> 3: home off, CW limit on
  ev = drain(m);
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].line, InputLine::kCwLimit);
  EXPECT_TRUE(ev[0].level);
  EXPECT_EQ(ev[0].t, 3000);
  EXPECT_EQ(ev[1].line, InputLine::kHome);
  EXPECT_FALSE(ev[1].level);
  EXPECT_EQ(ev[1].t, 3000);
  EXPECT_TRUE(m.read(InputLine::kCwLimit));
  m.write(OutputLine::kStep, false, 3500);
  pulse(m, OutputLine::kStep, 4000);  // -> 4: limit stays actuated beyond
  EXPECT_EQ(m.position(), 4);
  EXPECT_TRUE(drain(m).empty());

  // Back to -2: CW limit releases at 2, home on 2..1, CCW limit at -2.
  const Nanos end = steps(m, -6, 10'000);
  (void)end;
  EXPECT_EQ(m.position(), -2);
  ev = drain(m);
  ASSERT_EQ(ev.size(), 4u);
  EXPECT_EQ(ev[0].line, InputLine::kCwLimit);  // at 2
  EXPECT_FALSE(ev[0].level);
  EXPECT_EQ(ev[1].line, InputLine::kHome);  // at 2
  EXPECT_TRUE(ev[1].level);
  EXPECT_EQ(ev[0].t, ev[1].t);
  EXPECT_EQ(ev[2].line, InputLine::kHome);  // at 0
  EXPECT_FALSE(ev[2].level);
  EXPECT_EQ(ev[2].t, ev[0].t + 20'000);
  EXPECT_EQ(ev[3].line, InputLine::kCcwLimit);  // at -2
  EXPECT_TRUE(ev[3].level);
  EXPECT_EQ(ev[3].t, ev[0].t + 40'000);
}

TEST(GpioSimMachine, NormallyClosedSwitchesGoLowWhileActuated) {
  SimAxisParams p = switches(true);
  p.start_position = 3;  // on the CW limit at start-up
  SimMachine m(0, p, kAllInputs);
  EXPECT_FALSE(m.read(InputLine::kCwLimit));
  EXPECT_TRUE(m.read(InputLine::kCcwLimit));
  EXPECT_TRUE(m.read(InputLine::kHome));
  // Inputs without a simulated actuator rest at the unactuated NC level (high).
  EXPECT_TRUE(m.read(InputLine::kEStop));
  EXPECT_TRUE(m.read(InputLine::kCapture));
  EXPECT_TRUE(m.read(InputLine::kExternal));
  steps(m, -1, 0);  // -> 2: limit released (high), home actuated (low)
  const auto ev = drain(m);
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].line, InputLine::kCwLimit);
  EXPECT_TRUE(ev[0].level);
  EXPECT_EQ(ev[1].line, InputLine::kHome);
  EXPECT_FALSE(ev[1].level);
}

TEST(GpioSimMachine, AbsentSwitchKeysAreNeverActuated) {
  SimAxisParams p = no_encoder();
  p.home_from = 1;  // without home_to: no home switch
  SimMachine m(0, p, kAllInputs);
  steps(m, 50, 0);
  steps(m, -100, 1'000'000);
  EXPECT_TRUE(drain(m).empty());
  EXPECT_FALSE(m.read(InputLine::kHome));
}

TEST(GpioSimMachine, UnwiredInputsStayLowAndSilent) {
  SimAxisParams p = switches(true);  // NC: a wired line would be high
  p.encoder_ratio = 1;
  SimMachine m(0, p, input_bit(InputLine::kCwLimit));
  EXPECT_FALSE(m.read(InputLine::kHome));
  EXPECT_FALSE(m.read(InputLine::kEncA));
  EXPECT_TRUE(m.read(InputLine::kCwLimit));
  steps(m, 3, 0);
  const auto ev = drain(m);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].line, InputLine::kCwLimit);
  m.force(input_bit(InputLine::kHome), input_bit(InputLine::kHome), 1);
  EXPECT_TRUE(drain(m).empty()) << "forcing an unwired input does nothing";
  EXPECT_FALSE(m.read(InputLine::kHome));
}

// ---- encoder ---------------------------------------------------------------------------------

struct AB {
  bool a, b;
  bool operator==(const AB&) const = default;
};

// Replays the A/B events onto levels and returns the (A, B) state after each event.
std::vector<AB> ab_states(const std::vector<InputEvent>& ev, AB start = {false, false}) {
  std::vector<AB> r;
  AB s = start;
  for (const auto& e : ev) {
    if (e.line == InputLine::kEncA) s.a = e.level;
    if (e.line == InputLine::kEncB) s.b = e.level;
    if (e.line == InputLine::kEncA || e.line == InputLine::kEncB) r.push_back(s);
  }
  return r;
}

TEST(GpioSimMachine, EncoderX4SequenceCountingUpALeadsB) {
  SimMachine m(0, SimAxisParams{}, kAllInputs);
  steps(m, 8, 0);
  EXPECT_EQ(m.encoder(), 8);
  const auto ev = drain(m);
  ASSERT_EQ(ev.size(), 8u) << "one A or B edge per count";
  const std::vector<AB> want = {{1, 0}, {1, 1}, {0, 1}, {0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
  EXPECT_EQ(ab_states(ev), want);
  for (std::size_t i = 0; i < ev.size(); ++i) EXPECT_EQ(ev[i].t, 5000 + 10'000 * Nanos(i));
}

TEST(GpioSimMachine, EncoderX4SequenceCountingDownBLeadsA) {
  SimMachine m(0, SimAxisParams{}, kAllInputs);
  steps(m, -4, 0);
  EXPECT_EQ(m.encoder(), -4);
  const std::vector<AB> want = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  EXPECT_EQ(ab_states(drain(m)), want);
}

TEST(GpioSimMachine, EncoderRatioTwoGivesTwoCountsPerStep) {
  SimAxisParams p;
  p.encoder_ratio = 2;
  SimMachine m(0, p, kAllInputs);
  steps(m, 2, 0);
  EXPECT_EQ(m.encoder(), 4);
  const auto ev = drain(m);
  ASSERT_EQ(ev.size(), 4u);
  const std::vector<AB> want = {{1, 0}, {1, 1}, {0, 1}, {0, 0}};
  EXPECT_EQ(ab_states(ev), want);
  EXPECT_EQ(ev[0].t, ev[1].t) << "both counts of one step at the step's time";
  EXPECT_EQ(ev[2].t, ev[1].t + 10'000);
}

TEST(GpioSimMachine, EncoderRatioHalfAccumulatesFractions) {
  SimAxisParams p;
  p.encoder_ratio = 0.5;
  SimMachine m(0, p, kAllInputs);
  steps(m, 1, 0);
  EXPECT_EQ(m.encoder(), 0);
  EXPECT_TRUE(drain(m).empty());
  steps(m, 3, 100'000);
  EXPECT_EQ(m.encoder(), 2);
  const auto ev = drain(m);
  const std::vector<AB> want = {{1, 0}, {1, 1}};
  EXPECT_EQ(ab_states(ev), want);
  // Back and forth around a half count does not drift.
  for (int i = 0; i < 10; ++i) {
    steps(m, 1, 1'000'000 + i * 100'000);
    steps(m, -1, 1'050'000 + i * 100'000);
  }
  EXPECT_EQ(m.encoder(), 2);
  steps(m, -4, 3'000'000);
  EXPECT_EQ(m.encoder(), 0);
  EXPECT_EQ(m.read(InputLine::kEncA), false);
  EXPECT_EQ(m.read(InputLine::kEncB), false);
}

TEST(GpioSimMachine, EncoderNegativeRatioReversesTheSequence) {
  SimAxisParams p;
  p.encoder_ratio = -1;
  SimMachine m(0, p, kAllInputs);
  steps(m, 4, 0);  // CW motor steps count down
  EXPECT_EQ(m.encoder(), -4);
  const std::vector<AB> want = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  EXPECT_EQ(ab_states(drain(m)), want);
}

TEST(GpioSimMachine, EncoderRatioZeroHasNoSignals) {
  SimMachine m(0, no_encoder(), kAllInputs);
  steps(m, 20, 0);
  EXPECT_EQ(m.encoder(), 0);
  EXPECT_TRUE(drain(m).empty());
}

TEST(GpioSimMachine, EncoderMarkerHighForOneCountAtEachMultiple) {
  SimAxisParams p;
  p.marker_every = 4;
  p.start_position = 1;
  SimMachine m(0, p, kAllInputs);
  EXPECT_FALSE(m.read(InputLine::kEncZ));
  steps(m, 8, 0);  // counts 2..9: markers at 4 and 8
  auto z = only(drain(m), InputLine::kEncZ);
  ASSERT_EQ(z.size(), 4u);
  EXPECT_TRUE(z[0].level);
  EXPECT_EQ(z[0].t, 5000 + 2 * 10'000);  // count 4 = third step
  EXPECT_FALSE(z[1].level);
  EXPECT_EQ(z[1].t, z[0].t + 10'000);  // low at the next count
  EXPECT_TRUE(z[2].level);
  EXPECT_EQ(z[2].t, z[0].t + 40'000);
  EXPECT_FALSE(z[3].level);
  // Going back over a marker pulses it again, also at negative counts.
  steps(m, -14, 1'000'000);  // 9 -> -5: markers at 8, 4, 0, -4
  z = only(drain(m), InputLine::kEncZ);
  ASSERT_EQ(z.size(), 8u);
  EXPECT_EQ(m.encoder(), -5);
}

TEST(GpioSimMachine, EncoderMarkerWithRatioTwoCountsEncoderCounts) {
  SimAxisParams p;
  p.encoder_ratio = 2;
  p.marker_every = 4;
  p.start_position = 1;  // count 2
  SimMachine m(0, p, kAllInputs);
  steps(m, 1, 0);  // counts 3, 4: Z rises with the second count
  const auto ev = drain(m);
  const auto z = only(ev, InputLine::kEncZ);
  ASSERT_EQ(z.size(), 1u);
  EXPECT_TRUE(z[0].level);
  EXPECT_EQ(ev.back().line, InputLine::kEncZ);
}

// ---- forcing (docs/interface.md section 4) ------------------------------------------------------

constexpr std::uint32_t kHomeBit = 1u << 2;
constexpr std::uint32_t kEStopBit = 1u << 3;

TEST(GpioSimMachine, ForcedInputTakesTheForcedLevelAndReleaseRestoresTheSwitch) {
  SimMachine m(0, switches(false), kAllInputs);
  m.force(kEStopBit, kEStopBit, 500);
  auto ev = drain(m);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].line, InputLine::kEStop);
  EXPECT_TRUE(ev[0].level);
  EXPECT_EQ(ev[0].t, 500);
  EXPECT_TRUE(m.read(InputLine::kEStop));
  m.force(kEStopBit, kEStopBit, 600);  // unchanged: no event
  EXPECT_TRUE(drain(m).empty());
  m.force(0, 0, 700);
  ev = drain(m);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_FALSE(ev[0].level);
  EXPECT_EQ(ev[0].t, 700);
  EXPECT_FALSE(m.read(InputLine::kEStop));
}

TEST(GpioSimMachine, ForcedLineHidesSimulatedChangesUntilReleased) {
  SimMachine m(0, switches(false), kAllInputs);
  m.force(kHomeBit, 0, 100);  // forced low = its present level: no event
  EXPECT_TRUE(drain(m).empty());
  steps(m, 1, 1000);  // into home: simulated high, forced low
  EXPECT_TRUE(drain(m).empty());
  EXPECT_FALSE(m.read(InputLine::kHome));
  m.force(0, 0, 100'000);  // release: the switch is actuated now
  auto ev = drain(m);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].line, InputLine::kHome);
  EXPECT_TRUE(ev[0].level);
  EXPECT_EQ(ev[0].t, 100'000);
  EXPECT_TRUE(m.read(InputLine::kHome));
  // Forced high while actuated, then the axis leaves the switch: release gives low.
  m.force(kHomeBit, kHomeBit, 200'000);
  EXPECT_TRUE(drain(m).empty());
  steps(m, -1, 300'000);
  EXPECT_TRUE(drain(m).empty());
  m.force(0, 0, 400'000);
  ev = drain(m);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_FALSE(ev[0].level);
  EXPECT_EQ(ev[0].t, 400'000);
}

TEST(GpioSimMachine, SimulatedChangeBeforeAForceIsReportedFirst) {
  SimMachine m(0, switches(false), kAllInputs);
  steps(m, 1, 1000);  // home high at 6000, not yet polled
  m.force(kHomeBit, 0, 50'000);
  const auto ev = drain(m);
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_TRUE(ev[0].level);
  EXPECT_EQ(ev[0].t, 6000);
  EXPECT_FALSE(ev[1].level);
  EXPECT_EQ(ev[1].t, 50'000);
}

// Issue 16 (CI): a forced E-stop while the encoder's edges of a fast move waited unpolled was
// lost behind them (a 256-slot queue), and the daemon stopped the axis for a lost input instead
// of the E-stop. A real E-stop line has a kernel FIFO of its own.
TEST(GpioSimMachine, ForceBehindAFullRingOfEncoderEdgesIsDeliveredInTimeOrderAndNotLost) {
  constexpr std::size_t kRing = 1024;
  SimMachine m(0, SimAxisParams{}, kAllInputs, kRing);
  const Nanos end = steps(m, static_cast<int>(kRing), 0);  // exactly fills the ring
  EXPECT_EQ(m.lost_events(), 0u);
  m.force(kEStopBit, kEStopBit, end + 1);
  m.force(kEStopBit, kEStopBit, end + 2);  // every scan asks again: no second edge
  EXPECT_TRUE(m.read(InputLine::kEStop)) << "the level is forced at once";
  const auto ev = drain(m);
  EXPECT_EQ(m.lost_events(), 0u);
  ASSERT_EQ(ev.size(), kRing + 1);
  EXPECT_EQ(ev.back().line, InputLine::kEStop);
  EXPECT_TRUE(ev.back().level);
  EXPECT_EQ(ev.back().t, end + 1);
  for (std::size_t i = 1; i < ev.size(); ++i) EXPECT_LE(ev[i - 1].t, ev[i].t) << i;
}

TEST(GpioSimMachine, SimulatedEdgeAfterAForceIsFilteredByIt) {
  SimMachine m(0, switches(false), kAllInputs);
  m.force(kHomeBit, 0, 1000);  // home held low before the axis reaches it
  steps(m, 1, 2000);           // home actuated at 7000: hidden by the force
  EXPECT_TRUE(drain(m).empty());
  EXPECT_EQ(m.position(), 1);
}

TEST(GpioSimMachine, MoreUnpolledPanelChangesThanItsQueueKeepTheLastAndCountTheRest) {
  SimMachine m(0, SimAxisParams{}, kAllInputs);
  for (int i = 0; i < 200; ++i) m.force(kEStopBit, (i % 2) ? 0u : kEStopBit, 1000 + i);
  EXPECT_GT(m.lost_events(), 0u) << "changes that could not be kept are reported lost";
  const auto ev = drain(m);
  ASSERT_FALSE(ev.empty());
  EXPECT_FALSE(ev.back().level) << "the last change (199: released level) is in effect";
  EXPECT_FALSE(m.read(InputLine::kEStop));
}

TEST(GpioSimMachine, ForcingIgnoresNonPanelBits) {
  SimMachine m(0, SimAxisParams{}, kAllInputs);
  m.force(0xFFFFFFC0u, 0xFFFFFFFFu, 10);  // bits 6.. are not panel inputs (encoder)
  EXPECT_TRUE(drain(m).empty());
  EXPECT_FALSE(m.read(InputLine::kEncA));
}

TEST(GpioSimMachine, FullEventRingCountsLostEvents) {
  SimMachine m(0, SimAxisParams{}, kAllInputs, 4);
  steps(m, 10, 0);  // 10 encoder edges into a ring of 4
  EXPECT_EQ(m.lost_events(), 6u);
  EXPECT_EQ(drain(m).size(), 4u);
  EXPECT_EQ(m.encoder(), 10) << "the machine itself is not affected";
}

}  // namespace
}  // namespace stepmod::gpio
