// End to end: the stepmodctl program driving the real stepmodd on the simulated machine, with the
// shipped examples (examples/3602-sim.toml, 3202-sim.toml) as configuration. Each 3602 and 3202
// command of stepmodctl runs here against a daemon, checked through the status it prints, the
// image, the panel and the exact step counts of the VCD trace.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include "ipc/client.hpp"
#include "module_types/m3202/plc_status_3202.hpp"
#include "module_types/m3602/plc_status_3602.hpp"
#include "tests/support/ctl_run.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/vcd_reader.hpp"
#include "module_types/m3202/words_3202.hpp"
#include "module_types/m3602/words_3602.hpp"

namespace stepmod::testing {
namespace {

using std::chrono::milliseconds;

// The example with the harness' name placeholder and the late-edge limit of a loaded test VM
// (the guard has its own tests).
std::string example(const char* file) {
  std::string t = slurp_file(std::string(STEPMOD_SOURCE_DIR) + "/examples/" + file);
  const auto replace = [&t](const std::string& from, const std::string& to) {
    const auto at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at == std::string::npos) return;
    const auto end = t.find('\n', at);
    t.replace(at, end - at, to);
  };
  replace("name = \"stepmod\"", "name = \"{NAME}\"");
  // The guard at its loosest: a loaded, shared VM (tests/support/sim_config.hpp says why).
  replace("[rt]", "[rt]\nlate_limit_us = 1000000");
  for (std::size_t at = t.find("lag_limit_steps = "); at != std::string::npos;
       at = t.find("lag_limit_steps = ", at + 1)) {
    t.replace(at, t.find('\n', at) - at, "lag_limit_steps = 1000000");
  }
  return t;
}

class CtlDaemon : public ::testing::Test {
 protected:
  void start(const char* example_file) {
    daemon_ = std::make_unique<DaemonProcess>(example(example_file));
    ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
  }
  // stepmodctl on this daemon; asserts the exit status.
  CtlRun ctl(const std::string& args, int want = 0) {
    const CtlRun r = stepmodctl("-n " + daemon_->name() + " " + args);
    EXPECT_EQ(r.exit_status, want) << "stepmodctl " << args << "\n" << r.err << r.out;
    return r;
  }
  ImageWords inputs() const {
    ipc::Client c(daemon_->name());
    ImageWords in;
    c.read_inputs(in);
    return in;
  }
  Vcd stop_and_read_trace() {
    EXPECT_EQ(daemon_->terminate(), 0) << daemon_->log();
    return read_vcd(daemon_->trace_path());
  }
  std::unique_ptr<DaemonProcess> daemon_;
};

// ---- 3602 --------------------------------------------------------------------------------------

namespace m2 = words::m3602;

class Ctl3602 : public CtlDaemon {
 protected:
  void SetUp() override {
    start("3602-sim.toml");
    for (const char* axis : {"1", "2"}) {
      ctl(std::string("--axis ") + axis +
          " configure --capture --external --home --cw-limit --ccw-limit --start-speed 1000");
    }
  }
  plc::m3602::Status status(unsigned axis) const {
    return plc::m3602::decode_status(inputs(), axis);
  }
};

TEST_F(Ctl3602, HomeBothAxesAtOnceStatusNamesBoth) {
  // The example's home switches: axis 1 at 5000..5100 (CW of 0), axis 2 at -3000..-2900.
  ctl("--axis 1 home + -s 10000 -a 100 -d 100");
  ctl("--axis 2 home - -s 10000 -a 100 -d 100");
  for (unsigned ax = 0; ax < 2; ++ax) {
    // Up to 30 s: a homing sequence is several moves and 2-s pauses, and under TSan on a loaded
    // machine 10 s once found axis 1 still on its way.
    for (int i = 0; i < 600 && !status(ax).has(m2::status_msw::kAtHome); ++i) {
      std::this_thread::sleep_for(milliseconds(50));
    }
    EXPECT_TRUE(status(ax).has(m2::status_msw::kAtHome)) << "axis " << ax + 1 << "\n"
                                                         << ctl("status").out << daemon_->log();
    EXPECT_EQ(status(ax).position, 0) << "axis " << ax + 1;
  }
  const CtlRun s = ctl("status");
  for (const char* want : {"3602 axis 1 in COMMAND mode", "3602 axis 2 in COMMAND mode",
                           "1  bit  4  At Home", "position = 0"}) {
    EXPECT_NE(s.out.find(want), std::string::npos) << want << "\n" << s.out;
  }
  EXPECT_NE(s.out.find("At Home", s.out.find("axis 2")), std::string::npos) << s.out;
}

TEST_F(Ctl3602, JogHoldResumeExactStepCounts) {
  ctl("--axis 1 jog + -s 5000 -a 100 -d 100 --for 0.3");
  const std::int32_t jogged = status(0).position;
  EXPECT_GT(jogged, 0);
  ctl("--axis 2 jog - -s 5000 -a 100 -d 100 --for 0.3");
  const std::int32_t jogged2 = status(1).position;
  EXPECT_LT(jogged2, 0);
  // 8 s at 10,000 steps/s: the Hold (another stepmodctl process, 0.5 s later) comes before the
  // end even when starting a process takes seconds (TSan on a loaded machine: more than 2.4 s).
  ctl("--axis 1 move rel 80000 -s 10000 -a 100 -d 100");
  std::this_thread::sleep_for(milliseconds(500));
  ctl("--axis 1 hold");
  ctl("--axis 1 wait-idle --max 20", 1);  // held, not Move Complete
  EXPECT_TRUE(status(0).has(m2::status_msw::kHoldState)) << daemon_->log();
  EXPECT_LT(status(0).position, jogged + 80'000);
  ctl("--axis 1 resume -s 20000 -a 200 -d 200 --scurve tri");
  ctl("--axis 1 wait-idle --max 20");
  EXPECT_EQ(status(0).position, jogged + 80'000) << ctl("status").out << daemon_->log();
  EXPECT_TRUE(status(0).has(m2::status_msw::kMoveComplete));
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising("axis1.step").size(), static_cast<std::size_t>(jogged + 80'000));
  EXPECT_EQ(vcd.rising("axis2.step").size(), static_cast<std::size_t>(-jogged2));
}

TEST_F(Ctl3602, MinRegistrationThenRegistrationMoveStopsAfterTheTrigger) {
  const CtlRun set = ctl("--axis 2 min-registration 100");
  EXPECT_TRUE(status(1).has_lsw(m2::status_lsw::kMinRegistrationSet)) << set.out;
  EXPECT_NE(set.out.find("1  bit 10  Min. Registration Distance Set"), std::string::npos)
      << set.out;
  // The jog bit is held 3 s (15,000 steps at full speed); External after 0.5 s triggers the
  // registration: 700 steps more, then the axis stops on its own.
  std::thread trigger([this] {
    std::this_thread::sleep_for(milliseconds(500));
    const CtlRun r = stepmodctl("-n " + daemon_->name() + " panel force 2 external 1");
    EXPECT_EQ(r.exit_status, 0) << r.err;
  });
  ctl("--axis 2 jog - -s 5000 -a 100 -d 100 --for 3 --registration 700");
  trigger.join();
  ctl("panel release 2 all");
  const std::int32_t p = status(1).position;
  EXPECT_LT(p, -700);
  EXPECT_GT(p, -10'000);  // well short of the 3 s jog
  EXPECT_EQ(status(0).position, 0);
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising("axis2.step").size(), static_cast<std::size_t>(-p));
  EXPECT_EQ(vcd.rising("axis1.step").size(), 0u);
}

TEST_F(Ctl3602, BlendProgramAndRunOnAxis2ExactCount) {
  ctl("--axis 2 blend program --segment 6000:5000:100 --segment 4000:10000:200:tri "
      "--final-decel 100 --final-type trap");
  ctl("--axis 2 blend run -");
  ctl("--axis 2 wait-idle --max 20");
  EXPECT_EQ(status(1).position, -10'000);
  EXPECT_EQ(status(0).position, 0);
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising("axis2.step").size(), 10'000u);
}

TEST_F(Ctl3602, GpoPresetMoveStopReset) {
  const CtlRun on = ctl("--axis 1 gpo on");
  EXPECT_TRUE(status(0).has_lsw(m2::status_lsw::kGpo)) << on.out;
  ctl("--axis 1 preset -100");
  EXPECT_EQ(status(0).position, -100);
  // The GPO stays on through later commands of the axis (a level in every command LSW).
  ctl("--axis 1 move abs -s 10000 -a 100 -d 100 -- -50100");
  std::this_thread::sleep_for(milliseconds(300));
  ctl("--axis 1 stop");
  EXPECT_FALSE(status(0).moving());
  // Immediate Stop sets Position Invalid (3602 manual ch. 9, status bits MSW).
  EXPECT_TRUE(status(0).has(m2::status_msw::kPositionInvalid));
  EXPECT_GT(status(0).position, -50'100);
  const std::int32_t stopped_at = status(0).position;
  ctl("--axis 1 reset");
  EXPECT_TRUE(status(0).has_lsw(m2::status_lsw::kGpo));
  ctl("--axis 1 gpo off");
  EXPECT_FALSE(status(0).has_lsw(m2::status_lsw::kGpo));
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising("axis1.step").size(), static_cast<std::size_t>(-100 - stopped_at));
  EXPECT_EQ(vcd.rising("axis1.gpo").size(), 1u);
  EXPECT_EQ(vcd.final_level("axis1.gpo"), 0);
  EXPECT_EQ(vcd.rising("axis2.gpo").size(), 0u);
}

TEST_F(Ctl3602, ACommandTheModuleRefusesExitsOneAndNamesTheBit) {
  // Resume when nothing is held: Command Error (3602-CE list).
  const CtlRun r = ctl("--axis 2 resume", 1);
  EXPECT_NE(r.err.find("Command Error"), std::string::npos) << r.err;
  ctl("--axis 2 reset");
  EXPECT_FALSE(status(1).has(m2::status_msw::kCommandError));
}

// The interpolated moves (path ...): both axes on one path, exact end points and counts; a held
// path resumes to its end; a geometry the module refuses exits 1 naming the bits.
TEST_F(Ctl3602, PathLineFullCircleHeldArcAndARefusedRadius) {
  ctl("path line 3000 -4000 -s 20000 -a 100 -d 100");
  ctl("path wait --max 20");
  EXPECT_EQ(status(0).position, 3'000);
  EXPECT_EQ(status(1).position, -4'000);
  ctl("path centre cw 0 0 1000 0 -s 20000 -a 100 -d 100");  // a full circle, r = 1000
  ctl("path wait --max 20");
  EXPECT_EQ(status(0).position, 3'000);
  EXPECT_EQ(status(1).position, -4'000);
  // A half circle of radius 5000 (15,708 steps at 5,000 steps/s), held on axis 1 and resumed.
  ctl("path via 10000 0 5000 5000 -s 5000 -a 100 -d 100");
  std::this_thread::sleep_for(milliseconds(300));
  ctl("--axis 1 hold");
  ctl("path wait --max 20");
  EXPECT_TRUE(status(0).has(m2::status_msw::kHoldState));
  EXPECT_NE(status(0).position, 13'000);
  ctl("--axis 1 resume -s 20000 -a 100 -d 100");
  ctl("path wait --max 20");
  EXPECT_EQ(status(0).position, 13'000);
  EXPECT_EQ(status(1).position, -4'000);
  // |R| < |E - S| / 2: no such circle (3602-CE-I7), reported on axis 1.
  const CtlRun r = ctl("path radius ccw 1000 0 10 -s 20000 -a 100 -d 100", 1);
  EXPECT_NE(r.err.find("Command Error"), std::string::npos) << r.err;
  // With its item, as every refusal (docs/error-reasons.md).
  EXPECT_NE(r.err.find("3602-CE-I7: circle: radius below half the chord"), std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("3602 axis 1 in COMMAND mode"), std::string::npos) << r.out;
  ctl("--axis 1 reset");
  EXPECT_FALSE(status(0).has(m2::status_msw::kCommandError));
  const Vcd vcd = stop_and_read_trace();
  // Line |dx|, |dy|; a full circle crosses 4 r integers per axis; the half circle from its left
  // end over the top: 2 r in X, r up and r down in Y.
  EXPECT_EQ(vcd.rising("axis1.step").size(), 3'000u + 4'000u + 10'000u);
  EXPECT_EQ(vcd.rising("axis2.step").size(), 4'000u + 4'000u + 10'000u);
}

// ---- 3202 --------------------------------------------------------------------------------------

class Ctl3202 : public CtlDaemon {
 protected:
  void SetUp() override {
    start("3202-sim.toml");
    for (const char* ch : {"1", "2"}) {
      ctl(std::string("--channel ") + ch +
          " configure --home --cw-limit --ccw-limit --encoder --start-speed 1000");
    }
  }
  plc::m3202::Status status(unsigned ch) const { return plc::m3202::decode_status(inputs(), ch); }
};

TEST_F(Ctl3202, BlendFromAFileOnChannel2StatusNamesBothChannels) {
  const std::string file = "/tmp/stepmodctl-blend-" + daemon_->name();
  std::ofstream(file) << "# two segments\nsegment = 6000:5000:100000:tri\n"
                         "segment = 4000:10000:200000\nfinal_decel = 100000\nfinal_type = trap\n";
  ctl("-c 2 blend program --file " + file);
  std::remove(file.c_str());
  ctl("-c 2 blend run -");
  ctl("-c 2 wait-idle --max 20");
  EXPECT_EQ(status(1).position, -10'000) << ctl("status").out << daemon_->log();
  EXPECT_EQ(status(0).position, 0);
  const CtlRun s = ctl("status");
  for (const char* want : {"3202 channel 1 in COMMAND mode", "3202 channel 2 in COMMAND mode",
                           "position = -10000", "encoder  = -10000"}) {
    EXPECT_NE(s.out.find(want), std::string::npos) << want << "\n" << s.out;
  }
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising("axis2.step").size(), 10'000u);
  EXPECT_EQ(vcd.rising("axis1.step").size(), 0u);
}

TEST_F(Ctl3202, BlendFromOptionsOnChannel1) {
  ctl("-c 1 blend program --segment 3000:5000:100000 --segment 2000:8000:100000 "
      "--final-decel 100000");
  ctl("-c 1 blend run +");
  ctl("-c 1 wait-idle --max 20");
  EXPECT_EQ(status(0).position, 5'000) << ctl("status").out << daemon_->log();
}

TEST_F(Ctl3202, EveryChannelCommandOnChannel2LeavesChannel1Alone) {
  ctl("-c 2 jog + -s 5000 -a 100000 -d 100000 --for 0.3");
  const std::int32_t jogged = status(1).position;
  EXPECT_GT(jogged, 0);
  // 4 s at 10,000 steps/s (the example's CW limit is at 50,000): the Hold (another stepmodctl
  // process, 0.5 s later) comes before the end even when starting a process takes seconds (TSan on
  // a loaded machine: more than 2.5 s).
  ctl("-c 2 move rel 40000 -s 10000 -a 100000 -d 100000");
  std::this_thread::sleep_for(milliseconds(500));
  ctl("-c 2 hold");
  ctl("-c 2 wait-idle --max 20", 1);  // held, not Move Complete
  EXPECT_LT(status(1).position, jogged + 40'000) << daemon_->log();
  ctl("-c 2 resume");  // the held move's own speed and rates
  ctl("-c 2 wait-idle --max 20");
  EXPECT_EQ(status(1).position, jogged + 40'000) << ctl("status").out << daemon_->log();
  ctl("-c 2 preset 100");
  EXPECT_EQ(status(1).position, 100);
  ctl("-c 2 preset-encoder 77");
  EXPECT_EQ(status(1).encoder, 77);
  ctl("-c 2 move abs -s 10000 -a 100000 -d 100000 -- -40000");
  std::this_thread::sleep_for(milliseconds(300));
  ctl("-c 2 stop");
  EXPECT_FALSE(status(1).moving());
  ctl("-c 2 reset");
  const std::int32_t before_home = status(1).position;
  ctl("-c 2 home - -s 5000 -a 100000 -d 100000");
  std::this_thread::sleep_for(milliseconds(300));
  EXPECT_LT(status(1).position, before_home);  // searching CCW
  ctl("-c 2 stop");
  EXPECT_EQ(status(0).position, 0);
  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising("axis1.step").size(), 0u);
}

}  // namespace
}  // namespace stepmod::testing
