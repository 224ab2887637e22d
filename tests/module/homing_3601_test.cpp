// 3601 Find Home + / - in virtual time: the four homing options from both sides of the switch and
// with the home (proximity) signal already active, the end-limit reversal, the start checks and
// the homing errors (3601 manual Ch.3 item 10, Ch.4 "Find Home", Ch.6; the 3601 checklist's
// HI/IE/PI/AH/STP items, A8 A12 A15 A44 A49).
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "tests/module/plc_3601.hpp"
#include "tests/support/checklist_rows.hpp"

namespace stepmod::testing {
namespace {

using namespace m::status_msw;
namespace cmd = m::cmd_msw;
namespace cfg = m::cfg_msw;

// Where the machine's switches are and where the axis starts (default_3601: limits at
// +-100,000, home switch 5,000..5,100, a marker every 4,000 encoder counts, 1 count per step).
struct Machine {
  std::int64_t start = 0;
  std::optional<std::int64_t> home_from = 5'000;
  std::optional<std::int64_t> home_to = 5'100;
  std::int64_t cw_limit = 100'000;
  std::int64_t ccw_limit = -100'000;
};

VirtualMachineOptions machine(const Machine& mc) {
  VirtualMachineOptions o = default_3601();
  gpio::SimAxisParams& s = o.axes[0].sim;
  s.start_position = mc.start;
  s.home_from = mc.home_from;
  s.home_to = mc.home_to;
  s.cw_limit_at = mc.cw_limit;
  s.ccw_limit_at = mc.ccw_limit;
  return o;
}

// The four homing options (3601 manual ch. 3 table).
constexpr std::uint16_t kSwitchOnly = kFullConfigMsw;
constexpr std::uint16_t kSwitchBackplane = kFullConfigMsw | cfg::kBackplaneProximity;
constexpr std::uint16_t kMarkerHome = kFullConfigMsw | cfg::kMarkerHoming;
constexpr std::uint16_t kMarkerBackplane =
    (kFullConfigMsw & ~cfg::kHomeUsed) | cfg::kMarkerHoming | cfg::kBackplaneProximity;

// Vp 10,000 steps/s, 100 steps/ms/s: 495 steps to ramp between Vs (1,000) and Vp.
constexpr Move kProfile{.target = 0, .speed = 10'000, .accel = 100, .decel = 100};
constexpr std::uint16_t kProx = m::cmd_lsw::kBackplaneProximity;
constexpr Nanos kStepAtVs = kNsPerSec / 1'000;

class Homing3601 : public Plc3601 {
 protected:
  explicit Homing3601(Machine mc = {}) : Plc3601(machine(mc)) {}
  void SetUp() override { configure(kSwitchOnly); }

  // The PLC program's proximity sensor: the backplane bit is on while the motor is within
  // [from, to] (a sensor wired to the PLC, read once per scan).
  void prox_zone(std::int64_t from, std::int64_t to) {
    prox_from_ = from;
    prox_to_ = to;
  }
  void plc_scan() {
    if (prox_from_) {
      const bool on = motor() >= *prox_from_ && motor() <= *prox_to_;
      word(1) = on ? (word(1) | kProx) : (word(1) & ~kProx);
    }
    vm_.scans(1);
  }
  bool run_plc(const std::function<bool()>& done, Nanos limit) {
    const Nanos end = vm_.now() + limit;
    while (vm_.now() < end) {
      plc_scan();
      if (done()) return true;
    }
    return false;
  }
  void run_plc_for(Nanos d) {
    run_plc([] { return false; }, d);
  }
  // Find Home + / - as a PLC issues it: the bit for three scans, then cleared.
  void home(std::uint16_t bit, Move p = kProfile) {
    set_words(bit, p.lsw, p.target, p.speed, p.accel, p.decel);
    for (int i = 0; i < 3; ++i) plc_scan();
    word(0) = 0;
    plc_scan();
  }
  // The homing has ended one way or the other (a PLC waits for At Home or an error).
  bool ended() const {
    return status(kAtHome) || status(kStopped) || status(kHomeInvalid) || status(kInputError);
  }
  bool wait_end(Nanos limit = 60 * kNsPerSec) {
    return run_plc([this] { return ended(); }, limit);
  }
  bool errors() const {
    return status(kCommandError) || status(kInvalidProfile) || status(kInputError) ||
           status(kHomeInvalid);
  }
  // A successful homing: At Home, position 0 and valid, no error, no Stopped (3601-STP-N1).
  void expect_homed_at(std::int64_t motor_position) {
    EXPECT_TRUE(status(kAtHome));
    EXPECT_EQ(motor(), motor_position);
    EXPECT_EQ(position(), 0);
    EXPECT_FALSE(status(kPositionInvalid));
    EXPECT_FALSE(status(kStopped));
    EXPECT_FALSE(status(kMoveComplete));
    EXPECT_FALSE(errors());
  }
  // Gaps of at least 1 s between consecutive steps: the homing's pauses.
  std::vector<Nanos> pauses() const {
    std::vector<Nanos> out;
    const auto& t = vm_.step_times(0);
    for (std::size_t i = 1; i < t.size(); ++i) {
      if (t[i] - t[i - 1] >= kNsPerSec) out.push_back(t[i] - t[i - 1]);
    }
    return out;
  }
  void expect_pauses(std::size_t n) {
    const auto p = pauses();
    ASSERT_EQ(p.size(), n);
    for (const Nanos d : p) {
      EXPECT_GE(d, 2 * kNsPerSec);
      EXPECT_LT(d, 2 * kNsPerSec + 20 * kNsPerMs);  // stop noticed within a scan or two
    }
  }
  // The last steps were output at the starting speed (the creep, or the approach at Vs).
  void expect_last_steps_at_vs() {
    const auto& t = vm_.step_times(0);
    ASSERT_GE(t.size(), 3u);
    const Nanos d = t[t.size() - 1] - t[t.size() - 2];
    EXPECT_NEAR(static_cast<double>(d), static_cast<double>(kStepAtVs), kStepAtVs * 0.02);
  }
  // Motor extremes over the motion, sampled every scan by run_plc_track.
  bool run_track(Nanos limit = 60 * kNsPerSec) {
    return run_plc(
        [this] {
          min_seen_ = std::min(min_seen_, motor());
          max_seen_ = std::max(max_seen_, motor());
          return ended();
        },
        limit);
  }

  std::optional<std::int64_t> prox_from_, prox_to_;
  std::int64_t min_seen_ = INT64_MAX;
  std::int64_t max_seen_ = INT64_MIN;
};

class Homing3601Above : public Homing3601 {
 protected:
  Homing3601Above() : Homing3601({.start = 10'000}) {}
};
class Homing3601OnHome : public Homing3601 {
 protected:
  Homing3601OnHome() : Homing3601({.start = 5'050}) {}
};
class Homing3601AtCwLimit : public Homing3601 {
 protected:
  Homing3601AtCwLimit() : Homing3601({.start = 100'000}) {}
};
class Homing3601AtCcwLimit : public Homing3601 {
 protected:
  Homing3601AtCcwLimit() : Homing3601({.start = -100'000}) {}
};
// No home switch at all, limits at +-30,000: a homing can only end in an error.
class Homing3601NoSwitch : public Homing3601 {
 protected:
  Homing3601NoSwitch()
      : Homing3601({.home_from = std::nullopt,
                    .home_to = std::nullopt,
                    .cw_limit = 30'000,
                    .ccw_limit = -30'000}) {}
};

// ---- Homings that end At Home: options 1 (H-A), 2 (H-B), 3 and 4 (H-D), from below, above and on
// the switch, and from an end limit (H-C) ---------------------------------------------------------

// The motor's extremes over the motion (run_track), where a row checks them.
struct Extremes {
  std::optional<std::int64_t> max_eq{}, max_above{}, max_at_most{}, min_eq{}, min_below{};
};

struct Homes {
  const char* name;
  std::int64_t start = 0;              // where the axis starts (0: below the switch)
  std::uint16_t config = kSwitchOnly;  // the homing option
  std::optional<std::pair<std::int64_t, std::int64_t>> prox{};  // the PLC's proximity zone
  std::uint16_t command = cmd::kFindHomeCw;
  Move profile = kProfile;
  std::uint16_t active_lsw = 0;  // a status LSW bit that must be set before the start
  std::uint16_t moving = 0;      // the status MSW direction bit right after the command
  Extremes seen{};
  std::int64_t homed_at = 0;  // the motor position At Home (expect_homed_at)
  std::optional<std::size_t> pauses{};
  bool last_at_vs = false;      // the last steps at the starting speed (the creep, the approach)
  bool encoder_zeroed = false;  // the encoder count 0 At Home
  std::optional<std::int64_t> machine_encoder{};  // the machine's own encoder count At Home
};

constexpr std::int64_t kAbove = 10'000;  // above the switch (5,000..5,100)
constexpr std::int64_t kOnHome = 5'050;
constexpr std::pair<std::int64_t, std::int64_t> kProxZone{4'000, 6'000};
constexpr std::pair<std::int64_t, std::int64_t> kMarkerProxZone{3'000, 6'000};

const Homes kHomings[] = {
    // Step 3 decelerated past the 100-step switch (495 steps), step 5 crossed it again, step 7
    // crept back up to its lower edge.
    {.name = "HA_FindHomePlusFromBelowStopsAtTheSwitchEdge",
     .moving = kMovingCw,
     .seen = {.max_above = 5'100, .min_below = 5'000},
     .homed_at = 5'000,
     .pauses = 2,
     .last_at_vs = true},
    {.name = "HA_FindHomeMinusFromAboveStopsAtTheUpperEdge",
     .start = kAbove,
     .command = cmd::kFindHomeCcw,
     .moving = kMovingCcw,
     .homed_at = 5'100,
     .pauses = 2,
     .last_at_vs = true},
    // The switch lies behind: the CCW limit is met (H-C), the reversal crosses the switch.
    {.name = "HA_FindHomeMinusFromBelowReversesAtTheCcwLimit",
     .command = cmd::kFindHomeCcw,
     .seen = {.min_eq = -100'000},
     .homed_at = 5'100,
     .pauses = 2},
    // A steep decel (2,000 steps/ms/s: 25 steps) stops inside the switch: the reversal only has
    // to leave it.
    {.name = "HA_DecelerationInsideTheSwitch",
     .profile = {.target = 0, .speed = 10'000, .accel = 100, .decel = 2'000},
     .seen = {.max_at_most = 5'100},
     .homed_at = 5'000,
     .pauses = 2},
    // Step 4/5 at once: off the switch, opposite direction; no pause before moving off.
    {.name = "HA_HomeActiveAtStartMovesOffFirst",
     .start = kOnHome,
     .active_lsw = m::status_lsw::kHomeActive,
     .moving = kMovingCcw,
     .seen = {.max_at_most = 5'050},
     .homed_at = 5'000,
     .pauses = 1},
    {.name = "HA_HomeActiveAtStartMinus",
     .start = kOnHome,
     .command = cmd::kFindHomeCcw,
     .moving = kMovingCw,
     .homed_at = 5'100,
     .pauses = 1},
    {.name = "HC_OppositeLimitActiveAtStartHomesNormally",
     .start = -100'000,
     .active_lsw = m::status_lsw::kCcwLimitActive,
     .moving = kMovingCw,
     .homed_at = 5'000,
     .pauses = 2},
    // No overshoot, no reversal: decelerated to Vs on the bit (495 steps < 1,000).
    {.name = "HB_FindHomePlusFromBelowSlowsOnTheBitAndStopsOnHome",
     .config = kSwitchBackplane,
     .prox = kProxZone,
     .seen = {.max_eq = 5'000},
     .homed_at = 5'000,
     .pauses = 0,
     .last_at_vs = true},
    {.name = "HB_FindHomeMinusFromAbove",
     .start = kAbove,
     .config = kSwitchBackplane,
     .prox = kProxZone,
     .command = cmd::kFindHomeCcw,
     .seen = {.min_eq = 5'100},
     .homed_at = 5'100,
     .pauses = 0},
    // [01] Ch.4 Note 2: off until the proximity bit (not the home input) goes off: below 4,000.
    {.name = "HB_HomeActiveAtStartMovesOffUntilTheBitFalls",
     .start = kOnHome,
     .config = kSwitchBackplane,
     .prox = kProxZone,
     .moving = kMovingCcw,
     .seen = {.min_below = 4'000},
     .homed_at = 5'000,
     .pauses = 1},
    // Back through the whole proximity zone, not just the switch.
    {.name = "HB_EndLimitReversalWatchesTheProximityBit",
     .start = kAbove,
     .config = kSwitchBackplane,
     .prox = kProxZone,
     .seen = {.max_eq = 100'000, .min_below = 4'000},
     .homed_at = 5'000,
     .pauses = 2},
    // Home (the proximity) at 5,000 slows to Vs; the next marker is at 8,000.
    {.name = "HD_MarkerWithHomeProximityPlusFromBelow",
     .config = kMarkerHome,
     .homed_at = 8'000,
     .pauses = 0,
     .last_at_vs = true,
     .encoder_zeroed = true,
     .machine_encoder = 8'000},
    // Home at 5,100, the next marker going down at 4,000.
    {.name = "HD_MarkerWithHomeProximityMinusFromAbove",
     .start = kAbove,
     .config = kMarkerHome,
     .command = cmd::kFindHomeCcw,
     .homed_at = 4'000,
     .encoder_zeroed = true},
    {.name = "HD_MarkerWithHomeProximityActiveAtStart",
     .start = kOnHome,
     .config = kMarkerHome,
     .moving = kMovingCcw,
     .seen = {.min_below = 5'000},
     .homed_at = 8'000,
     .pauses = 1},
    {.name = "HD_MarkerWithHomeProximityEndLimitReversal",
     .start = kAbove,
     .config = kMarkerHome,
     .seen = {.max_eq = 100'000},
     .homed_at = 8'000,
     .pauses = 2},
    // The bit at 3,000, the next marker at 4,000.
    {.name = "HD_MarkerWithBackplaneProximityPlusFromBelow",
     .config = kMarkerBackplane,
     .prox = kMarkerProxZone,
     .homed_at = 4'000,
     .pauses = 0,
     .encoder_zeroed = true},
    // The bit at 6,000, the next marker going down at 4,000.
    {.name = "HD_MarkerWithBackplaneProximityMinusFromAbove",
     .start = kAbove,
     .config = kMarkerBackplane,
     .prox = kMarkerProxZone,
     .command = cmd::kFindHomeCcw,
     .homed_at = 4'000,
     .pauses = 0},
    // Moved off until the bit went off (below 3,000).
    {.name = "HD_MarkerWithBackplaneProximityActiveAtStart",
     .start = kOnHome,
     .config = kMarkerBackplane,
     .prox = kMarkerProxZone,
     .moving = kMovingCcw,
     .seen = {.min_below = 3'000},
     .homed_at = 4'000,
     .pauses = 1},
    // The marker at 4,000 came before the home input: the axis went on at Vp to 8,000.
    {.name = "HD_MarkersIgnoredBeforeTheProximity",
     .config = kMarkerHome,
     .seen = {.max_eq = 8'000},
     .homed_at = 8'000},
};

class Homes3601 : public Homing3601, public ::testing::WithParamInterface<Homes> {
 protected:
  Homes3601() : Homing3601({.start = ::testing::WithParamInterface<Homes>::GetParam().start}) {}
  void expect_seen(const Extremes& e) const {
    if (e.max_eq) {
      EXPECT_EQ(max_seen_, *e.max_eq);
    }
    if (e.max_above) {
      EXPECT_GT(max_seen_, *e.max_above);
    }
    if (e.max_at_most) {
      EXPECT_LE(max_seen_, *e.max_at_most);
    }
    if (e.min_eq) {
      EXPECT_EQ(min_seen_, *e.min_eq);
    }
    if (e.min_below) {
      EXPECT_LT(min_seen_, *e.min_below);
    }
  }
};

TEST_P(Homes3601, AtHome) {
  const Homes& r = GetParam();
  if (r.config != kSwitchOnly) configure(r.config);
  if (r.prox) prox_zone(r.prox->first, r.prox->second);
  if (r.active_lsw != 0) {
    ASSERT_TRUE(lsw_status(r.active_lsw));
  }
  home(r.command, r.profile);
  if (r.moving != 0) {
    EXPECT_TRUE(status(r.moving));
  }
  ASSERT_TRUE(run_track());
  expect_seen(r.seen);
  expect_homed_at(r.homed_at);
  if (r.machine_encoder) {
    EXPECT_EQ(vm_.sim().encoder(0), *r.machine_encoder);
  }
  if (r.encoder_zeroed) {
    EXPECT_EQ(encoder(), 0);
  }
  if (r.pauses) expect_pauses(*r.pauses);
  if (r.last_at_vs) expect_last_steps_at_vs();
}

INSTANTIATE_TEST_SUITE_P(Options, Homes3601, ::testing::ValuesIn(kHomings), RowName{});

// ---- H-C: end limits ---------------------------------------------------------------------------

TEST_F(Homing3601Above, HC_EndLimitReachedStopsWaitsAndReverses) {
  const Nanos t0 = vm_.now();
  home(cmd::kFindHomeCw);
  ASSERT_TRUE(run_track());
  // Immediate stop at the limit (no deceleration past it), 2 s, back over the switch, 2 s,
  // creep to its lower edge.
  EXPECT_EQ(max_seen_, 100'000);
  EXPECT_LT(min_seen_, 5'000);
  expect_homed_at(5'000);
  expect_pauses(2);
  EXPECT_GT(vm_.now() - t0, 4 * kNsPerSec);
  // The limit ended no motion with an error: 3601-STP-04 does not apply to homing.
  EXPECT_FALSE(status(kInputError));
}

TEST_F(Homing3601AtCwLimit, HC_EndLimitActiveAtStartBeginsAtTheReversal) {
  ASSERT_TRUE(lsw_status(m::status_lsw::kCwLimitActive));
  const std::size_t before = vm_.step_times(0).size();
  const Nanos t0 = vm_.now();
  home(cmd::kFindHomeCw);
  EXPECT_TRUE(status(kMovingCcw));
  ASSERT_GT(vm_.step_times(0).size(), before);
  EXPECT_LT(vm_.step_times(0)[before] - t0, 10 * kNsPerMs);  // no wait before the reversal
  ASSERT_TRUE(wait_end());
  expect_homed_at(5'000);
  expect_pauses(1);
}

TEST_F(Homing3601, HB_HomeInputIgnoredUntilTheProximityBitRises) {
  configure(kSwitchBackplane);
  prox_zone(4'000, 6'000);
  home(cmd::kFindHomeCw);
  run_plc([this] { return motor() >= 2'000; }, 5 * kNsPerSec);
  force(InputLine::kHome, true);  // a home edge before the bit: ignored
  run_plc_for(5 * kNsPerMs);
  release(InputLine::kHome);
  EXPECT_TRUE(status(kMovingCw));
  ASSERT_TRUE(wait_end());
  expect_homed_at(5'000);
}

// ---- Start checks (3601 manual Ch.4 "Find Home", Ch.6 HI #1..#3, CE #5 #10) ------------------

// Refused at the start: the error bits, no step and no At Home.
struct RefusedHoming {
  const char* name;
  Move profile = kProfile;
  std::uint16_t config = kSwitchOnly;
  bool estop_active = false;           // E-Stop active before the command
  std::vector<std::uint16_t> set{};    // status MSW bits set after the command
  std::vector<std::uint16_t> clear{};  // and not set
};

const RefusedHoming kRefusedHomings[] = {
    // CE: 3601-CE-05; IP: 3601-IP-01 (the 3601 checklist).
    {.name = "HI_01_SpeedBelowStartingSpeed",
     .profile = {.target = 0, .speed = 999, .accel = 100, .decel = 100},
     .set = {kHomeInvalid, kCommandError, kInvalidProfile}},
    {.name = "HI_02_A8_TargetNotZero",  // A8: CE too
     .profile = {.target = 100, .speed = 10'000, .accel = 100, .decel = 100},
     .set = {kHomeInvalid, kCommandError},
     .clear = {kInvalidProfile}},
    {.name = "CE_13_FindHomePlusWithoutCwLimit",  // and 3601-HI-03
     .config = kSwitchOnly & ~cfg::kCwLimitUsed,
     .set = {kCommandError, kHomeInvalid}},
    {.name = "A15_EStopActiveAtStartRefusesTheHoming",
     .estop_active = true,
     .set = {kInputError},
     .clear = {kHomeInvalid}},
};

class RefusedHoming3601 : public Homing3601, public ::testing::WithParamInterface<RefusedHoming> {};

TEST_P(RefusedHoming3601, NoStep) {
  const RefusedHoming& r = GetParam();
  if (r.config != kSwitchOnly) configure(r.config);
  if (r.estop_active) {
    force(InputLine::kEStop, true);
    vm_.scans(2);
  }
  home(cmd::kFindHomeCw, r.profile);
  for (const std::uint16_t bit : r.set) EXPECT_TRUE(status(bit)) << "status bit " << bit;
  for (const std::uint16_t bit : r.clear) EXPECT_FALSE(status(bit)) << "status bit " << bit;
  run_plc_for(100 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
  EXPECT_TRUE(vm_.step_times(0).empty());
  EXPECT_FALSE(status(kAtHome));
}

INSTANTIATE_TEST_SUITE_P(Items, RefusedHoming3601, ::testing::ValuesIn(kRefusedHomings), RowName{});

TEST_F(Homing3601, HI_01_SpeedEqualToStartingSpeedIsAccepted) {
  home(cmd::kFindHomeCw, {.target = 0, .speed = 1'000, .accel = 100, .decel = 100});
  EXPECT_FALSE(errors());
  ASSERT_TRUE(wait_end());
  expect_homed_at(5'000);
}

TEST_F(Homing3601, HI_03_NoEndLimitConfiguredInThatDirection) {
  configure(kSwitchOnly & ~cfg::kCcwLimitUsed);
  home(cmd::kFindHomeCcw);
  EXPECT_TRUE(status(kHomeInvalid));
  EXPECT_TRUE(status(kCommandError));
  run_plc_for(100 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
  // The other direction has its limit: accepted after Reset Errors.
  command(cmd::kResetErrors);
  ASSERT_FALSE(errors());
  home(cmd::kFindHomeCw);
  ASSERT_TRUE(wait_end());
  expect_homed_at(5'000);
}

TEST_F(Homing3601, CE_10_SCurveRefused) {
  for (const std::uint16_t lsw : {std::uint16_t{0x1}, std::uint16_t{0x3}}) {
    home(cmd::kFindHomeCw, {.target = 0, .speed = 10'000, .accel = 100, .decel = 100, .lsw = lsw});
    EXPECT_TRUE(status(kCommandError));
    EXPECT_FALSE(status(kHomeInvalid));
    run_plc_for(100 * kNsPerMs);
    EXPECT_EQ(motor(), 0);
    command(cmd::kResetErrors);
  }
  // LSW bit 1 alone selects nothing (it only qualifies bit 0): constant acceleration, accepted.
  home(cmd::kFindHomeCw, {.target = 0, .speed = 10'000, .accel = 100, .decel = 100, .lsw = 0x2});
  EXPECT_FALSE(errors());
  ASSERT_TRUE(wait_end());
  expect_homed_at(5'000);
}

TEST_F(Homing3601, CE_04_ParameterOutOfRangeRaisesCeAndHi) {
  // The 3601 checklist: a homing's bad parameters give CE + HI (IP only for Vp < Vs).
  const Move bad[] = {{.target = 0, .speed = 10'000, .accel = 0, .decel = 100},
                      {.target = 0, .speed = 10'000, .accel = 100, .decel = 2'001},
                      {.target = 0, .speed = 1'000'001, .accel = 100, .decel = 100}};
  for (const Move& p : bad) {
    home(cmd::kFindHomeCw, p);
    EXPECT_TRUE(status(kCommandError));
    EXPECT_TRUE(status(kHomeInvalid));
    EXPECT_FALSE(status(kInvalidProfile));
    run_plc_for(50 * kNsPerMs);
    EXPECT_EQ(motor(), 0);
    command(cmd::kResetErrors);
  }
}

// ---- Homing errors (Ch.6 HI #4 #5, IE #4 #5, PI #5 #6) ------------------------------------------

TEST_F(Homing3601NoSwitch, HI_04_OtherLimitReachedAfterTheReversal) {
  home(cmd::kFindHomeCw);
  ASSERT_TRUE(run_track());
  EXPECT_EQ(max_seen_, 30'000);
  EXPECT_EQ(motor(), -30'000);  // immediate stop at the second limit
  EXPECT_TRUE(status(kHomeInvalid));
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_FALSE(status(kStopped));  // 3601-STP-04: not for homing
  EXPECT_FALSE(status(kAtHome));
  expect_pauses(1);  // the 2 s at the first limit
  run_plc_for(500 * kNsPerMs);
  EXPECT_EQ(motor(), -30'000);
}

TEST_F(Homing3601NoSwitch, IE_04_MinusHomingMeetsTheCwLimitAfterReversing) {
  home(cmd::kFindHomeCcw);
  ASSERT_TRUE(run_track());
  EXPECT_EQ(min_seen_, -30'000);
  EXPECT_EQ(motor(), 30'000);
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kHomeInvalid));
  EXPECT_FALSE(moving());
}

TEST_F(Homing3601NoSwitch, PI_05_BothLimitsInvalidateAPresetPosition) {
  command(cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  ASSERT_FALSE(status(kPositionInvalid));
  home(cmd::kFindHomeCw);
  ASSERT_TRUE(wait_end());
  EXPECT_TRUE(status(kPositionInvalid));
  // An absolute move now needs a preset or a homing first (3601-CE-06).
  command(cmd::kResetErrors);
  command(cmd::kAbsoluteMove, {.target = 0});
  EXPECT_TRUE(status(kCommandError));
}

TEST_F(Homing3601, HI_05_OppositeLimitReachedFirst) {
  home(cmd::kFindHomeCw);
  run_plc([this] { return motor() >= 2'000; }, 5 * kNsPerSec);
  force(InputLine::kCcwLimit, true);  // miswired: the CCW limit during a + search
  const std::int64_t at = motor();
  run_plc_for(500 * kNsPerMs);
  EXPECT_LE(motor(), at + 1);  // immediate stop, no deceleration
  EXPECT_TRUE(status(kHomeInvalid));
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_FALSE(status(kStopped));
  EXPECT_FALSE(moving());
}

TEST_F(Homing3601OnHome, IE_05_OppositeLimitWhileMovingOffTheSwitch) {
  home(cmd::kFindHomeCw);  // moves off CCW first
  run_plc_for(20 * kNsPerMs);
  ASSERT_TRUE(status(kMovingCcw));
  force(InputLine::kCcwLimit, true);
  const std::int64_t at = motor();
  run_plc_for(500 * kNsPerMs);
  EXPECT_LE(std::abs(motor() - at), 1);
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kHomeInvalid));
  EXPECT_TRUE(status(kPositionInvalid));
}

TEST_F(Homing3601Above, PI_06_CwLimitDuringMinusSearch) {
  command(cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  ASSERT_FALSE(status(kPositionInvalid));
  home(cmd::kFindHomeCcw);
  run_plc_for(200 * kNsPerMs);
  force(InputLine::kCwLimit, true);
  run_plc_for(100 * kNsPerMs);
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_TRUE(status(kHomeInvalid));
  EXPECT_TRUE(status(kInputError));
  EXPECT_FALSE(moving());
}

TEST_F(Homing3601Above, A12_CommandedLimitAgainAfterTheReversal) {
  home(cmd::kFindHomeCw);
  run_plc([this] { return status(kMovingCcw); }, 30 * kNsPerSec);  // reversed from the CW limit
  run_plc([this] { return motor() <= 99'000; }, 5 * kNsPerSec);
  ASSERT_FALSE(lsw_status(m::status_lsw::kCwLimitActive));
  force(InputLine::kCwLimit, true);
  const std::int64_t at = motor();
  run_plc_for(500 * kNsPerMs);
  EXPECT_GE(motor(), at - 1);
  EXPECT_TRUE(status(kHomeInvalid));
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_FALSE(status(kAtHome));
}

TEST_F(Homing3601, IE_01_A49_EStopDuringHomingNoHomeInvalid) {
  home(cmd::kFindHomeCw);
  run_plc_for(300 * kNsPerMs);
  force(InputLine::kEStop, true);
  const std::int64_t at = motor();
  run_plc_for(500 * kNsPerMs);
  EXPECT_LE(motor(), at + 1);
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_FALSE(status(kHomeInvalid));  // A49
  EXPECT_TRUE(status(kStopped));       // 3601-STP-02
  EXPECT_FALSE(status(kAtHome));
}

TEST_F(Homing3601, A49_EStopDuringAPauseEndsTheHoming) {
  home(cmd::kFindHomeCw);
  run_plc([this] { return motor() > 5'100; }, 5 * kNsPerSec);
  run_plc([this] { return !moving(); }, 5 * kNsPerSec);  // the first 2-s pause
  run_plc_for(500 * kNsPerMs);
  const std::int64_t at = motor();
  force(InputLine::kEStop, true);
  run_plc_for(5 * kNsPerSec);
  EXPECT_EQ(motor(), at);  // no reversal after the pause
  EXPECT_TRUE(status(kInputError));
  EXPECT_FALSE(status(kHomeInvalid));
  EXPECT_FALSE(status(kAtHome));
}

// ---- Commands and inputs during homing -----------------------------------------------------

TEST_F(Homing3601, CE_07_HoldDuringHomingIsRefusedAndHomingContinues) {
  home(cmd::kFindHomeCw);
  run_plc_for(300 * kNsPerMs);
  raw_command(cmd::kHold);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(status(kMovingCw));
  ASSERT_TRUE(run_plc([this] { return status(kAtHome); }, 30 * kNsPerSec));
  EXPECT_EQ(motor(), 5'000);
  EXPECT_EQ(position(), 0);
  EXPECT_FALSE(status(kHoldState));
  EXPECT_TRUE(status(kCommandError));  // stays until Reset Errors
}

TEST_F(Homing3601, CE_03_MoveDuringHomingIsRefused) {
  home(cmd::kFindHomeCw);
  run_plc_for(300 * kNsPerMs);
  command(cmd::kRelativeMove, {.target = 1'000});
  EXPECT_TRUE(status(kCommandError));
  // During a pause too: the homing is in progress (3601 manual ch. 4 "Find Home").
  command(cmd::kResetErrors);
  run_plc([this] { return motor() > 5'100; }, 5 * kNsPerSec);
  run_plc([this] { return !moving(); }, 5 * kNsPerSec);
  home(cmd::kFindHomeCcw);
  EXPECT_TRUE(status(kCommandError));
  ASSERT_TRUE(run_plc([this] { return status(kAtHome); }, 30 * kNsPerSec));
  EXPECT_EQ(motor(), 5'000);
}

TEST_F(Homing3601, CE_01_ConfigurationModeWaitsForTheHomingToFinish) {
  home(cmd::kFindHomeCw);
  run_plc([this] { return motor() > 5'100; }, 5 * kNsPerSec);
  write_config(kSwitchOnly, kAllActiveHigh, 1'000);
  vm_.scans(3);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(status(kConfigMode));
  // The pauses go on while the mode bit waits: the homing ends at the switch edge, then the
  // module enters configuration mode and CE clears.
  ASSERT_TRUE(vm_.run_until_true([this] { return status(kConfigMode); }, 30 * kNsPerSec));
  EXPECT_EQ(motor(), 5'000);
  EXPECT_FALSE(status(kCommandError));
}

TEST_F(Homing3601, STP_03_ImmediateStopDuringHoming) {
  home(cmd::kFindHomeCw);
  run_plc_for(300 * kNsPerMs);
  raw_command(cmd::kImmediateStop);
  const std::int64_t at = motor();
  run_plc_for(3 * kNsPerSec);
  EXPECT_LE(motor(), at + 1);
  EXPECT_TRUE(status(kStopped));
  EXPECT_TRUE(status(kPositionInvalid));  // 3601-PI-02
  EXPECT_FALSE(status(kAtHome));
  EXPECT_FALSE(status(kHomeInvalid));
  EXPECT_FALSE(status(kInputError));
}

TEST_F(Homing3601, External_InputHasNoEffectDuringHoming) {
  home(cmd::kFindHomeCw);
  run_plc_for(200 * kNsPerMs);
  force(InputLine::kExternal, true);
  run_plc_for(200 * kNsPerMs);
  EXPECT_TRUE(status(kMovingCw));
  ASSERT_TRUE(wait_end());
  expect_homed_at(5'000);
  EXPECT_FALSE(status(kHoldState));
}

// ---- Completion (AH-01, HI-C1, STP-N1) ---------------------------------------------------------

TEST_F(Homing3601, AH_01_CompletionZeroesPositionEncoderAndCapture) {
  command(cmd::kRelativeMove, {.target = 1'234});
  ASSERT_TRUE(wait_idle());
  force(InputLine::kCapture, true);
  vm_.scans(2);
  release(InputLine::kCapture);
  ASSERT_EQ(capture(), 1'234);  // encoder count captured
  ASSERT_EQ(encoder(), 1'234);
  ASSERT_TRUE(status(kPositionInvalid));  // configured, never preset
  home(cmd::kFindHomeCw);
  EXPECT_FALSE(status(kAtHome));
  ASSERT_TRUE(wait_end());
  EXPECT_TRUE(status(kAtHome));
  EXPECT_EQ(position(), 0);
  EXPECT_EQ(encoder(), 0);
  EXPECT_EQ(capture(), 0);
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_EQ(motor(), 5'000);
  // Positions now count from the home: an absolute move is allowed and lands where it should.
  command(cmd::kAbsoluteMove, {.target = -1'000});
  EXPECT_FALSE(status(kAtHome));  // cleared by the next motion
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), 4'000);
  EXPECT_EQ(position(), -1'000);
  EXPECT_EQ(encoder(), -1'000);
}

TEST_F(Homing3601, AH_01_ClearedByAManualMove) {
  home(cmd::kFindHomeCw);
  ASSERT_TRUE(wait_end());
  ASSERT_TRUE(status(kAtHome));
  set_words(cmd::kManualCcw, 0, 0, 2'000, 10, 10);
  vm_.scans(3);
  EXPECT_FALSE(status(kAtHome));
  word(0) = 0;
  ASSERT_TRUE(wait_idle());
}

TEST_F(Homing3601, HI_C1_SuccessfulHomingClearsHomeInvalid) {
  home(cmd::kFindHomeCw);
  run_plc_for(200 * kNsPerMs);
  force(InputLine::kCcwLimit, true);  // 3601-HI-05
  run_plc_for(100 * kNsPerMs);
  ASSERT_TRUE(status(kHomeInvalid));
  release(InputLine::kCcwLimit);
  home(cmd::kFindHomeCw);
  EXPECT_FALSE(status(kInputError));  // 3601-IE-C1: cleared by the new start
  EXPECT_TRUE(status(kHomeInvalid));  // HI only by success (or Reset Errors)
  ASSERT_TRUE(run_plc([this] { return status(kAtHome); }, 30 * kNsPerSec));
  EXPECT_FALSE(status(kHomeInvalid));
  EXPECT_FALSE(status(kPositionInvalid));
}

TEST_F(Homing3601, STP_N1_NoStoppedAfterHoming) {
  // A manual move leaves Stopped set (3601-STP-01); the homing clears it and does not set it.
  set_words(cmd::kManualCcw, 0, 0, 2'000, 10, 10);
  vm_.scans(50);
  word(0) = 0;
  ASSERT_TRUE(wait_idle());
  ASSERT_TRUE(status(kStopped));
  home(cmd::kFindHomeCw);
  EXPECT_FALSE(status(kStopped));
  ASSERT_TRUE(run_plc([this] { return status(kAtHome); }, 30 * kNsPerSec));
  run_plc_for(100 * kNsPerMs);
  EXPECT_FALSE(status(kStopped));
  EXPECT_FALSE(status(kMoveComplete));  // 3601-MC-02
}

// ---- Status bits during the sequence (DIR-01, ACC-01, LSW-01) ---------------------------------

TEST_F(Homing3601, DIR_01_ACC_01_StatusBitsFollowEachSegment) {
  home(cmd::kFindHomeCw);
  EXPECT_TRUE(status(kMovingCw));
  EXPECT_TRUE(status(kAccelerating));
  run_plc([this] { return lsw_status(m::status_lsw::kHomeActive); }, 5 * kNsPerSec);
  run_plc_for(5 * kNsPerMs);
  EXPECT_TRUE(status(kMovingCw));
  EXPECT_TRUE(status(kDecelerating));  // step 3
  run_plc([this] { return !moving(); }, 5 * kNsPerSec);
  run_plc_for(kNsPerSec);  // in the pause: no direction, no ramp bits
  EXPECT_EQ(status_msw() & (kMovingCw | kMovingCcw | kAccelerating | kDecelerating), 0);
  run_plc([this] { return moving(); }, 2 * kNsPerSec);
  run_plc_for(5 * kNsPerMs);        // the first steps of the new motion
  EXPECT_TRUE(status(kMovingCcw));  // step 4
  EXPECT_TRUE(status(kAccelerating));
  run_plc([this] { return !moving(); }, 5 * kNsPerSec);
  run_plc([this] { return moving(); }, 3 * kNsPerSec);
  run_plc_for(50 * kNsPerMs);
  EXPECT_TRUE(status(kMovingCw));  // step 7: the creep, no ramp
  EXPECT_FALSE(status(kAccelerating));
  EXPECT_FALSE(status(kDecelerating));
  ASSERT_TRUE(wait_end());
  EXPECT_EQ(status_msw() & (kMovingCw | kMovingCcw | kAccelerating | kDecelerating), 0);
}

TEST_F(Homing3601, LSW_01_A44_ProximityEchoIsLiveAndIgnoredUnlessConfigured) {
  // Option 1 (config bit 6 = 0): the echo still follows the bit (A44), at rest and homing.
  word(1) = kProx;
  vm_.scans(2);
  EXPECT_TRUE(lsw_status(m::status_lsw::kProximityEcho));
  word(1) = 0;
  vm_.scans(2);
  EXPECT_FALSE(lsw_status(m::status_lsw::kProximityEcho));
  home(cmd::kFindHomeCw);
  run_plc([this] { return motor() >= 2'000; }, 5 * kNsPerSec);
  word(1) = kProx;  // would slow an option-2 search to Vs; ignored here
  vm_.scans(5);
  EXPECT_TRUE(lsw_status(m::status_lsw::kProximityEcho));
  const auto& t = vm_.step_times(0);
  EXPECT_LT(t[t.size() - 1] - t[t.size() - 2], kStepAtVs / 5);  // still at Vp
  ASSERT_TRUE(wait_end());
  expect_homed_at(5'000);  // H-A, with its reversal and creep
  expect_pauses(2);
}

TEST_F(Homing3601, LSW_01_ProximityEchoDuringBackplaneHoming) {
  configure(kSwitchBackplane);
  prox_zone(4'000, 6'000);
  home(cmd::kFindHomeCw);
  run_plc([this] { return motor() >= 4'100; }, 5 * kNsPerSec);
  EXPECT_TRUE(lsw_status(m::status_lsw::kProximityEcho));
  EXPECT_TRUE(status(kDecelerating));  // slowing to Vs on the bit
  ASSERT_TRUE(wait_end());
  EXPECT_TRUE(lsw_status(m::status_lsw::kProximityEcho));  // 5,000 is inside the zone
  expect_homed_at(5'000);
}

}  // namespace
}  // namespace stepmod::testing
