// The example board config (examples/3601-board.toml) documents the [[axis]] line options and the
// drive-enable keys in comments. Uncommented as a user would, they must be a valid configuration
// that carries those options: the example cannot drift from the parser. debounce_us is refused
// by a build with libgpiod 1.6, as the comment next to it says.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "gpio/line_options.hpp"
#include "config/config.hpp"

namespace stepmod::tools {
namespace {

std::string example() {
  std::ifstream in(std::string(STEPMOD_SOURCE_DIR) + "/examples/3601-board.toml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The example with its commented `home = { ... }` line in place of `home = 13` in [[axis]] (the
// comment stands above the section) and its commented `enable...` lines in force.
std::string uncommented(std::string text) {
  std::smatch m;
  if (std::regex_search(text, m, std::regex("\n#   (home = \\{[^\n]*\\})"))) {
    const std::string table = m[1];
    text = std::regex_replace(text, std::regex("\nhome = 13\n"), "\n" + table + "\n");
  }
  return std::regex_replace(text, std::regex("\n#   (enable[a-z_]* = [^#\n]*[^# \n])[^\n]*"),
                            "\n$1");
}

TEST(ExampleBoardConfig, CommentedLineOptionsAndEnableKeysAreValid) {
  const std::string text = uncommented(example());
  ASSERT_NE(text.find("\nhome = { offset = 13, bias = \"pull-up\", debounce_us = 2000 }"),
            std::string::npos)
      << "the example's commented home line changed:\n"
      << text;
  ASSERT_NE(text.find("\nenable = { offset = 22, active_low = true }"), std::string::npos) << text;
  ASSERT_NE(text.find("\nenable_release_on = [\"estop\"]"), std::string::npos) << text;
  if (!gpio::gpiod_capabilities().debounce) {
    try {
      parse_config(text, "3601-board.toml");
      FAIL() << "debounce_us accepted by a libgpiod 1.6 build";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("debounce_us"), std::string::npos) << e.what();
    }
    return;
  }
  const Config c = parse_config(text, "3601-board.toml");
  const AxisSection& a = c.axes.at(0);
  const gpio::LineOptions& home = a.in_opt[static_cast<unsigned>(InputLine::kHome)];
  EXPECT_EQ(a.in[static_cast<unsigned>(InputLine::kHome)], 13u);
  EXPECT_EQ(home.bias, gpio::Bias::kPullUp);
  EXPECT_EQ(home.debounce_us, 2000u);
  EXPECT_EQ(a.enable, 22u);
  EXPECT_TRUE(a.enable_opt.active_low);
  EXPECT_EQ(a.enable_delay_ns, 10 * kNsPerMs);
  EXPECT_EQ(a.enable_release, kReleaseOnEStop);
}

TEST(ExampleBoardConfig, WithoutDebounceTheCommentedOptionsParseOnEveryBuild) {
  std::string text = uncommented(example());
  text = std::regex_replace(text, std::regex(", debounce_us = 2000"), "");
  const Config c = parse_config(text, "3601-board.toml");
  EXPECT_EQ(c.axes.at(0).in_opt[static_cast<unsigned>(InputLine::kHome)].bias, gpio::Bias::kPullUp);
  EXPECT_EQ(c.axes.at(0).enable, 22u);
}

}  // namespace
}  // namespace stepmod::tools
