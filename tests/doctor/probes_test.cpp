// The doctor's probes on files of known content (a fake root): each file format parsed.
#include <gtest/gtest.h>

#include "doctor/cpu_isolation_probe.hpp"
#include "doctor/cpu_list.hpp"
#include "doctor/governor_probe.hpp"
#include "doctor/preempt_probe.hpp"
#include "doctor/rt_throttle_probe.hpp"
#include "doctor/rtprio_probe.hpp"
#include "doctor/tenants_probe.hpp"
#include "fake_root.hpp"

namespace stepmod::doctor {
namespace {

using testing::FakeRoot;

TEST(DoctorCpuList, ParsesRangesAndSingles) {
  EXPECT_EQ(parse_cpu_list("0-2,5\n"), (std::vector<int>{0, 1, 2, 5}));
  EXPECT_EQ(parse_cpu_list("3"), (std::vector<int>{3}));
  EXPECT_EQ(parse_cpu_list("\n"), std::vector<int>{});
  EXPECT_EQ(parse_cpu_list("(null)\n"), std::vector<int>{});
  EXPECT_FALSE(parse_cpu_list("2-1"));
  EXPECT_FALSE(parse_cpu_list("a"));
  EXPECT_FALSE(parse_cpu_list("1,,2"));
}

TEST(DoctorCpuList, FormatsTheShortestList) {
  EXPECT_EQ(format_cpu_list({0, 1, 2, 5}), "0-2,5");
  EXPECT_EQ(format_cpu_list({1}), "1");
  EXPECT_EQ(format_cpu_list({}), "");
}

TEST(DoctorPreempt, NamesTheModelOfTheVersionString) {
  EXPECT_EQ(model_of_version("#1 SMP PREEMPT_RT Debian 6.1.0-rt"), "PREEMPT_RT");
  EXPECT_EQ(model_of_version("#1 SMP PREEMPT_DYNAMIC @0"), "PREEMPT_DYNAMIC");
  EXPECT_EQ(model_of_version("#1 SMP PREEMPT Mon"), "PREEMPT");
  EXPECT_EQ(model_of_version("#1 SMP Debian"), "voluntary or none");
  EXPECT_EQ(chosen_preempt_mode("none voluntary (full) lazy\n"), "full");
  EXPECT_EQ(chosen_preempt_mode("none"), "");
}

TEST(DoctorPreempt, RealtimeFileMakesItRt) {
  FakeRoot r;
  r.write("/proc/sys/kernel/version", "#1 SMP PREEMPT_DYNAMIC\n");
  r.write("/sys/kernel/debug/sched/preempt", "none voluntary (full)\n");
  PreemptModel m = probe_preempt(SysRoot(r.dir()));
  EXPECT_FALSE(m.rt);
  EXPECT_EQ(m.model, "PREEMPT_DYNAMIC");
  EXPECT_EQ(m.dynamic_mode, "full");
  r.write("/sys/kernel/realtime", "1\n");
  m = probe_preempt(SysRoot(r.dir()));
  EXPECT_TRUE(m.rt);
  EXPECT_EQ(m.model, "PREEMPT_RT");
}

TEST(DoctorIsolation, ReadsOnlineIsolatedNohzFull) {
  FakeRoot r;
  r.write("/sys/devices/system/cpu/online", "0-3\n");
  r.write("/sys/devices/system/cpu/isolated", "3\n");
  const CpuIsolation c = probe_cpu_isolation(SysRoot(r.dir()));
  EXPECT_EQ(c.online, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(c.isolated, (std::vector<int>{3}));
  EXPECT_TRUE(c.nohz_full.empty());  // absent file: none
}

TEST(DoctorThrottle, ReadsRuntimeAndPeriod) {
  FakeRoot r;
  r.write("/proc/sys/kernel/sched_rt_runtime_us", "950000\n");
  r.write("/proc/sys/kernel/sched_rt_period_us", "1000000\n");
  RtThrottle t = probe_rt_throttle(SysRoot(r.dir()));
  EXPECT_FALSE(t.off());
  EXPECT_EQ(t.withheld_us_per_s(), 50'000);
  r.write("/proc/sys/kernel/sched_rt_runtime_us", "-1\n");
  t = probe_rt_throttle(SysRoot(r.dir()));
  EXPECT_TRUE(t.off());
  EXPECT_EQ(t.withheld_us_per_s(), 0);
  EXPECT_FALSE(parse_integer("x"));
}

TEST(DoctorGovernor, ReadsThePulseCpusGovernor) {
  FakeRoot r;
  r.write("/sys/devices/system/cpu/cpu3/cpufreq/scaling_governor", "ondemand\n");
  EXPECT_EQ(probe_governor(SysRoot(r.dir()), 3), "ondemand");
  EXPECT_EQ(probe_governor(SysRoot(r.dir()), 2), "");
}

TEST(DoctorTenants, ParsesAStatLineWhoseNameHasBlanksAndParentheses) {
  // Fields after the name: 3 state ... 9 flags ... 39 processor.
  std::string rest = " S";
  for (int f = 4; f <= 52; ++f) {
    rest += ' ';
    rest += std::to_string(f == 9 ? 0x00200000 : f == 39 ? 2 : f);
  }
  const auto t = parse_task_stat("42 (a (b) c)" + rest);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->comm, "a (b) c");
  EXPECT_TRUE(t->kernel_thread());
  EXPECT_EQ(t->processor, 2);
  EXPECT_FALSE(parse_task_stat("garbage"));
}

std::string stat_line(const std::string& comm, int processor, bool kernel) {
  std::string s = "1 (" + comm + ") R";
  for (int f = 4; f <= 52; ++f) {
    s += ' ';
    s += std::to_string(f == 9 ? (kernel ? 0x00200000 : 0x400000) : f == 39 ? processor : 0);
  }
  return s + "\n";
}

void add_task(FakeRoot& r, int pid, int tid, const std::string& comm, const std::string& allowed,
              int processor, bool kernel = false) {
  const std::string dir = "/proc/" + std::to_string(pid) + "/task/" + std::to_string(tid);
  r.write(dir + "/stat", stat_line(comm, processor, kernel));
  r.write(dir + "/status", "Name:\t" + comm + "\nCpus_allowed_list:\t" + allowed + "\n");
}

TEST(DoctorTenants, CountsTheThreadsAllowedOnTheCpu) {
  FakeRoot r;
  add_task(r, 10, 10, "cc1plus", "0-3", 3);
  add_task(r, 10, 11, "cc1plus", "0-3", 1);
  add_task(r, 20, 20, "sshd", "0-2", 0);
  add_task(r, 30, 30, "ksoftirqd/3", "3", 3, true);
  add_task(r, 40, 40, "doctor", "0-3", 3);  // the caller: left out
  EXPECT_EQ(status_field("Name:\tx\nCpus_allowed_list:\t0-3\n", "Cpus_allowed_list"), "0-3");
  const CpuTenants t = probe_tenants(SysRoot(r.dir()), 3, 40);
  EXPECT_EQ(t.user_tasks, 2u);
  EXPECT_EQ(t.kernel_tasks, 1u);
  EXPECT_EQ(t.ran_there, 1u);
  EXPECT_EQ(t.names, std::vector<std::string>{"cc1plus"});
  EXPECT_EQ(probe_tenants(SysRoot(r.dir()), 2, 40).user_tasks, 3u);  // sshd, cc1plus x2
}

TEST(DoctorRtprio, ParsesLimitsPasswdAndUnit) {
  const std::string limits =
      "Limit                     Soft Limit           Hard Limit           Units     \n"
      "Max nice priority         0                    0                    \n"
      "Max realtime priority     95                   99                   \n";
  EXPECT_EQ(parse_limits_rtprio(limits), 95);
  EXPECT_FALSE(parse_limits_rtprio("Max nice priority 0 0\n"));
  EXPECT_EQ(uid_in_passwd("root:x:0:0::/root:/bin/sh\nstepmod:x:998:998::/:/usr/sbin/nologin\n",
                          "stepmod"),
            998);
  EXPECT_FALSE(uid_in_passwd("stepmodx:x:5:5::/:/bin/sh\n", "stepmod"));
  EXPECT_EQ(unit_setting("[Service]\nLimitRTPRIO=50\nLimitRTPRIO=99\n", "LimitRTPRIO"), "99");
}

TEST(DoctorRtprio, TheServiceUsersUnitWhenNoDaemonRuns) {
  FakeRoot r;
  r.write("/etc/passwd", "stepmod:x:998:998::/:/usr/sbin/nologin\n");
  r.write("/lib/systemd/system/stepmodd@.service", "[Service]\nUser=stepmod\nLimitRTPRIO=99\n");
  RtprioLimit l = probe_rtprio(SysRoot(r.dir()), 1, 1000);
  EXPECT_EQ(l.user, "stepmod");
  EXPECT_EQ(l.soft, 99);
  EXPECT_EQ(l.source, "/lib/systemd/system/stepmodd@.service");
  // A running stepmodd of that user: its own limit.
  r.write("/proc/812/status", "Name:\tstepmodd\nUid:\t998\t998\t998\t998\n");
  r.write("/proc/812/limits", "Max realtime priority     7     7\n");
  l = probe_rtprio(SysRoot(r.dir()), 1, 1000);
  EXPECT_EQ(l.soft, 7);
  EXPECT_EQ(l.source, "stepmodd pid 812");
}

TEST(DoctorRtprio, TheCallerWithoutAServiceUser) {
  FakeRoot r;
  r.write("/etc/passwd", "root:x:0:0::/root:/bin/sh\n");
  r.write("/proc/77/limits", "Max realtime priority     0     0\n");
  const RtprioLimit l = probe_rtprio(SysRoot(r.dir()), 77, 0);
  EXPECT_EQ(l.soft, 0);
  EXPECT_TRUE(l.root);
  EXPECT_NE(l.user.find("uid 0"), std::string::npos);
}

}  // namespace
}  // namespace stepmod::doctor
