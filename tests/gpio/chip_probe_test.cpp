// The chip probe's decisions over a fake chip list (the kernel's own chips: tests/vm's
// check_hardware_* cases): which chip a `chip` value names, what a missing chip's message lists,
// which configured lines are past the chip's end or busy.
#include "gpio/chip_probe.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace stepmod::gpio {
namespace {

// A Raspberry Pi 5 on a kernel where the header's RP1 chip is not gpiochip0.
const std::vector<ChipInfo> kPi5 = {
    {"/dev/gpiochip0", "gpiochip0", "gpio-brcmstb@107d508500", 32, 0},
    {"/dev/gpiochip4", "gpiochip4", "pinctrl-rp1", 54, 0},
    {"/dev/gpiochip10", "gpiochip10", "gpio-brcmstb@107d517c00", 4, 0},
};

TEST(ChipProbe, FindsAChipByNameNumberPathOrLabel) {
  EXPECT_EQ(find_chip(kPi5, "pinctrl-rp1")->path, "/dev/gpiochip4");
  EXPECT_EQ(find_chip(kPi5, "gpiochip4")->label, "pinctrl-rp1");
  EXPECT_EQ(find_chip(kPi5, "4")->name, "gpiochip4");
  EXPECT_EQ(find_chip(kPi5, "/dev/gpiochip10")->lines, 4u);
  EXPECT_FALSE(find_chip(kPi5, "gpiochip9"));
  EXPECT_FALSE(find_chip(kPi5, "pinctrl-bcm2711"));
  EXPECT_FALSE(find_chip(kPi5, ""));
}

TEST(ChipProbe, ANameWinsOverALabelThatLooksLikeIt) {
  const std::vector<ChipInfo> chips = {{"/dev/gpiochip0", "gpiochip0", "gpiochip1", 8, 0},
                                       {"/dev/gpiochip1", "gpiochip1", "other", 8, 0}};
  EXPECT_EQ(find_chip(chips, "gpiochip1")->path, "/dev/gpiochip1");
}

TEST(ChipProbe, AMissingChipListsTheChipsThatExistAndGpiodetect) {
  const std::string m = chip_missing_message("gpiochip9", kPi5);
  EXPECT_NE(m.find("GPIO chip 'gpiochip9' not found"), std::string::npos) << m;
  EXPECT_NE(m.find("gpiodetect"), std::string::npos) << m;
  EXPECT_NE(m.find("gpiochip4 [pinctrl-rp1] (54 lines)"), std::string::npos) << m;
  EXPECT_NE(m.find("gpiochip0 [gpio-brcmstb@107d508500] (32 lines)"), std::string::npos) << m;
  const std::string none = chip_missing_message("pinctrl-rp1", {});
  EXPECT_NE(none.find("no GPIO chip"), std::string::npos) << none;
  EXPECT_NE(none.find("gpiodetect"), std::string::npos) << none;
}

TEST(ChipProbe, AChipThatCannotBeOpenedIsListedWithWhyAndTheGroupHint) {
  const std::vector<ChipInfo> chips = {{"/dev/gpiochip0", "gpiochip0", "", 0, EACCES}};
  EXPECT_NE(chip_list_text(chips).find("gpiochip0 (cannot open: Permission denied)"),
            std::string::npos);
  EXPECT_NE(chip_access_hint(EACCES).find("usermod -aG gpio"), std::string::npos);
  EXPECT_EQ(chip_access_hint(ENOENT), "");
}

std::vector<AxisLines> one_axis(unsigned step, unsigned dir, unsigned home) {
  AxisLines a;
  a.out[static_cast<unsigned>(OutputLine::kStep)] = step;
  a.out[static_cast<unsigned>(OutputLine::kDir)] = dir;
  a.in[static_cast<unsigned>(InputLine::kHome)] = home;
  return {a};
}

TEST(ChipProbe, ConfiguredLinesCarryTheirKeys) {
  const std::vector<LineState> lines = configured_lines(one_axis(17, 27, 13));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].key, "axis1.step");
  EXPECT_EQ(lines[0].offset, 17u);
  EXPECT_EQ(lines[2].key, "axis1.home");
}

TEST(ChipProbe, ALinePastTheChipsLastOneOrBusyIsAProblem) {
  const ChipInfo small = kPi5[2];  // 4 lines
  std::vector<LineState> lines = configured_lines(one_axis(3, 4, 13));
  EXPECT_TRUE(line_problems(kPi5[1], lines).empty());
  const std::vector<std::string> p = line_problems(small, lines);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NE(p[0].find("line 4 (axis1.dir): offset out of range (the chip has 4 lines, 0..3"),
            std::string::npos)
      << p[0];
  EXPECT_NE(p[1].find("axis1.home"), std::string::npos) << p[1];
  lines[0].used = true;
  lines[0].consumer = "other-app";
  const std::vector<std::string> busy = line_problems(kPi5[1], lines);
  ASSERT_EQ(busy.size(), 1u);
  EXPECT_NE(busy[0].find("line 3 (axis1.step): line busy (used by 'other-app'"), std::string::npos)
      << busy[0];
  lines[0].consumer = "stepmod";
  EXPECT_NE(line_problems(kPi5[1], lines)[0].find("a stepmodd running?"), std::string::npos);
}

TEST(ChipProbe, ADirectoryWithoutChipsHasNoneAndTheProbeSaysSo) {
  const std::string dir = ::testing::TempDir() + "/no-chips";
  std::filesystem::create_directories(dir);
  EXPECT_TRUE(list_chips(dir).empty());
  try {
    probe_chip("pinctrl-rp1", one_axis(17, 27, 13), dir);
    FAIL() << "probe_chip found a chip in an empty directory";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'pinctrl-rp1' not found"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stepmod::gpio
