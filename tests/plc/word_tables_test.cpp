// The modules' word tables (module_types/m3601/words_3601.hpp, m3602, m3202): the 3601 constants
// derived from the table keep the values the module code was written against, every table names
// each bit once, and status decoding by name reads them.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "plc/bit_names.hpp"
#include "module_types/m3202/plc_words_3202.hpp"
#include "module_types/m3202/words_3202.hpp"
#include "module_types/m3601/plc_words_3601.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "module_types/m3602/plc_words_3602.hpp"
#include "module_types/m3602/words_3602.hpp"

namespace stepmod::plc {
namespace {

namespace m = words::m3601;

// The values of words_3601.hpp before it became a table, written out as the manual gives them.
static_assert(m::kWords == (8));
static_assert(m::out_word::kMsw == (0));
static_assert(m::out_word::kLsw == (1));
static_assert(m::out_word::kTargetMsw == (2));
static_assert(m::out_word::kTargetLsw == (3));
static_assert(m::out_word::kSpeedMsw == (4));
static_assert(m::out_word::kSpeedLsw == (5));
static_assert(m::out_word::kAccel == (6));
static_assert(m::out_word::kDecel == (7));
static_assert(m::in_word::kStatusMsw == (0));
static_assert(m::in_word::kStatusLsw == (1));
static_assert(m::in_word::kPositionMsw == (2));
static_assert(m::in_word::kPositionLsw == (3));
static_assert(m::in_word::kEncoderMsw == (4));
static_assert(m::in_word::kEncoderLsw == (5));
static_assert(m::in_word::kCaptureMsw == (6));
static_assert(m::in_word::kCaptureLsw == (7));
static_assert(m::in_word::kFirmwareMajor == (6));
static_assert(m::in_word::kFirmwareMinor == (7));
static_assert(m::cfg_msw::kCaptureUsed == ((1u << 0)));
static_assert(m::cfg_msw::kExternalUsed == ((1u << 1)));
static_assert(m::cfg_msw::kHomeUsed == ((1u << 2)));
static_assert(m::cfg_msw::kEStopUsed == ((1u << 3)));
static_assert(m::cfg_msw::kCwLimitUsed == ((1u << 4)));
static_assert(m::cfg_msw::kCcwLimitUsed == ((1u << 5)));
static_assert(m::cfg_msw::kBackplaneProximity == ((1u << 6)));
static_assert(m::cfg_msw::kQuadratureEncoder == ((1u << 8)));
static_assert(m::cfg_msw::kDiagnosticFeedback == ((1u << 9)));
static_assert(m::cfg_msw::kStepDirOutput == ((1u << 10)));
static_assert(m::cfg_msw::kMarkerHoming == ((1u << 12)));
static_assert(m::cfg_msw::kConfigMode == ((1u << 15)));
static_assert(m::cfg_msw::kReserved == ((1u << 7) | (1u << 11) | (1u << 13) | (1u << 14)));
static_assert(m::cfg_lsw::kReserved == (0xFFC0));
static_assert(m::cmd_msw::kAbsoluteMove == ((1u << 0)));
static_assert(m::cmd_msw::kRelativeMove == ((1u << 1)));
static_assert(m::cmd_msw::kHold == ((1u << 2)));
static_assert(m::cmd_msw::kResume == ((1u << 3)));
static_assert(m::cmd_msw::kImmediateStop == ((1u << 4)));
static_assert(m::cmd_msw::kFindHomeCw == ((1u << 5)));
static_assert(m::cmd_msw::kFindHomeCcw == ((1u << 6)));
static_assert(m::cmd_msw::kManualCw == ((1u << 7)));
static_assert(m::cmd_msw::kManualCcw == ((1u << 8)));
static_assert(m::cmd_msw::kPresetPosition == ((1u << 9)));
static_assert(m::cmd_msw::kPresetEncoder == ((1u << 10)));
static_assert(m::cmd_msw::kResetErrors == ((1u << 11)));
static_assert(m::cmd_msw::kRunBlendCw == ((1u << 12)));
static_assert(m::cmd_msw::kRunBlendCcw == ((1u << 13)));
static_assert(m::cmd_msw::kReserved14 == ((1u << 14)));
static_assert(m::cmd_msw::kConfigMode == ((1u << 15)));
static_assert(m::cmd_msw::kCommandMask == (0x3FFF));
static_assert(m::cmd_lsw::kSCurve == ((1u << 0)));
static_assert(m::cmd_lsw::kTrapezoidalS == ((1u << 1)));
static_assert(m::cmd_lsw::kEncoderMove == ((1u << 2)));
static_assert(m::cmd_lsw::kEncoderFollower == ((1u << 7)));
static_assert(m::cmd_lsw::kProgramBlend == ((1u << 8)));
static_assert(m::cmd_lsw::kBlendTransmit == ((1u << 9)));
static_assert(m::cmd_lsw::kStoreMinRegistration == ((1u << 10)));
static_assert(m::cmd_lsw::kBackplaneProximity == ((1u << 12)));
static_assert(m::status_msw::kMovingCw == ((1u << 0)));
static_assert(m::status_msw::kMovingCcw == ((1u << 1)));
static_assert(m::status_msw::kHoldState == ((1u << 2)));
static_assert(m::status_msw::kStopped == ((1u << 3)));
static_assert(m::status_msw::kAtHome == ((1u << 4)));
static_assert(m::status_msw::kAccelerating == ((1u << 5)));
static_assert(m::status_msw::kDecelerating == ((1u << 6)));
static_assert(m::status_msw::kMoveComplete == ((1u << 7)));
static_assert(m::status_msw::kHomeInvalid == ((1u << 8)));
static_assert(m::status_msw::kInvalidProfile == ((1u << 9)));
static_assert(m::status_msw::kPositionInvalid == ((1u << 10)));
static_assert(m::status_msw::kInputError == ((1u << 11)));
static_assert(m::status_msw::kCommandError == ((1u << 12)));
static_assert(m::status_msw::kConfigurationError == ((1u << 13)));
static_assert(m::status_msw::kModuleOk == ((1u << 14)));
static_assert(m::status_msw::kConfigMode == ((1u << 15)));
static_assert(m::status_lsw::kCaptureActive == ((1u << 0)));
static_assert(m::status_lsw::kExternalActive == ((1u << 1)));
static_assert(m::status_lsw::kHomeActive == ((1u << 2)));
static_assert(m::status_lsw::kEStopActive == ((1u << 3)));
static_assert(m::status_lsw::kCwLimitActive == ((1u << 4)));
static_assert(m::status_lsw::kCcwLimitActive == ((1u << 5)));
static_assert(m::status_lsw::kFollowerMode == ((1u << 7)));
static_assert(m::status_lsw::kBlendRunning == ((1u << 8)));
static_assert(m::status_lsw::kBlendAcknowledge == ((1u << 9)));
static_assert(m::status_lsw::kMinRegistrationSet == ((1u << 10)));
static_assert(m::status_lsw::kProximityEcho == ((1u << 12)));
static_assert(m::kFirmwareMajor == (4));
static_assert(m::kFirmwareMinor == (1));
// No two fields of a table overlap and no two share a name.
void expect_well_formed(BitTable table, unsigned word_bits, const char* what) {
  std::uint64_t used = 0;
  std::set<std::string_view> names;
  for (const NamedBit& b : table) {
    const std::uint64_t mask = ((1ull << b.width) - 1) << b.bit;
    EXPECT_LE(b.bit + b.width, word_bits) << what << ": " << b.name;
    EXPECT_EQ(used & mask, 0u) << what << ": " << b.name << " overlaps another field";
    used |= mask;
    EXPECT_TRUE(names.insert(b.name).second) << what << ": " << b.name << " named twice";
  }
}

TEST(WordTables, EveryTableNamesEachBitOnce) {
  expect_well_formed(m::kConfigMswBits, 16, "3601 config MSW");
  expect_well_formed(m::kConfigLswBits, 16, "3601 config LSW");
  expect_well_formed(m::kCommandMswBits, 16, "3601 command MSW");
  expect_well_formed(m::kCommandLswBits, 16, "3601 command LSW");
  expect_well_formed(m::kStatusMswBits, 16, "3601 status MSW");
  expect_well_formed(m::kStatusLswBits, 16, "3601 status LSW");
  namespace m2 = words::m3602;
  expect_well_formed(m2::kConfigMswBits, 16, "3602 config MSW");
  expect_well_formed(m2::kConfigLswBits, 16, "3602 config LSW");
  expect_well_formed(m2::kCommandMswBits, 16, "3602 command MSW");
  expect_well_formed(m2::kCommandLswBits, 16, "3602 command LSW");
  expect_well_formed(m2::kStatusMswBits, 16, "3602 status MSW");
  expect_well_formed(m2::kStatusLswBits, 16, "3602 status LSW");
  namespace m3 = words::m3202;
  expect_well_formed(m3::kConfigBits, 32, "3202 configuration");
  expect_well_formed(m3::kConfigEchoBits, 32, "3202 configuration echo");
  expect_well_formed(m3::kCommandBits, 32, "3202 command");
  expect_well_formed(m3::kStatusBits, 32, "3202 status");
}

// The positions where the three manuals differ (3202 manual ch. 6; 3602 manual tables 8.2, 9.3).
TEST(WordTables, ThePositionsWhereTheModulesDiffer) {
  namespace m2 = words::m3602;
  namespace m3 = words::m3202;
  EXPECT_EQ((mask_of<std::uint32_t>(m3::kStatusBits, "Home Invalid")), 1u << 14);
  EXPECT_EQ((mask_of<std::uint32_t>(m3::kStatusBits, "Invalid Profile")), 1u << 15);
  EXPECT_EQ((mask_of<std::uint32_t>(m3::kStatusBits, "Module OK")), 1u << 30);
  EXPECT_EQ((mask_of<std::uint16_t>(m2::kStatusMswBits, "Axis Enabled")), 1u << 14);
  EXPECT_EQ(
      (mask_of<std::uint16_t>(m2::kConfigMswBits, "CW Input Function (1 = limit, 2 = E-stop)")),
      0b11u << 3);
  EXPECT_EQ((mask_of<std::uint16_t>(m2::kCommandLswBits, "Program Blend Move")), 1u << 4);
  EXPECT_EQ((mask_of<std::uint16_t>(m::kCommandLswBits, "Program Blend Move")), 1u << 8);
}

TEST(BitNames, SetFieldsByNameInBitOrder) {
  EXPECT_EQ(set_bit_names(m::status_msw::kModuleOk | m::status_msw::kMovingCw, m::kStatusMswBits),
            "Moving CW, Module OK");
  EXPECT_EQ(set_bit_names(0, m::kStatusMswBits), "-");
  // A two-bit field shows its value: CW input as E-stop (10b at bits 4:3).
  EXPECT_EQ(set_bit_names(0b10u << 3, words::m3602::kConfigMswBits),
            "CW Input Function (1 = limit, 2 = E-stop)=2");
}

}  // namespace
}  // namespace stepmod::plc

namespace stepmod::plc {
namespace {

// plc/accel_bits.hpp finds each manual's S-curve bits by name: the values the dialects had
// written out by hand.
TEST(PlcAccelBits, EachModuleGetsTheBitsItsManualGivesEachType) {
  namespace m1 = words::m3601;
  namespace m2 = words::m3602;
  namespace m3 = words::m3202;
  EXPECT_EQ(m3601::accel_bits(AccelType::kConstant), 0);
  EXPECT_EQ(m3601::accel_bits(AccelType::kTriangularS), m1::cmd_lsw::kSCurve);
  EXPECT_EQ(m3601::accel_bits(AccelType::kTrapezoidalS),
            m1::cmd_lsw::kSCurve | m1::cmd_lsw::kTrapezoidalS);
  EXPECT_EQ(m3602::accel_bits(AccelType::kConstant), 0);
  EXPECT_EQ(m3602::accel_bits(AccelType::kTriangularS), m2::cmd_lsw::kSCurve);
  EXPECT_EQ(m3602::accel_bits(AccelType::kTrapezoidalS),
            m2::cmd_lsw::kSCurve | m2::cmd_lsw::kTrapezoidalS);
  EXPECT_EQ(m3202::accel_bits(AccelType::kConstant), 0u);
  EXPECT_EQ(m3202::accel_bits(AccelType::kTriangularS), m3::cmd_bit::kSCurve);
  EXPECT_EQ(m3202::accel_bits(AccelType::kTrapezoidalS),
            m3::cmd_bit::kSCurve | m3::cmd_bit::kTrapezoidalS);
}

}  // namespace
}  // namespace stepmod::plc
