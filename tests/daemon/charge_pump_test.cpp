// The charge pump's rules (daemon/charge_pump.hpp, docs/safety.md "Charge pump") on the simulated
// backend, whose panel output levels show the pump's wire in bit 4 of the axis carrying it: a
// toggle every half period of whole scans while nothing stops it; each cause stops it at the scan
// that sees it, at its inactive level; it runs again once every cause is gone; a stop of the
// daemon is for good. And which health flags stop it (daemon/charge_pump_feed.hpp).
#include "daemon/charge_pump.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "daemon/charge_pump_feed.hpp"
#include "gpio/sim_backend.hpp"
#include "ipc/stepmod_image.h"

namespace stepmod::tools {
namespace {

constexpr unsigned kHalf = 5;  // scans per half period: 100 Hz at 1 ms scans
constexpr Nanos kScan = kNsPerMs;

struct Rig {
  std::vector<gpio::SimAxisSetup> setups;
  std::unique_ptr<gpio::SimBackend> sim;
  std::unique_ptr<ChargePump> pump;
  Nanos now = 0;
  unsigned changes = 0;

  explicit Rig(bool active_low = false) {
    gpio::SimAxisSetup s;
    s.sim.encoder_ratio = 0;  // nothing simulated but the wires
    s.lines.charge_pump = 3;
    s.lines.charge_pump_opt = gpio::LineOptions{.active_low = active_low};
    s.lines.out[0] = 1;  // step and dir, which every axis has
    s.lines.out[1] = 2;
    setups = {s};
    sim = std::make_unique<gpio::SimBackend>(setups);
    pump = std::make_unique<ChargePump>(*sim, ChargePump::Setup{0, kHalf, 100});
  }
  bool wire() const { return (sim->output_levels(0) & gpio::SimBackend::kChargePumpLevelBit) != 0; }
  // `n` scans under `c`; the line changes they made.
  unsigned scans(unsigned n, const ChargePump::Conditions& c = {}) {
    unsigned made = 0;
    for (unsigned i = 0; i < n; ++i) {
      now += kScan;
      if (pump->scan(c, now)) ++made;
    }
    changes += made;
    return made;
  }
};

// One of each cause alone.
std::vector<std::pair<const char*, ChargePump::Conditions>> each_cause() {
  std::vector<std::pair<const char*, ChargePump::Conditions>> causes(5);
  causes[0] = {"E-stop", {}};
  causes[0].second.estop = true;
  causes[1] = {"fault", {}};
  causes[1].second.fault = true;
  causes[2] = {"PLC lost", {}};
  causes[2].second.plc_lost = true;
  causes[3] = {"lease expired", {}};
  causes[3].second.lease_expired = true;
  causes[4] = {"trace lost", {}};
  causes[4].second.trace_lost = true;
  return causes;
}

TEST(ChargePump, TogglesEveryHalfPeriodOfWholeScansFromTheFirstScan) {
  Rig r;
  EXPECT_FALSE(r.wire()) << "inactive before the first scan";
  EXPECT_EQ(r.scans(1), 1u);
  EXPECT_TRUE(r.wire()) << "high at the first healthy scan";
  EXPECT_TRUE(r.pump->running());
  EXPECT_EQ(r.scans(kHalf - 1), 0u) << "held for the rest of the half period";
  EXPECT_EQ(r.scans(1), 1u);
  EXPECT_FALSE(r.wire());
  // 1000 scans more: exactly one change every kHalf scans (100 Hz at 1 ms: 200 edges a second).
  EXPECT_EQ(r.scans(1000), 1000u / kHalf);
}

TEST(ChargePump, EachCauseStopsItAtTheScanThatSeesItWhicheverTheLevel) {
  for (const auto& [name, cause] : each_cause()) {
    for (unsigned phase = 0; phase < 2 * kHalf; ++phase) {
      SCOPED_TRACE(std::string(name) + ", " + std::to_string(phase) + " scans into the wave");
      Rig r;
      r.scans(1 + phase);
      const bool was_high = r.wire();
      EXPECT_EQ(r.scans(1, cause), was_high ? 1u : 0u) << "a high line falls at once";
      EXPECT_FALSE(r.wire());
      EXPECT_FALSE(r.pump->running());
      EXPECT_EQ(r.scans(10 * kHalf, cause), 0u) << "no toggle while the cause lasts";
      EXPECT_FALSE(r.wire());
    }
  }
}

TEST(ChargePump, RunsAgainOnlyOnceEveryCauseIsGone) {
  Rig r;
  r.scans(3);
  ChargePump::Conditions both;
  both.estop = true;
  both.plc_lost = true;
  r.scans(20, both);
  ChargePump::Conditions plc_only;
  plc_only.plc_lost = true;
  EXPECT_EQ(r.scans(20, plc_only), 0u) << "the E-stop released, the PLC still lost";
  EXPECT_FALSE(r.pump->running());
  EXPECT_EQ(r.scans(1), 1u) << "every cause gone: a toggle at once";
  EXPECT_TRUE(r.wire());
  EXPECT_TRUE(r.pump->running());
  EXPECT_EQ(r.scans(kHalf - 1), 0u) << "a whole half period, as from the start";
  EXPECT_EQ(r.scans(1), 1u);
}

TEST(ChargePump, TheDaemonsStopIsForGood) {
  Rig r;
  r.scans(1);
  ASSERT_TRUE(r.wire());
  EXPECT_TRUE(r.pump->stop(r.now));
  EXPECT_FALSE(r.wire());
  EXPECT_FALSE(r.pump->running());
  EXPECT_EQ(r.scans(10 * kHalf), 0u) << "no scan restarts it";
  EXPECT_FALSE(r.pump->stop(r.now)) << "a second stop changes nothing";
}

TEST(ChargePump, ActiveLowHoldsAHighWireWhenStopped) {
  Rig r(true);
  EXPECT_TRUE(r.wire()) << "inactive, active low: a high wire";
  r.scans(1);
  EXPECT_FALSE(r.wire());
  ChargePump::Conditions c;
  c.fault = true;
  r.scans(1, c);
  EXPECT_TRUE(r.wire());
  r.sim->idle_outputs();
  EXPECT_TRUE(r.wire()) << "idle outputs leave it inactive";
}

TEST(ChargePumpFeed, EveryHealthFlagThatStopsTheAxesStopsThePumpAndALostTraceToo) {
  const auto stops = [](std::uint32_t flags, bool estop = false) {
    const ChargePump::Conditions c = ChargePumpFeed::conditions(flags, estop);
    return c.estop || c.fault || c.plc_lost || c.lease_expired || c.trace_lost;
  };
  EXPECT_FALSE(stops(0));
  EXPECT_TRUE(stops(0, true));
  EXPECT_TRUE(ChargePumpFeed::conditions(STEPMOD_HEALTH_LATE_EDGE, false).fault);
  EXPECT_TRUE(ChargePumpFeed::conditions(STEPMOD_HEALTH_INPUT_LOST, false).fault);
  EXPECT_TRUE(ChargePumpFeed::conditions(STEPMOD_HEALTH_PLC_STALE, false).plc_lost);
  EXPECT_TRUE(ChargePumpFeed::conditions(STEPMOD_HEALTH_SEQ_STUCK, false).plc_lost);
  EXPECT_TRUE(ChargePumpFeed::conditions(STEPMOD_HEALTH_LEASE_EXPIRED, false).lease_expired);
  EXPECT_TRUE(ChargePumpFeed::conditions(STEPMOD_HEALTH_TRACE_LOST, false).trace_lost);
  // Warnings that stop no axis: a PLC writing past the seqlock, a heartbeat during a lease.
  EXPECT_FALSE(stops(STEPMOD_HEALTH_SEQ_BYPASS));
  EXPECT_FALSE(stops(STEPMOD_HEALTH_LEASE_CONFLICT));
}

// docs/safety.md "Charge pump", restart rule: a late-edge fault or lost input events stop the
// pump for FaultDrop::kDrop from each new fault, then it runs although the health bit stands
// (cleared only by the PLC's next accepted motion): the chain's Reset, not a move, re-enables.
TEST(ChargePumpFeed, AFaultStopsThePumpForTheDropTimeThenItRunsWithTheBitStanding) {
  using Drop = ChargePumpFeed::FaultDrop;
  constexpr Nanos kT0 = 5 * kNsPerSec;
  Drop d;
  EXPECT_FALSE(d.stops(ipc::Health{}, kT0));
  const ipc::Health late{.flags = STEPMOD_HEALTH_LATE_EDGE, .late_faults = 1};
  EXPECT_TRUE(d.stops(late, kT0));
  EXPECT_TRUE(d.stops(late, kT0 + Drop::kDrop - 1));
  EXPECT_FALSE(d.stops(late, kT0 + Drop::kDrop)) << "the bit stands, the drop time is over";
  // One more late-edge fault while bit 0 stands: a new drop.
  const ipc::Health again{.flags = STEPMOD_HEALTH_LATE_EDGE, .late_faults = 2};
  EXPECT_TRUE(d.stops(again, kT0 + 2 * Drop::kDrop));
  EXPECT_FALSE(d.stops(again, kT0 + 3 * Drop::kDrop));
  // Lost input events rising beside it: a new drop too.
  const ipc::Health lost{.flags = STEPMOD_HEALTH_LATE_EDGE | STEPMOD_HEALTH_INPUT_LOST,
                         .late_faults = 2};
  EXPECT_TRUE(d.stops(lost, kT0 + 3 * Drop::kDrop + 1));
  // The PLC's next accepted motion clears the bits: nothing stops it.
  EXPECT_FALSE(d.stops(ipc::Health{.late_faults = 2}, kT0 + 3 * Drop::kDrop + 2));
}

}  // namespace
}  // namespace stepmod::tools
