// The unit-state block as the page gets it (docs/interface.md 3.6, web/unit_state.hpp): the
// configuration a unit took decoded by its module's view into the form's fields, each input line,
// the drive enable.
#include <gtest/gtest.h>

#include "web/unit_state.hpp"

namespace stepmod::web {
namespace {

TEST(WebUnitState, NoConfigurationTakenYetIsNull) {
  stepmod_unit_state_t s{};
  EXPECT_TRUE(unit_state_json(ModuleType::k3601, s)["config"].is_null());
  EXPECT_TRUE(unit_state_json(ModuleType::k3601, std::nullopt).is_null());
}

TEST(WebUnitState, The3602sWordsAreTheFormsFieldsWithTheHomingTimeout) {
  stepmod_unit_state_t s{};
  s.config_seq = 4;
  s.config_words[0] = static_cast<std::int16_t>(0x844C);  // mode bit 15 + the form's bits
  s.config_words[1] = 0x1F;
  s.config_words[2] = 0;
  s.config_words[3] = 321;  // starting speed, binary split
  s.config_words[4] = 30;   // homing timeout, s
  const auto c = unit_state_json(ModuleType::k3602, s)["config"];
  EXPECT_EQ(c["seq"], 4);
  EXPECT_EQ(c["msw"], 0x844C);
  EXPECT_EQ(c["lsw"], 0x1F);
  EXPECT_EQ(c["start_speed"], 321);
  EXPECT_EQ(c["homing_timeout"], 30);
}

TEST(WebUnitState, The3601sStartingSpeedIsSplitInThousands) {
  stepmod_unit_state_t s{};
  s.config_seq = 1;
  s.config_words[0] = static_cast<std::int16_t>(0x8104);
  s.config_words[2] = 12;  // 12,345 steps/s: 12 thousands and 345
  s.config_words[3] = 345;
  const auto c = unit_state_json(ModuleType::k3601, s)["config"];
  EXPECT_EQ(c["msw"], 0x8104);
  EXPECT_EQ(c["start_speed"], 12345);
  EXPECT_FALSE(c.contains("homing_timeout"));
}

TEST(WebUnitState, The3202sDintAndStartingSpeed) {
  stepmod_unit_state_t s{};
  s.config_seq = 1;
  s.config_words[0] = static_cast<std::int32_t>(0x80000134u);
  s.config_words[1] = 1000;
  const auto c = unit_state_json(ModuleType::k3202, s)["config"];
  EXPECT_EQ(c["bits"], 0x80000134u);
  EXPECT_EQ(c["start_speed"], 1000);
}

TEST(WebUnitState, InputLinesAndDriveEnable) {
  stepmod_unit_state_t s{};
  // home: wired, used, level 1, active; capture: wired only; E-stop: not wired.
  s.inputs = (0x04u << STEPMOD_UNIT_LEVELS_SHIFT) | (0x05u << STEPMOD_UNIT_WIRED_SHIFT) |
             (0x04u << STEPMOD_UNIT_USED_SHIFT) | (0x04u << STEPMOD_UNIT_ACTIVE_SHIFT);
  s.drive_enable = STEPMOD_UNIT_ENABLE_WIRED;
  const auto j = unit_state_json(ModuleType::k3601, s);
  const auto& in = j["inputs"];
  ASSERT_EQ(in.size(), 6u);
  EXPECT_EQ(in[2]["name"], "home");
  EXPECT_EQ(in[2]["level"], true);
  EXPECT_EQ(in[2]["active"], true);
  EXPECT_EQ(in[2]["used"], true);
  EXPECT_EQ(in[0]["wired"], true);
  EXPECT_EQ(in[0]["used"], false);
  EXPECT_EQ(in[3]["name"], "estop");
  EXPECT_EQ(in[3]["wired"], false);
  EXPECT_EQ(j["enable"]["wired"], true);
  EXPECT_EQ(j["enable"]["asserted"], false);
}

}  // namespace
}  // namespace stepmod::web
