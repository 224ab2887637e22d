// The doctor's arithmetic and words: the safe rate under the guard, the wake-up histogram, the
// daemon's start-up notice and the advice, from facts of known content.
#include <gtest/gtest.h>

#include "doctor/advice.hpp"
#include "doctor/fitness.hpp"
#include "doctor/startup_notice.hpp"
#include "doctor/wake_probe.hpp"
#include "fake_root.hpp"

namespace stepmod::doctor {
namespace {

TEST(DoctorFitness, SafeRateIsLagLimitOverWorstPause) {
  const std::vector<std::uint32_t> lags{8, 16};
  const Fitness f = judge_fitness(400 * kNsPerUs, 200 * kNsPerMs, lags, 25'000);
  ASSERT_EQ(f.axes.size(), 2u);
  EXPECT_DOUBLE_EQ(f.axes[0].safe_rate, 20'000);  // 8 steps / 400 us
  EXPECT_DOUBLE_EQ(f.axes[1].safe_rate, 40'000);
  EXPECT_TRUE(f.within_late_limit);
  EXPECT_FALSE(f.fit);  // axis 1 holds 20,000 < 25,000
  EXPECT_TRUE(judge_fitness(400 * kNsPerUs, 200 * kNsPerMs, lags, 20'000).fit);
  EXPECT_TRUE(judge_fitness(400 * kNsPerUs, 200 * kNsPerMs, lags, 0).fit);
}

TEST(DoctorFitness, APauseBeyondTheLateLimitIsNeverFit) {
  const std::vector<std::uint32_t> lags{8};
  const Fitness f = judge_fitness(300 * kNsPerMs, 200 * kNsPerMs, lags, 0);
  EXPECT_FALSE(f.within_late_limit);
  EXPECT_FALSE(f.fit);
  EXPECT_EQ(f.axes[0].safe_rate, 0);
}

TEST(DoctorWakeLatencies, PercentilesAndWorst) {
  WakeLatencies l;
  for (int i = 0; i < 99; ++i) l.add(10 * kNsPerUs + 500);
  l.add(5 * kNsPerMs);
  EXPECT_EQ(l.count(), 100u);
  EXPECT_EQ(l.percentile(0.5), 11 * kNsPerUs);
  EXPECT_EQ(l.percentile(0.99), 11 * kNsPerUs);
  EXPECT_EQ(l.percentile(1.0), 5001 * kNsPerUs);
  EXPECT_EQ(l.worst(), 5 * kNsPerMs);
  l.add(60 * kNsPerSec);  // beyond the histogram: the worst itself
  EXPECT_EQ(l.percentile(1.0), 60 * kNsPerSec);
}

BoardFacts quiet_board() {
  BoardFacts f;
  f.pulse_cpu = 3;
  f.preempt.rt = true;
  f.preempt.model = "PREEMPT_RT";
  f.cpus.online = {0, 1, 2, 3};
  f.cpus.isolated = {3};
  f.cpus.nohz_full = {3};
  f.throttle.runtime_us = -1;
  f.throttle.period_us = 1'000'000;
  f.rtprio.root = true;
  return f;
}

TEST(DoctorStartupNotice, SilentOnACpuOfItsOwn) {
  EXPECT_EQ(pulse_cpu_notice(quiet_board()), "");
}

TEST(DoctorStartupNotice, NamesSharingThrottlingAndTheKernel) {
  BoardFacts f = quiet_board();
  f.tenants.user_tasks = 12;
  f.throttle.runtime_us = 950'000;
  f.preempt.rt = false;
  f.preempt.model = "PREEMPT_DYNAMIC";
  const std::string n = pulse_cpu_notice(f);
  EXPECT_NE(n.find("CPU 3 is shared with 12 other threads"), std::string::npos) << n;
  EXPECT_NE(n.find("throttling takes 50 ms"), std::string::npos) << n;
  EXPECT_NE(n.find("not PREEMPT_RT (PREEMPT_DYNAMIC)"), std::string::npos) << n;
  f = quiet_board();
  f.pulse_cpu = -1;
  EXPECT_NE(pulse_cpu_notice(f).find("not pinned"), std::string::npos);
}

TEST(DoctorStartupNotice, ReadsTheBoardUnderARoot) {
  testing::FakeRoot r;
  r.write("/proc/sys/kernel/version", "#1 SMP PREEMPT_RT\n");
  r.write("/sys/devices/system/cpu/online", "0-3\n");
  r.write("/proc/sys/kernel/sched_rt_runtime_us", "-1\n");
  EXPECT_EQ(pulse_cpu_notice(3, SysRoot(r.dir())), "");
  r.write("/proc/sys/kernel/sched_rt_runtime_us", "950000\n");
  r.write("/proc/sys/kernel/sched_rt_period_us", "1000000\n");
  EXPECT_NE(pulse_cpu_notice(3, SysRoot(r.dir())).find("throttling"), std::string::npos);
}

TEST(DoctorAdvice, SaysWhatToChange) {
  BoardFacts f = quiet_board();
  f.pulse_cpu = -1;
  f.preempt.rt = false;
  f.throttle.runtime_us = 950'000;
  f.governor = "ondemand";
  rt::OutputThreadStatus st;
  st.fifo = true;
  const auto advice = advise({f, 80, st, false});
  std::string all;
  for (const auto& a : advice) all += a + "\n";
  EXPECT_NE(all.find("PREEMPT_RT"), std::string::npos) << all;
  EXPECT_NE(all.find("stepmodctl isolate --cpu 3"), std::string::npos) << all;
  EXPECT_NE(all.find("sched_rt_runtime_us = -1"), std::string::npos) << all;
  EXPECT_NE(all.find("performance"), std::string::npos) << all;
  EXPECT_NE(all.find("lag_limit_steps"), std::string::npos) << all;
}

}  // namespace
}  // namespace stepmod::doctor
