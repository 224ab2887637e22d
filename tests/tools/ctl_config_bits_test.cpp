// stepmodctl's configure flags for the configuration bits that the 3601 and the 3202 name alike
// (tools/ctl_args.hpp shared_config_bits, words/shared_config_bits.hpp): each flag sets exactly
// the bit of the name the manual gives it, at its module's position (3601 manual ch. 3
// configuration MSW, 3202 manual ch. 3 configuration DINT); --cw-ccw clears Step+Direction Output.
#include <gtest/gtest.h>

#include <cstdint>
#include <string_view>
#include <utility>

#include "core/bit_table.hpp"
#include "module_types/m3202/words_3202.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "tools/ctl_args.hpp"

namespace stepmod::tools::ctl {
namespace {

// Written out here again on purpose: a mask that the shared table gives the wrong name fails.
const std::pair<bool ConfigureArgs::*, std::string_view> kFlagNames[] = {
    {&ConfigureArgs::capture, "Capture Input Used"},
    {&ConfigureArgs::external, "External Input Used"},
    {&ConfigureArgs::home, "Home Input Used"},
    {&ConfigureArgs::estop, "E-Stop Input Used"},
    {&ConfigureArgs::cw_limit, "CW Limit Used"},
    {&ConfigureArgs::ccw_limit, "CCW Limit Used"},
    {&ConfigureArgs::proximity, "Backplane Home Proximity"},
    {&ConfigureArgs::encoder, "Quadrature Encoder"},
    {&ConfigureArgs::diagnostic, "Diagnostic Feedback"},
    {&ConfigureArgs::marker, "Marker Homing (0 = home switch)"},
};
constexpr std::string_view kStepDir = "Step+Direction Output (0 = CW/CCW)";

std::uint32_t bit_named(BitTable table, std::string_view name) {
  for (const NamedBit& b : table) {
    if (b.name == name) return 1u << b.bit;
  }
  ADD_FAILURE() << "no bit named " << name;
  return 0;
}

void expect_each_flag_sets_its_bit(BitTable table, const words::SharedConfigMasks& m) {
  const std::uint32_t step_dir = bit_named(table, kStepDir);
  EXPECT_EQ(shared_config_bits(ConfigureArgs{}, m), step_dir) << "no flag: step+direction only";
  ConfigureArgs cw_ccw;
  cw_ccw.cw_ccw = true;
  EXPECT_EQ(shared_config_bits(cw_ccw, m), 0u) << "--cw-ccw clears Step+Direction Output";
  for (const auto& [flag, name] : kFlagNames) {
    ConfigureArgs a;
    a.*flag = true;
    EXPECT_EQ(shared_config_bits(a, m), bit_named(table, name) | step_dir) << name;
  }
}

TEST(CtlConfigBits, Each3601FlagSetsTheBitTheConfigurationMswNames) {
  expect_each_flag_sets_its_bit(words::m3601::kConfigMswBits, words::m3601::cfg_msw::kShared);
}

TEST(CtlConfigBits, Each3202FlagSetsTheBitTheConfigurationDintNames) {
  expect_each_flag_sets_its_bit(words::m3202::kConfigBits, words::m3202::cfg_bit::kShared);
}

}  // namespace
}  // namespace stepmod::tools::ctl
