// stepmodd under a systemd-like supervisor: readiness and watchdog notifications arrive on
// NOTIFY_SOCKET (sd_notify's datagrams) as systemd would receive them for a Type=notify unit with
// WatchdogSec=: READY=1 once, then WATCHDOG=1 about every half watchdog period.
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/support/daemon_process.hpp"
#include "tests/support/sim_config.hpp"

namespace stepmod::testing {
namespace {

TEST(DaemonWatchdog, NotifiesReadyThenPetsTheWatchdogWhileRunning) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("stepmod-notify-" + std::to_string(::getpid())))
          .string();
  ::unlink(path.c_str());
  const int s = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(s, 0);
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  path.copy(a.sun_path, sizeof a.sun_path - 1);
  ASSERT_EQ(::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  timeval tv{0, 100'000};
  ::setsockopt(s, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);

  // What systemd puts in a service's environment: WatchdogSec=0.4s.
  ::setenv("NOTIFY_SOCKET", path.c_str(), 1);
  ::setenv("WATCHDOG_USEC", "400000", 1);
  DaemonProcess daemon(sim_3601_config("", ""), false);
  ::unsetenv("NOTIFY_SOCKET");
  ::unsetenv("WATCHDOG_USEC");
  ASSERT_TRUE(daemon.wait_ready()) << daemon.log();

  int ready = 0;
  int pets = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(1500);
  while (std::chrono::steady_clock::now() < end) {
    char buf[512];
    const ssize_t n = ::recv(s, buf, sizeof buf - 1, 0);
    if (n <= 0) continue;
    const std::string msg(buf, static_cast<std::size_t>(n));
    if (msg.find("READY=1") != std::string::npos) ++ready;
    if (msg.find("WATCHDOG=1") != std::string::npos) ++pets;
  }
  EXPECT_EQ(daemon.terminate(), 0) << daemon.log();
  ::close(s);
  ::unlink(path.c_str());
  EXPECT_EQ(ready, 1);
  // Every 200 ms for 1.5 s: 7 or 8; a loaded machine may lose a few, but not most.
  EXPECT_GE(pets, 4);
  EXPECT_LE(pets, 9);
}

}  // namespace
}  // namespace stepmod::testing
