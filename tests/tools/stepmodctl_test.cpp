// The stepmodctl program against images nobody scans: the command dialect is chosen from the
// image header, a command writes only its axis' / channel's words, and bad input never writes a
// word (exit 2). tests/integration/stepmodctl_daemon_test.cpp runs it against a real daemon.
#include <unistd.h>

#include <gtest/gtest.h>

#include <string>

#include "ipc/client.hpp"
#include "ipc/shm_image.hpp"
#include "tests/support/ctl_run.hpp"

namespace stepmod::tools {
namespace {

using testing::CtlRun;
using testing::stepmodctl;

std::string image_name(const char* tag) {
  return std::string("ctl-") + tag + "-" + std::to_string(::getpid());
}

ImageWords outputs_of(const std::string& name) {
  ipc::Client c(name);
  ImageWords w;
  c.read_outputs(w);
  return w;
}

TEST(Stepmodctl, A3202CommandWritesOnlyItsChannelsDints) {
  const std::string n = image_name("3202");
  ipc::ShmImage img(n, {ModuleType::k3202, 2, 4, 16, 16});
  // Nobody scans this image: the words are written, then the wait times out (exit 3).
  const CtlRun r =
      stepmodctl("-n " + n + " --timeout 200 -c 2 move abs 100 -s 1000 -a 100000 -d 50000");
  EXPECT_EQ(r.exit_status, 3) << r.err;
  const ImageWords w = outputs_of(n);
  for (unsigned i = 0; i < 8; ++i) EXPECT_EQ(w.w[i], 0) << "channel 1 DINT " << i;
  EXPECT_EQ(w.w[8], 0);  // the edge-triggered bit is released after the wait
  EXPECT_EQ(w.w[9], 100);
  EXPECT_EQ(w.w[10], 1'000);
  EXPECT_EQ(w.w[11], 100'000);  // steps/s^2, a native DINT (A31)
  EXPECT_EQ(w.w[12], 50'000);
}

TEST(Stepmodctl, A3202RefusesWhatItLacksAndABadChannel) {
  const std::string n = image_name("3202");
  ipc::ShmImage img(n, {ModuleType::k3202, 2, 4, 16, 16});
  const CtlRun follow = stepmodctl("-n " + n + " follow +");
  EXPECT_EQ(follow.exit_status, 2) << follow.err;
  const CtlRun reg = stepmodctl("-n " + n + " jog + -s 1000 -a 1000 -d 1000 --registration 5");
  EXPECT_EQ(reg.exit_status, 2) << reg.err;
  const CtlRun channel = stepmodctl("-n " + n + " -c 3 stop");
  EXPECT_EQ(channel.exit_status, 2) << channel.err;
  const char* bad[] = {
      "min-registration 100",                            // no registration move
      "gpo on",                                          // no GPO
      "configure --cw-estop",                            // the 3602's
      "configure --active-low brake",                    // no such input
      "move abs 4294967296 -s 1000 -a 1000 -d 1000",     // beyond a DINT
      "blend program --file /nonexistent/profile.txt",   // unreadable
      "blend program --file /dev/null --segment 1:2:3",  // one source
      "blend program --segment 100:1000:1000 --segment 100:x:1000 --final-decel 1",
      "resume -a 1000",                         // all three or none
      "path line 1 2 -s 1000 -a 1000 -d 1000",  // no interpolated moves
      "path wait",
  };
  for (const char* args : bad) {
    const CtlRun r = stepmodctl("-n " + n + " --timeout 200 -c 2 " + args);
    EXPECT_EQ(r.exit_status, 2) << args << ": " << r.err;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  EXPECT_EQ(outputs_of(n), ImageWords{});
}

TEST(Stepmodctl, A3602CommandWritesOnlyItsAxisWordsStatusDecodesBoth) {
  const std::string n = image_name("3602");
  ipc::ShmImage img(n, {ModuleType::k3602, 2, 2, 16, 16});
  // Nobody scans this image: the words are written, then the wait times out (exit 3).
  const CtlRun r = stepmodctl("-n " + n + " --timeout 200 --axis 2 home + -s 5000 -a 10 -d 20");
  EXPECT_EQ(r.exit_status, 3) << r.err;
  const ImageWords w = outputs_of(n);
  for (unsigned i = 0; i < 8; ++i) EXPECT_EQ(w.w[i], 0) << "axis 1 word " << i;
  EXPECT_EQ(w.w[8], 0);  // the edge-triggered bit is released after the wait
  EXPECT_EQ(w.w[10], 0);
  EXPECT_EQ(w.w[11], 0);  // Find Home: words 2/3 reserved 0
  EXPECT_EQ(w.w[12], 0);
  EXPECT_EQ(w.w[13], 5'000);  // binary split: MSW 0, LSW 5000
  EXPECT_EQ(w.w[14], 10);
  EXPECT_EQ(w.w[15], 20);
  // Nobody scans: status shows the words as they are, says the module does not scan, exit 3.
  const CtlRun status = stepmodctl("-n " + n + " status");
  EXPECT_EQ(status.exit_status, 3) << status.err;
  EXPECT_NE(status.err.find("is not scanning"), std::string::npos) << status.err;
  EXPECT_NE(status.out.find("3602 axis 1 in COMMAND mode"), std::string::npos) << status.out;
  EXPECT_NE(status.out.find("3602 axis 2 in COMMAND mode"), std::string::npos) << status.out;
}

TEST(Stepmodctl, A3602RefusesWhatItLacksAndWhatItsWordsCannotCarry) {
  const std::string n = image_name("3602bad");
  ipc::ShmImage img(n, {ModuleType::k3602, 2, 2, 16, 16});
  const char* bad[] = {
      "follow +",                                     // no encoder follower
      "preset-encoder 5",                             // no encoder
      "move rel 5 -s 1000 -a 10 -d 10 --encoder",     // no encoder move
      "--axis 3 stop",                                // two axes
      "--axis 1 --channel 2 stop",                    // contradicting unit
      "move abs 4294967296 -s 1000 -a 10 -d 10",      // beyond int32
      "move abs 5 -s 1000 -a 40000 -d 10",            // accel beyond a 16-bit word
      "move abs 12x -s 1000 -a 10 -d 10",             // not a number
      "configure --estop",                            // no E-stop terminal
      "configure --cw-limit --cw-estop",              // limit or E-stop
      "configure --active-low estop",                 // no estop input
      "jog + -s 1000 -a 10 -d 10 --registration 0x",  // not a number
      "blend program --segment 100:1000:10 --segment 100:1000:10 --final-decel 3000",  // > 2047
      "blend program --segment 100:1000:10",  // no final decel
      "blend run up",                         // direction
      "resume -s 1000",                       // all three or none
      "gpo maybe",                            // on or off
  };
  for (const char* args : bad) {
    const CtlRun r = stepmodctl("-n " + n + " --timeout 200 " + args);
    EXPECT_EQ(r.exit_status, 2) << args << ": " << r.err;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  EXPECT_EQ(outputs_of(n), ImageWords{});
}

// An interpolated move writes the whole block, data first with the command bits clear (nobody
// scans this image: the bits never follow, exit 3).
TEST(Stepmodctl, A3602PathWritesTheInterpolatedBlockDataFirst) {
  const std::string n = image_name("3602path");
  ipc::ShmImage img(n, {ModuleType::k3602, 2, 2, 16, 16});
  const CtlRun r = stepmodctl(
      "-n " + n + " --timeout 200 path radius ccw -- 70000 -3 -40000 -s 5000 -a 10 -d 20");
  EXPECT_EQ(r.exit_status, 2) << r.err;  // options after "--" are positional: a usage error
  const CtlRun ok = stepmodctl("-n " + n +
                               " --timeout 200 path radius ccw 70000 -3 -40000 -s 70000 -a 10 "
                               "-d 20 --scurve trap");
  EXPECT_EQ(ok.exit_status, 3) << ok.err;
  const ImageWords w = outputs_of(n);
  EXPECT_EQ(w.w[0], 0);
  EXPECT_EQ(w.w[1], 3);  // S-curve + trapezoidal (bits 0, 1); no command bits yet
  EXPECT_EQ(w.w[2], 1);  // 70,000 = 16#0001 / 16#1170
  EXPECT_EQ(w.w[3], 0x1170);
  EXPECT_EQ(w.w[4], 10);
  EXPECT_EQ(w.w[5], 20);
  EXPECT_EQ(w.w[6], 1);  // X
  EXPECT_EQ(w.w[7], 0x1170);
  EXPECT_EQ(w.w[8], 0);  // axis 2's command words: reserved
  EXPECT_EQ(w.w[9], 0);
  EXPECT_EQ(w.w[10], -1);  // Y = -3: 16#FFFF / 16#FFFD
  EXPECT_EQ(w.w[11], -3);
  EXPECT_EQ(w.w[12], -1);  // R = -40,000: 16#FFFF / 16#63C0
  EXPECT_EQ(w.w[13], static_cast<std::int16_t>(0x63C0));
  EXPECT_EQ(w.w[14], 0);  // the radius method leaves words 14/15 reserved
  EXPECT_EQ(w.w[15], 0);
}

TEST(Stepmodctl, A3602PathBadInputIsAUsageErrorAndWritesNothing) {
  const std::string n = image_name("3602pathbad");
  ipc::ShmImage img(n, {ModuleType::k3602, 2, 2, 16, 16});
  const char* bad[] = {
      "path line 100 -s 1000 -a 10 -d 10",                    // no Y
      "path line 100 200",                                    // no profile
      "path line 100 200 -s 1000 -a 10",                      // no decel
      "path line 4294967296 0 -s 1000 -a 10 -d 10",           // beyond int32
      "path line 0x 0 -s 1000 -a 10 -d 10",                   // not a number
      "path line 1 2 -s 1000 -a 40000 -d 10",                 // accel beyond a 16-bit word
      "path line 1 2 -s 1000 -a 10 -d 10 --scurve smooth",    // accel type
      "path centre 100 0 50 0 -s 1000 -a 10 -d 10",           // no sense
      "path centre up 0 0 50 0 -s 1000 -a 10 -d 10",          // not cw / ccw
      "path centre cw 0 0 50 -s 1000 -a 10 -d 10",            // no CY
      "path radius cw 100 0 -s 1000 -a 10 -d 10",             // no R
      "path radius cw 100 0 2147483648 -s 1000 -a 10 -d 10",  // R beyond int32
      "path via 100 0 50 -s 1000 -a 10 -d 10",                // no VY
      "path via cw 100 0 50 50 -s 1000 -a 10 -d 10",          // a via arc has no sense option
      "path spiral 1 2 -s 1000 -a 10 -d 10",                  // no such method
      "--axis 2 path line 1 2 -s 1000 -a 10 -d 10",           // commanded on axis 1
      "--axis 2 path wait",                                   // both axes
      "path wait --max -1",                                   // negative
  };
  for (const char* args : bad) {
    const CtlRun r = stepmodctl("-n " + n + " --timeout 200 " + args);
    EXPECT_EQ(r.exit_status, 2) << args << ": " << r.err;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  EXPECT_EQ(outputs_of(n), ImageWords{});
}

TEST(Stepmodctl, A3602OnlyOptionOnA3601IsAUsageErrorAndWritesNothing) {
  const std::string n = image_name("3601axis");
  ipc::ShmImage img(n, {ModuleType::k3601, 1, 2, 8, 8});
  EXPECT_EQ(stepmodctl("-n " + n + " --axis 2 stop").exit_status, 2);
  EXPECT_EQ(stepmodctl("-n " + n + " configure --home --cw-estop").exit_status, 2);
  EXPECT_EQ(stepmodctl("-n " + n + " gpo on").exit_status, 2);
  EXPECT_EQ(stepmodctl("-n " + n + " path line 1 2 -s 1000 -a 10 -d 10").exit_status, 2);
  EXPECT_EQ(stepmodctl("-n " + n + " path wait").exit_status, 2);
  EXPECT_EQ(stepmodctl("-n " + n +
                       " blend program --segment 1:1000:10 --segment 1:1000:10 "
                       "--final-decel 20000")
                .exit_status,
            2);  // beyond bits 13..0 of word 5
  EXPECT_EQ(outputs_of(n), ImageWords{});
}

TEST(Stepmodctl, A3601TargetTheWordsCannotCarryIsAUsageErrorAndWritesNothing) {
  const std::string n = image_name("3601");
  ipc::ShmImage img(n, {ModuleType::k3601, 1, 2, 8, 8});
  const CtlRun r = stepmodctl("-n " + n + " move abs 65537000 -s 1000 -a 10 -d 10");
  EXPECT_EQ(r.exit_status, 2) << r.err;
  EXPECT_NE(r.err.find("does not fit"), std::string::npos) << r.err;
  EXPECT_EQ(outputs_of(n), ImageWords{});
}

TEST(Stepmodctl, AFollowerRatioTheWordsCannotCarryIsAUsageErrorAndWritesNothing) {
  const std::string n = image_name("follow");
  ipc::ShmImage img(n, {ModuleType::k3601, 1, 2, 8, 8});
  const CtlRun r = stepmodctl("-n " + n + " follow + --multiplier 40000");
  EXPECT_EQ(r.exit_status, 2) << r.err;
  EXPECT_EQ(outputs_of(n), ImageWords{});
}

}  // namespace
}  // namespace stepmod::tools
