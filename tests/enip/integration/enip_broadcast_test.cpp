// Broadcast ListIdentity end to end (docs/ethernetip-design.md, "Encapsulation"): how RSLinx's
// browse and st-ethernet-ip's Browser find the devices on a network. In a network namespace of
// the test process's own (root, as CI runs; skipped elsewhere, a failure in CI), two veth pairs:
// v0/v1 the plant network 10.77.0.0/24 with the board at 10.77.0.1 (v0) and a PC at 10.77.0.2
// (v1); v2/v3 another network, 10.78.0.0/24, on another interface of the board. The daemon
// listens on 10.77.0.1.
#include <gtest/gtest.h>
#include <sched.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>

#include "tests/enip/enip_bytes.hpp"
#include "tests/enip/integration/partner_process.hpp"
#include "tests/enip/integration/raw_socket.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/shell.hpp"
#include "tests/support/sim_config.hpp"

namespace stepmod::testing {
namespace {

using std::chrono::milliseconds;
using Bytes = std::vector<std::uint8_t>;

// Both pairs up; the namespace's addresses may source what its own interfaces receive (the PC
// and the board share the namespace: without accept_local the kernel drops the PC's packets as
// martians at the board's end).
constexpr const char* kNetwork =
    "set -e; ip link set lo up; "
    "ip link add v0 type veth peer name v1; ip link add v2 type veth peer name v3; "
    "ip addr add 10.77.0.1/24 brd 10.77.0.255 dev v0; "
    "ip addr add 10.77.0.2/24 brd 10.77.0.255 dev v1; "
    "ip addr add 10.78.0.1/24 brd 10.78.0.255 dev v2; "
    "ip addr add 10.78.0.2/24 brd 10.78.0.255 dev v3; "
    "for i in v0 v1 v2 v3; do ip link set $i up; done; "
    "for i in all v0 v1 v2 v3; do echo 1 > /proc/sys/net/ipv4/conf/$i/accept_local; "
    "echo 0 > /proc/sys/net/ipv4/conf/$i/rp_filter; done";

// Why the namespace could not be made; empty when it stands.
std::string make_network() {
  if (::geteuid() != 0) return "a network namespace of the test's own needs root (CI runs as root)";
  if (::unshare(CLONE_NEWNET) != 0) return std::string("unshare: ") + std::strerror(errno);
  std::string out;
  if (run_shell(kNetwork, &out) != 0) return "the veth pairs (iproute2): " + out;
  return "";
}

// A ListIdentity whose sender allows 500 ms (the spec's least) before the answer.
const Bytes kListIdentity500 =
    enip::test::hex("6300 0000 00000000 00000000 f401000000000000 00000000");

// Every datagram that comes back to one ListIdentity broadcast from `local` to `to`: the first
// within `first` (generous: a loaded machine may be slow to schedule the adapter), then whatever
// else comes within `more` of it (a second answer would come within the 500 ms the request
// allows).
std::vector<Bytes> broadcast_list_identity(const std::string& local, const std::string& to,
                                           milliseconds first, milliseconds more) {
  std::vector<Bytes> replies;
  const int fd = bound_socket(SOCK_DGRAM, local);
  if (fd < 0) return replies;
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_BROADCAST, &one, sizeof one);
  const sockaddr_in a = ipv4(to, 44818);
  ::sendto(fd, kListIdentity500.data(), kListIdentity500.size(), 0,
           reinterpret_cast<const sockaddr*>(&a), sizeof a);
  auto end = std::chrono::steady_clock::now() + first;
  for (auto now = std::chrono::steady_clock::now(); now < end;
       now = std::chrono::steady_clock::now()) {
    Bytes r = receive(fd, std::chrono::duration_cast<milliseconds>(end - now));
    if (r.empty()) continue;
    if (replies.empty()) end = std::chrono::steady_clock::now() + more;
    replies.push_back(std::move(r));
  }
  ::close(fd);
  return replies;
}

bool names_the_board(const Bytes& reply) {
  return std::string(reply.begin(), reply.end()).find("stepmod 3601") != std::string::npos;
}

class EnipBroadcastDaemon : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { network_ = new std::string(make_network()); }
  static void TearDownTestSuite() { delete network_; }
  void SetUp() override {
    if (!network_->empty()) {
      if (in_ci()) FAIL() << *network_;
      GTEST_SKIP() << *network_;
    }
    const char* sim = "cw_limit_at = 10000000\nccw_limit_at = -10000000\n";
    daemon_ = std::make_unique<DaemonProcess>(
        sim_3601_config("", sim) +
        "\n[ethernetip]\nenabled = true\nlisten = \"10.77.0.1:44818\"\n");
    ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
  }
  void TearDown() override {
    if (daemon_ && daemon_->pid() > 0) {
      EXPECT_EQ(daemon_->terminate(), 0) << daemon_->log();
    }
  }
  static std::string* network_;
  std::unique_ptr<DaemonProcess> daemon_;
};
std::string* EnipBroadcastDaemon::network_ = nullptr;

TEST_F(EnipBroadcastDaemon, StEthernetIpsBrowserFindsTheBoard) {
  REQUIRE_ENIP_PARTNERS();
  PartnerProcess browser({"browse", "10.77.0.2"});
  const auto found = browser.line_with("device", std::chrono::seconds(15));
  ASSERT_TRUE(found.has_value()) << browser.transcript() << daemon_->log();
  EXPECT_EQ(json_field(*found, "productName"), "stepmod 3601") << *found;
  EXPECT_EQ(json_field(*found, "sin_addr"), "10.77.0.1") << *found;
  EXPECT_EQ(json_field(*found, "productCode"), "3601") << *found;
}

TEST_F(EnipBroadcastDaemon, EachBroadcastOnTheListenNetworkIsAnsweredOnce) {
  // 255.255.255.255 and the subnet's own broadcast address. The PC's broadcast also comes back
  // to the namespace on v1, the wrong interface: that copy must not be answered a second time.
  for (const char* to : {"255.255.255.255", "10.77.0.255"}) {
    const std::vector<Bytes> r =
        broadcast_list_identity("10.77.0.2", to, milliseconds(10000), milliseconds(1500));
    ASSERT_EQ(r.size(), 1u) << to << "\n" << daemon_->log();
    EXPECT_TRUE(names_the_board(r[0])) << to;
  }
}

TEST_F(EnipBroadcastDaemon, ABroadcastOnAnotherNetworkOfTheBoardIsNotAnswered) {
  for (const char* to : {"255.255.255.255", "10.78.0.255"}) {
    EXPECT_TRUE(broadcast_list_identity("10.78.0.2", to, milliseconds(2000), {}).empty()) << to;
  }
  // The board still answers on its own network (the silence above is the rule, not a dead
  // adapter).
  const auto own = broadcast_list_identity("10.77.0.2", "255.255.255.255", milliseconds(10000),
                                           milliseconds(1500));
  EXPECT_EQ(own.size(), 1u);
}

}  // namespace
}  // namespace stepmod::testing
