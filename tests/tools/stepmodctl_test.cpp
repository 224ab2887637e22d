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
      "resume -a 1000",  // all three or none
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
  const CtlRun status = stepmodctl("-n " + n + " status");
  EXPECT_EQ(status.exit_status, 0) << status.err;
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

TEST(Stepmodctl, A3602OnlyOptionOnA3601IsAUsageErrorAndWritesNothing) {
  const std::string n = image_name("3601axis");
  ipc::ShmImage img(n, {ModuleType::k3601, 1, 2, 8, 8});
  EXPECT_EQ(stepmodctl("-n " + n + " --axis 2 stop").exit_status, 2);
  EXPECT_EQ(stepmodctl("-n " + n + " configure --home --cw-estop").exit_status, 2);
  EXPECT_EQ(stepmodctl("-n " + n + " gpo on").exit_status, 2);
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
