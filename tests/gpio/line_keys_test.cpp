#include <gtest/gtest.h>

#include "gpio/backend.hpp"

namespace stepmod::gpio {

TEST(GpioLineKeys, InputKeysAreTheConfigKeys) {
  EXPECT_EQ(input_key(InputLine::kCapture), "capture");
  EXPECT_EQ(input_key(InputLine::kExternal), "external");
  EXPECT_EQ(input_key(InputLine::kHome), "home");
  EXPECT_EQ(input_key(InputLine::kEStop), "estop");
  EXPECT_EQ(input_key(InputLine::kCwLimit), "cw_limit");
  EXPECT_EQ(input_key(InputLine::kCcwLimit), "ccw_limit");
  EXPECT_EQ(input_key(InputLine::kEncA), "enc_a");
  EXPECT_EQ(input_key(InputLine::kEncB), "enc_b");
  EXPECT_EQ(input_key(InputLine::kEncZ), "enc_z");
}

TEST(GpioLineKeys, OutputKeysAreTheConfigKeys) {
  EXPECT_EQ(output_key(OutputLine::kStep), "step");
  EXPECT_EQ(output_key(OutputLine::kDir), "dir");
  EXPECT_EQ(output_key(OutputLine::kGpo), "gpo");
}

}  // namespace stepmod::gpio
