// End to end, issue 20: the error reasons as stepmodctl and the daemon's log show them, the CLI's
// new forms (--version, --check, a typo's suggestion, status --brief/--json, --wait, wait-idle's
// verdict, a stopped daemon), the commissioning lease (stepmodctl killed mid-move, a PLC
// heartbeat during a lease, refused while a PLC is live) and the daemon's signals (a closed log
// pipe, SIGHUP). The real stepmodd and stepmodctl on the simulated 3601 (examples/3601-sim.toml).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>

#include "ipc/client.hpp"
#include "tests/support/ctl_run.hpp"
#include "tests/support/daemon_process.hpp"

namespace stepmod::testing {
namespace {

using std::chrono::milliseconds;
using Clock = std::chrono::steady_clock;

// examples/3601-sim.toml with the harness' name, a late-edge limit for a loaded machine and
// optionally a PLC heartbeat timeout.
std::string config_3601(int plc_timeout_ms = 0) {
  std::string t = slurp_file(std::string(STEPMOD_SOURCE_DIR) + "/examples/3601-sim.toml");
  const auto line = [&t](const std::string& from, const std::string& to) {
    const auto at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at == std::string::npos) return;
    t.replace(at, t.find('\n', at) - at, to);
  };
  line("name = \"stepmod\"", "name = \"{NAME}\"");
  line("[rt]", "[rt]\nlate_limit_us = 1000000");
  line("lag_limit_steps = ", "lag_limit_steps = 1000000");  // not about timing (sim_config.hpp)
  if (plc_timeout_ms > 0) {
    line("scan_us = 1000", "scan_us = 1000\nplc_timeout_ms = " + std::to_string(plc_timeout_ms));
  }
  return t;
}

bool shm_exists(const std::string& name) {
  struct stat st {};
  return ::stat(("/dev/shm/stepmod." + name).c_str(), &st) == 0;
}

bool eventually(const std::function<bool()>& f, milliseconds limit) {
  const auto end = Clock::now() + limit;
  while (Clock::now() < end) {
    if (f()) return true;
    std::this_thread::sleep_for(milliseconds(5));
  }
  return f();
}

constexpr const char* kConfigure = "configure --home --cw-limit --ccw-limit --estop";

class Commissioning : public ::testing::Test {
 protected:
  void start(int plc_timeout_ms = 0) {
    daemon_ = std::make_unique<DaemonProcess>(config_3601(plc_timeout_ms), false);
    ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
  }
  CtlRun ctl(const std::string& args, int want) {
    const CtlRun r = stepmodctl("-n " + daemon_->name() + " " + args);
    EXPECT_EQ(r.exit_status, want) << "stepmodctl " << args << "\n" << r.err << r.out;
    return r;
  }
  // stepmodctl in the background (its pid), output discarded.
  pid_t ctl_background(const std::string& args) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, 1);
      ::dup2(null, 2);
      const std::string cmd =
          std::string("exec ") + STEPMODCTL_PATH + " -n " + daemon_->name() + " " + args;
      ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    return pid;
  }
  ipc::Client client() { return ipc::Client(daemon_->name()); }
  std::int64_t position() { return panel_position(); }
  std::int64_t panel_position() {
    const CtlRun r = stepmodctl("-n " + daemon_->name() + " status --json");
    const auto at = r.out.find("\"position\":");
    return at == std::string::npos ? -1 : std::stoll(r.out.substr(at + 11));
  }
  bool moving() {
    const CtlRun r = stepmodctl("-n " + daemon_->name() + " status --brief");
    return r.out.find(": moving") != std::string::npos;  // the state column
  }
  std::uint32_t health() { return client().read_health().flags; }
  std::unique_ptr<DaemonProcess> daemon_;
};

// ---- error reasons, as people see them ---------------------------------------------------------

TEST_F(Commissioning, ReasonOfARefusedCommandInStepmodctlTheLogAndStatus) {
  start();
  const CtlRun r = ctl("move rel 100 -s 1000 -a 10 -d 10", 1);
  // Every refusal names its item, a move before configuration too (stepmod's 3601-CE-S2).
  EXPECT_NE(r.err.find("Command Error: 3601-CE-S2: not configured: configure the axis first"),
            std::string::npos)
      << r.err;
  ctl(kConfigure, 0);
  const CtlRun vp = ctl("move rel 100 -s 500 -a 10 -d 10", 1);
  EXPECT_NE(vp.err.find("3601-CE-05: Vp 500 is below Vs 1000"), std::string::npos) << vp.err;
  EXPECT_TRUE(eventually(
      [&] {
        return daemon_->log().find("module 3601 axis 1: 3601-CE-05: Vp 500 is below Vs 1000") !=
               std::string::npos;
      },
      milliseconds(2000)))
      << daemon_->log();
  const CtlRun st = ctl("status", 0);
  EXPECT_NE(st.out.find("axis 1 last error reason: 3601-CE-05: Vp 500 is below Vs 1000"),
            std::string::npos)
      << st.out;
  const CtlRun brief = ctl("status --brief", 0);
  EXPECT_EQ(std::count(brief.out.begin(), brief.out.end(), '\n'), 1) << brief.out;
  EXPECT_NE(brief.out.find("axis 1: idle"), std::string::npos) << brief.out;
  EXPECT_NE(brief.out.find("errors: Command Error, Invalid Profile, Position Invalid "
                           "(3601-CE-05: Vp 500 is below Vs 1000)"),
            std::string::npos)
      << brief.out;
  const CtlRun json = ctl("status --json", 0);
  EXPECT_NE(json.out.find("\"reason_item\":10205"), std::string::npos) << json.out;
  EXPECT_NE(json.out.find("\"reason\":\"3601-CE-05: Vp 500 is below Vs 1000\""), std::string::npos)
      << json.out;
}

TEST_F(Commissioning, StaleCommandErrorDoesNotMakeStopHoldResumeFail) {
  start();
  ctl(kConfigure, 0);
  ctl("move rel 100 -s 500 -a 10 -d 10", 1);  // Command Error from here on
  for (const char* c : {"stop", "hold", "resume"}) {
    const CtlRun r = ctl(c, 0);
    EXPECT_NE(r.err.find("was already set before this command (3601-CE-05"), std::string::npos)
        << c << ": " << r.err;
  }
  // Another command the module ignores is still a failure, with the reason.
  const CtlRun m = ctl("move rel 100 -s 5000 -a 10 -d 10", 1);
  EXPECT_NE(m.err.find("ignores every command but Reset Errors"), std::string::npos) << m.err;
  ctl("reset", 0);
  ctl("move rel 100 -s 5000 -a 10 -d 10 --wait", 0);
}

// ---- waiting -----------------------------------------------------------------------------------

TEST_F(Commissioning, WaitEndsInMoveCompleteOrSaysWhyNot) {
  start();
  ctl(kConfigure, 0);
  const CtlRun ok = ctl("move rel 3000 -s 20000 -a 100 -d 100 --wait", 0);
  EXPECT_NE(ok.out.find("move complete at 3000"), std::string::npos) << ok.out;
  ctl("wait-idle", 0);
  // A move cut by the E-stop: wait-idle says so (issue 20: it returned 0 after a fault). Long
  // (30 s): a loaded machine may take seconds to start the stepmodctl that forces the E-stop.
  const pid_t mover = ctl_background("move rel 600000 -s 20000 -a 100 -d 100");
  ASSERT_TRUE(eventually([&] { return moving(); }, milliseconds(5000)));
  ctl("panel force 1 estop 1", 0);
  const CtlRun w = ctl("wait-idle", 1);
  EXPECT_NE(w.err.find("Input Error"), std::string::npos) << w.err << daemon_->log();
  EXPECT_NE(w.err.find("3601-IE-01: E-stop active: stopped at"), std::string::npos) << w.err;
  int status = 0;
  ::waitpid(mover, &status, 0);
  ctl("panel release 1 estop", 0);
  const CtlRun home = ctl("home + -s 20000 -a 100 -d 100 --wait", 0);
  EXPECT_NE(home.out.find("at home"), std::string::npos) << home.out;
}

// ---- the command line --------------------------------------------------------------------------

TEST(CommissioningCli, VersionCheckAndTypos) {
  const CtlRun v = stepmodctl("--version");
  EXPECT_EQ(v.exit_status, 0);
  EXPECT_EQ(v.out.rfind("stepmodctl ", 0), 0u) << v.out;
  std::string err;
  EXPECT_EQ(DaemonProcess::run_to_exit("--version", &err), 0);
  const CtlRun typo = stepmodctl("moov rel 5");
  EXPECT_EQ(typo.exit_status, 2);
  EXPECT_NE(typo.err.find("unknown command 'moov'; did you mean 'move'?"), std::string::npos)
      << typo.err;
  // --check: valid -> 0, a bad key -> 2, and no image is created either way.
  const std::string dir = "/tmp/stepmod-check-" + std::to_string(::getpid());
  ::mkdir(dir.c_str(), 0700);
  std::string cfg = config_3601();
  const std::string name = "check-" + std::to_string(::getpid());
  cfg.replace(cfg.find("{NAME}"), 6, name);
  {
    std::FILE* f = std::fopen((dir + "/ok.toml").c_str(), "w");
    std::fputs(cfg.c_str(), f);
    std::fclose(f);
  }
  EXPECT_EQ(DaemonProcess::run_to_exit("--check --config " + dir + "/ok.toml", &err), 0) << err;
  EXPECT_FALSE(shm_exists(name));
  cfg.replace(cfg.find("scan_us"), 7, "scan_usx");
  {
    std::FILE* f = std::fopen((dir + "/bad.toml").c_str(), "w");
    std::fputs(cfg.c_str(), f);
    std::fclose(f);
  }
  EXPECT_EQ(DaemonProcess::run_to_exit("--check --config " + dir + "/bad.toml", &err), 2);
  EXPECT_NE(err.find("scan_usx"), std::string::npos) << err;
  EXPECT_FALSE(shm_exists(name));
  std::remove((dir + "/ok.toml").c_str());
  std::remove((dir + "/bad.toml").c_str());
  ::rmdir(dir.c_str());
}

TEST_F(Commissioning, StoppedDaemonIsReportedAsUnreachable) {
  start();
  daemon_->signal(SIGSTOP);
  const CtlRun r = ctl("status", 3);
  EXPECT_NE(r.err.find("is not scanning"), std::string::npos) << r.err;
  ctl("status --brief", 3);
  daemon_->signal(SIGCONT);
  ctl("status --brief", 0);
}

// ---- the commissioning lease -------------------------------------------------------------------

TEST_F(Commissioning, KilledStepmodctlStopsTheAxisAndSetsBit6) {
  start(300);
  ctl(kConfigure, 0);
  const pid_t tool = ctl_background("move rel 90000 -s 5000 -a 100 -d 100 --wait");
  ASSERT_TRUE(eventually([&] { return client().raw().lease_holder != 0 && moving(); },
                         milliseconds(10'000)))
      << daemon_->log();
  // Held longer than plc_timeout_ms: the lease, not the heartbeat, keeps it going.
  std::this_thread::sleep_for(milliseconds(600));
  ASSERT_TRUE(moving()) << daemon_->log();
  ::kill(tool, SIGKILL);
  int status = 0;
  ::waitpid(tool, &status, 0);
  const auto killed = Clock::now();
  // The lease expires at most 500 ms after its last renewal; a loaded machine gets a margin.
  ASSERT_TRUE(eventually([&] { return !moving(); }, milliseconds(3000))) << daemon_->log();
  const auto took = std::chrono::duration_cast<milliseconds>(Clock::now() - killed).count();
  EXPECT_LT(took, 1500) << "the axis stopped " << took << " ms after the kill";
  EXPECT_TRUE(health() & STEPMOD_HEALTH_LEASE_EXPIRED);
  EXPECT_EQ(client().raw().lease_holder, 0u);
  const CtlRun brief = ctl("status --brief", 0);
  EXPECT_NE(brief.out.find("3601-PI-S2"), std::string::npos) << brief.out;
  EXPECT_NE(daemon_->log().find("expired without release"), std::string::npos) << daemon_->log();
}

TEST_F(Commissioning, PlcHeartbeatDuringALeaseSetsBit7) {
  start();
  ctl(kConfigure, 0);
  const pid_t tool = ctl_background("move rel 30000 -s 10000 -a 100 -d 100 --wait");
  // The daemon has seen the take (a heartbeat before that scan belongs to the time before it).
  ASSERT_TRUE(eventually(
      [&] { return daemon_->log().find("commissioning lease taken") != std::string::npos; },
      milliseconds(10'000)))
      << daemon_->log();
  ipc::Client plc(daemon_->name());
  plc.heartbeat();
  EXPECT_TRUE(eventually([&] { return (health() & STEPMOD_HEALTH_LEASE_CONFLICT) != 0; },
                         milliseconds(2000)));
  int status = 0;
  ::waitpid(tool, &status, 0);
  EXPECT_NE(daemon_->log().find("two writers"), std::string::npos) << daemon_->log();
}

TEST_F(Commissioning, NoLeaseWhileAPlcHeartbeatIsLive) {
  start(300);
  ctl(kConfigure, 0);
  std::atomic<bool> stop{false};
  std::thread plc([&] {
    ipc::Client c(daemon_->name());
    while (!stop) {
      c.heartbeat();
      std::this_thread::sleep_for(milliseconds(10));
    }
  });
  // Live as the daemon sees it (health bit 1 cleared), not only as this thread writes it.
  ASSERT_TRUE(
      eventually([&] { return (health() & STEPMOD_HEALTH_PLC_STALE) == 0; }, milliseconds(3000)));
  const CtlRun r = ctl("move rel 2000 -s 10000 -a 100 -d 100 --wait", 0);
  stop = true;
  plc.join();
  EXPECT_NE(r.err.find("a PLC heartbeat is live"), std::string::npos) << r.err;
  EXPECT_EQ(client().raw().lease_holder, 0u);
}

TEST_F(Commissioning, MoveWithoutWaitAndNoPlcSaysTheTimeoutWillStopIt) {
  start(300);
  ctl(kConfigure, 0);
  ASSERT_TRUE(
      eventually([&] { return (health() & STEPMOD_HEALTH_PLC_STALE) != 0; }, milliseconds(3000)));
  const CtlRun r = ctl("move rel 100000 -s 5000 -a 100 -d 100", 0);
  EXPECT_NE(r.err.find("plc_timeout_ms"), std::string::npos) << r.err;
  ASSERT_TRUE(eventually([&] { return !moving(); }, milliseconds(3000)));
  EXPECT_LT(position(), 100000);
}

// ---- signals -----------------------------------------------------------------------------------

// `stepmodd ... 2>&1 | head -1`: the reader goes away, the daemon logs on (a refused command
// makes it warn) and still stops cleanly on SIGTERM, removing its objects.
TEST(CommissioningSignals, ClosedLogPipeThenSigtermExitsZeroAndCleansUp) {
  const std::string dir = "/tmp/stepmod-pipe-" + std::to_string(::getpid());
  ::mkdir(dir.c_str(), 0700);
  const std::string name = "pipe-" + std::to_string(::getpid());
  std::string cfg = config_3601();
  cfg.replace(cfg.find("{NAME}"), 6, name);
  {
    std::FILE* f = std::fopen((dir + "/c.toml").c_str(), "w");
    std::fputs(cfg.c_str(), f);
    std::fclose(f);
  }
  for (const int sig : {SIGTERM, SIGHUP}) {
    int p[2];
    ASSERT_EQ(::pipe(p), 0);
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::dup2(p[1], 1);
      ::dup2(p[1], 2);
      ::close(p[0]);
      ::close(p[1]);
      const std::string path = DaemonProcess::daemon_path();
      const std::string conf = dir + "/c.toml";
      ::execl(path.c_str(), path.c_str(), "--config", conf.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(p[1]);
    char c = 0;
    ASSERT_EQ(::read(p[0], &c, 1), 1);  // the first log line is coming: the reader quits
    ::close(p[0]);
    ASSERT_TRUE(eventually([&] { return shm_exists(name); }, milliseconds(10'000)));
    // Log lines into the closed pipe: EPIPE (SIGPIPE would have ended it).
    stepmodctl("-n " + name + " move rel 100 -s 1000 -a 10 -d 10");
    stepmodctl("-n " + name + " move rel 100 -s 1000 -a 10 -d 10");
    std::this_thread::sleep_for(milliseconds(200));
    ASSERT_EQ(::waitpid(pid, nullptr, WNOHANG), 0) << "stepmodd died on the closed pipe";
    ::kill(pid, sig);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFEXITED(status)) << "signal " << sig << ": killed by " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 0) << "signal " << sig;
    EXPECT_FALSE(shm_exists(name)) << "signal " << sig;
    EXPECT_FALSE(shm_exists(name + ".sim")) << "signal " << sig;
  }
  std::remove((dir + "/c.toml").c_str());
  ::rmdir(dir.c_str());
}

}  // namespace
}  // namespace stepmod::testing
