// stepmodctl isolate's files in a fresh root: written, idempotent, removed, nothing left.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "doctor/isolate.hpp"
#include "fake_root.hpp"

namespace stepmod::doctor {
namespace {

using testing::FakeRoot;

constexpr const char* kConfig =
    "[module]\ntype = \"3601\"\nname = \"iso\"\n[gpio]\nbackend = \"sim\"\n[rt]\npriority = 80\n"
    "[[axis]]\nstep = 1\ndir = 2\n";

int isolate(const FakeRoot& r, int cpu, bool off, std::string* out = nullptr,
            std::string* err = nullptr, const std::string& config = "") {
  std::ostringstream o, e;
  const int rc = run_isolate({cpu, off, config, r.dir()}, o, e);
  if (out != nullptr) *out = o.str();
  if (err != nullptr) *err = e.str();
  return rc;
}

std::vector<std::string> files_under(const std::string& dir) {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) files.push_back(e.path().string().substr(dir.size()));
  }
  return files;
}

TEST(DoctorIsolate, WritesTheDropInsAndSysctlThenRemovesThem) {
  FakeRoot r;
  r.write("/sys/devices/system/cpu/online", "0-3\n");
  r.write("/etc/stepmod/iso.toml", kConfig);
  std::string out;
  ASSERT_EQ(isolate(r, 3, false, &out, nullptr, r.path("/etc/stepmod/iso.toml")), 0) << out;
  EXPECT_NE(r.read("/etc/systemd/system/system.slice.d/50-stepmod-cpu.conf")
                .find("[Slice]\nAllowedCPUs=0-2\n"),
            std::string::npos);
  EXPECT_NE(r.read("/etc/systemd/system/user.slice.d/50-stepmod-cpu.conf").find("AllowedCPUs=0-2"),
            std::string::npos);
  EXPECT_NE(r.read("/etc/systemd/system/init.scope.d/50-stepmod-cpu.conf")
                .find("[Scope]\nAllowedCPUs=0-2\n"),
            std::string::npos);
  EXPECT_NE(r.read("/etc/systemd/system/stepmod.slice").find("AllowedCPUs=0-3"), std::string::npos);
  const std::string svc = r.read("/etc/systemd/system/stepmodd@.service.d/50-cpu.conf");
  EXPECT_NE(svc.find("Slice=stepmod.slice\nCPUAffinity=0-2\n"), std::string::npos) << svc;
  EXPECT_NE(r.read("/etc/sysctl.d/50-stepmod.conf").find("kernel.sched_rt_runtime_us = -1"),
            std::string::npos);
  EXPECT_NE(r.read("/etc/stepmod/iso.toml").find("cpu = 3"), std::string::npos);

  // Again: nothing changes.
  ASSERT_EQ(isolate(r, 3, false, &out, nullptr, r.path("/etc/stepmod/iso.toml")), 0);
  EXPECT_EQ(out.find("wrote"), std::string::npos) << out;
  EXPECT_EQ(files_under(r.dir()).size(), 8u);  // 6 files, online, the config

  ASSERT_EQ(isolate(r, -1, true, &out, nullptr, r.path("/etc/stepmod/iso.toml")), 0) << out;
  EXPECT_EQ(r.read("/etc/stepmod/iso.toml"), kConfig);  // as it was
  EXPECT_EQ(files_under(r.dir()),
            (std::vector<std::string>{"/etc/stepmod/iso.toml", "/sys/devices/system/cpu/online"}))
      << out;
  EXPECT_FALSE(r.exists("/etc/systemd/system/system.slice.d"));
  // Off again: nothing to do, no error.
  EXPECT_EQ(isolate(r, -1, true), 0);
}

TEST(DoctorIsolate, RefusesACpuThatDoesNotExistOrAOneCpuBoard) {
  FakeRoot r;
  r.write("/sys/devices/system/cpu/online", "0-3\n");
  std::string err;
  EXPECT_EQ(isolate(r, 4, false, nullptr, &err), 2);
  EXPECT_NE(err.find("no CPU 4"), std::string::npos) << err;
  r.write("/sys/devices/system/cpu/online", "0\n");
  EXPECT_EQ(isolate(r, 0, false, nullptr, &err), 2);
  EXPECT_NE(err.find("one CPU"), std::string::npos) << err;
  EXPECT_EQ(files_under(r.dir()).size(), 1u);  // nothing written
  EXPECT_EQ(isolate(r, -1, false, nullptr, &err), 2);  // neither --cpu nor --off
}

TEST(DoctorIsolate, LeavesFilesItDidNotWrite) {
  FakeRoot r;
  r.write("/etc/sysctl.d/50-stepmod.conf", "kernel.sched_rt_runtime_us = -1\n");
  std::string err;
  EXPECT_EQ(isolate(r, -1, true, nullptr, &err), 0);
  EXPECT_TRUE(r.exists("/etc/sysctl.d/50-stepmod.conf"));
  EXPECT_NE(err.find("not written by stepmodctl isolate"), std::string::npos) << err;
}

TEST(DoctorIsolate, PinsAndUnpinsTheConfigKeepingTheUsersValue) {
  const std::string with_cpu = "[rt]\npriority = 80\ncpu = 1\n[[axis]]\nstep = 1\n";
  const std::string pinned = pin_in_config(with_cpu, 3);
  EXPECT_NE(pinned.find("# cpu = 1"), std::string::npos) << pinned;
  EXPECT_NE(pinned.find("\ncpu = 3"), std::string::npos) << pinned;
  EXPECT_EQ(pin_in_config(pinned, 3), pinned);  // idempotent
  EXPECT_EQ(pin_in_config(pinned, -1), with_cpu);
  const std::string no_rt = "[module]\ntype = \"3601\"\n";
  const std::string added = pin_in_config(no_rt, 2);
  EXPECT_NE(added.find("[rt]"), std::string::npos) << added;
  EXPECT_EQ(pin_in_config(added, -1), no_rt);
}

}  // namespace
}  // namespace stepmod::doctor
