// The adapter on the wire (docs/ethernetip-design.md, "Tests"): the Identity object read by the
// npm client `ethernet-ip`; ListIdentity on UDP and TCP parsed by st-ethernet-ip's Browser; the
// allow list; a whole session captured on the loopback and decoded by Debian's tshark with no
// malformed packet and no expert error; and a fuzz run of mutated frames on TCP and UDP against
// the running daemon: no crash, ListIdentity still answered, nothing written to the image.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <signal.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "fieldbus/enip/identity.hpp"
#include "tests/enip/integration/enip_daemon.hpp"
#include "tests/enip/integration/raw_socket.hpp"
#include "tests/enip/mutation_corpus.hpp"
#include "tests/support/shell.hpp"

namespace stepmod::testing {
namespace {

using std::chrono::milliseconds;
using Bytes = std::vector<std::uint8_t>;

constexpr const char* kSim = "cw_limit_at = 10000000\nccw_limit_at = -10000000\n";
const Bytes kListIdentity =
    enip::test::hex("6300 0000 00000000 00000000 0000000000000000 00000000");

std::string machine_id() {
  std::string id;
  std::ifstream("/etc/machine-id") >> id;
  return id;
}

class EnipDaemonWire : public EnipDaemon {
 protected:
  void start_3601(const std::string& extra = "") { start(sim_3601_config("", kSim), extra); }
  // ListIdentity from `local` by UDP: the reply's product name, empty when none came.
  std::string list_identity_name(const std::string& local) {
    const Bytes r = udp_exchange(local, target_, 44818, kListIdentity, milliseconds(1000));
    const std::string name = "stepmod 3601";
    return std::string(r.begin(), r.end()).find(name) != std::string::npos ? name : "";
  }
};

TEST_F(EnipDaemonWire, TheIdentityObjectReadByEthernetIp) {
  REQUIRE_ENIP_PARTNERS();
  start_3601();
  PartnerProcess p({"identity", target_});
  const auto r = p.line_with("all", std::chrono::seconds(20));
  ASSERT_TRUE(r.has_value()) << p.transcript() << daemon_->log();
  char serial[9];
  std::snprintf(serial, sizeof serial, "%08x",
                __builtin_bswap32(enip::identity_serial(machine_id(), daemon_->name())));
  // Get_Attributes_All: vendor 0xFFFF, device type 0x2B, product code 3601, revision 1.1,
  // status (no I/O connection), serial, "stepmod 3601".
  EXPECT_EQ(json_field(*r, "all"),
            std::string("ffff2b00110e01013000") + serial + "0c737465706d6f642033363031");
  EXPECT_EQ(json_field(*r, "name"), "stepmod 3601");
  EXPECT_EQ(json_field(*r, "version"), "1.1");
  // Get_Attribute_Single, each attribute.
  for (const auto& [attr, want] : std::vector<std::pair<std::string, std::string>>{
           {"1", "ffff"}, {"2", "2b00"}, {"3", "110e"}, {"4", "0101"}, {"6", serial}}) {
    EXPECT_EQ(json_field(*r, attr), want) << "attribute " << attr << ": " << *r;
  }
}

// The TCP/IP Interface and Ethernet Link objects describe the interface the request came in on:
// here the loopback with the daemon's 127.0.x.1.
TEST_F(EnipDaemonWire, TheInterfaceObjectsReadByEthernetIp) {
  REQUIRE_ENIP_PARTNERS();
  start_3601();
  PartnerProcess p({"interface", target_});
  const auto r = p.line_with("tcpip", std::chrono::seconds(20));
  ASSERT_TRUE(r.has_value()) << p.transcript() << daemon_->log();
  in_addr a{};
  ASSERT_EQ(::inet_pton(AF_INET, target_.c_str(), &a), 1);
  char ip_le[9];  // the address as the UDINT's little-endian bytes
  std::snprintf(ip_le, sizeof ip_le, "%08x", __builtin_bswap32(ntohl(a.s_addr)));
  // Attribute 5: the daemon's address, mask 255.0.0.0; the loopback has no gateway.
  EXPECT_NE(r->find(std::string("\"5\":\"") + ip_le + "000000ff00000000"), std::string::npos) << *r;
  EXPECT_NE(r->find("\"1\":\"01000000\""), std::string::npos) << *r;      // configured
  EXPECT_NE(r->find("\"4\":\"020020f62401\""), std::string::npos) << *r;  // → 0xF6 instance 1
  EXPECT_NE(r->find("\"7\":\"status 20\""), std::string::npos) << *r;     // GAA only (0x14)
  EXPECT_NE(r->find("\"10\":\"026c6f\""), std::string::npos) << *r;       // label "lo"
  EXPECT_NE(r->find("\"3\":\"000000000000\""), std::string::npos) << *r;  // its MAC
  EXPECT_NE(r->find("\"12\":\"status 20\""), std::string::npos) << *r;
  EXPECT_NE(r->find("\"revision\":\"0400\"}"), std::string::npos) << *r;  // class attribute 1
}

TEST_F(EnipDaemonWire, ListIdentityIsAnsweredOnUdpAndTcp) {
  REQUIRE_ENIP_PARTNERS();
  start_3601();
  for (const char* how : {"udp", "tcp"}) {
    PartnerProcess p({"list-identity", target_, scanner_ip_, how});
    const auto r = p.line_with("device", std::chrono::seconds(10));
    ASSERT_TRUE(r.has_value()) << how << ": " << p.transcript();
    EXPECT_EQ(json_field(*r, "via"), how);
    EXPECT_EQ(json_field(*r, "vendorID"), "65535") << *r;
    EXPECT_EQ(json_field(*r, "deviceType"), "43") << *r;
    EXPECT_EQ(json_field(*r, "productCode"), "3601") << *r;
    EXPECT_EQ(json_field(*r, "productName"), "stepmod 3601") << *r;
    EXPECT_EQ(json_field(*r, "sin_addr"), target_) << *r;
    EXPECT_EQ(json_field(*r, "sin_port"), "44818") << *r;
    EXPECT_EQ(json_field(*r, "state"), "3") << *r;
  }
}

TEST_F(EnipDaemonWire, AnOriginatorOutsideTheAllowListIsNotServed) {
  start_3601("allow = [\"{SCANNER}\"]\n");
  EXPECT_EQ(list_identity_name(scanner_ip_), "stepmod 3601");
  EXPECT_EQ(list_identity_name(other_ip_), "") << "a datagram from outside the list is answered";
  const int in = tcp_connect(scanner_ip_, target_, 44818);
  ASSERT_GE(in, 0);
  ASSERT_EQ(::send(in, kListIdentity.data(), kListIdentity.size(), MSG_NOSIGNAL),
            static_cast<ssize_t>(kListIdentity.size()));
  EXPECT_FALSE(receive(in, milliseconds(1000)).empty());
  ::close(in);
  // From elsewhere the connection is accepted by the kernel and closed at once, unanswered.
  const int out = tcp_connect(other_ip_, target_, 44818);
  ASSERT_GE(out, 0);
  ::send(out, kListIdentity.data(), kListIdentity.size(), MSG_NOSIGNAL);
  EXPECT_TRUE(receive(out, milliseconds(1000)).empty());
  ::close(out);
  EXPECT_NE(daemon_->log().find("dropped (not in [ethernetip] allow)"), std::string::npos)
      << daemon_->log();
}

// dumpcap on the loopback (root or CAP_NET_RAW), capturing the daemon's address until stop().
class Capture {
 public:
  Capture(const std::string& host, const std::string& file) : file_(file) {
    pid_ = ::fork();
    if (pid_ == 0) {
      const std::string filter = "host " + host;
      ::execlp("dumpcap", "dumpcap", "-q", "-i", "lo", "-f", filter.c_str(), "-w", file.c_str(),
               static_cast<char*>(nullptr));
      ::_exit(127);
    }
  }
  // Whether it is capturing (its file has its header) within 5 s.
  bool started() const {
    for (int i = 0; i < 500; ++i) {
      std::error_code ec;
      if (std::filesystem::file_size(file_, ec) > 0 && !ec) return true;
      if (::waitpid(pid_, nullptr, WNOHANG) != 0) return false;
      std::this_thread::sleep_for(milliseconds(10));
    }
    return false;
  }
  void stop() {
    if (pid_ <= 0) return;
    std::this_thread::sleep_for(milliseconds(200));  // the last packets reach the file
    ::kill(pid_, SIGINT);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
  ~Capture() { stop(); }

 private:
  std::string file_;
  pid_t pid_ = -1;
};

// How many packets of the capture `filter` matches; -1 when tshark refused (the filter, the
// file).
int tshark_count(const std::string& cap, const std::string& filter) {
  std::string out;
  const int rc = run_shell(
      "sh -c \"tshark -r " + cap + " -Y '" + filter + "' 2>/dev/null | wc -l; exit \\$?\"", &out);
  return rc == 0 ? std::stoi(out) : -1;
}

TEST_F(EnipDaemonWire, ACapturedSessionDecodesWithoutMalformedPacketsOrExpertErrors) {
  REQUIRE_ENIP_PARTNERS();
  std::string out;
  ASSERT_EQ(run_shell("tshark -v", &out), 0)
      << "tshark (scripts/install-deps installs it): " << out;
  start_3601();
  const std::string cap = daemon_->trace_path() + ".pcapng";
  Capture capture(target_, cap);
  if (!capture.started()) {
    // As a missing partner: skipped on a developer's machine, a failure in CI (CI=true).
    const char* why = "dumpcap cannot capture on lo (root or CAP_NET_RAW needed)";
    if (in_ci()) FAIL() << why;
    GTEST_SKIP() << why;
  }
  {  // a whole session: ListIdentity, the Identity object, an owner's I/O, a refused owner
    PartnerProcess list({"list-identity", target_, scanner_ip_, "udp"});
    ASSERT_TRUE(list.line_with("device", std::chrono::seconds(10)));
    PartnerProcess id({"identity", target_});
    ASSERT_TRUE(id.line_with("all", std::chrono::seconds(20))) << id.transcript();
    PartnerProcess objects({"interface", target_});
    ASSERT_TRUE(objects.line_with("tcpip", std::chrono::seconds(20))) << objects.transcript();
    auto owner = connect_scanner(10);
    ASSERT_TRUE(owner);
    owner->ask("set 0000000000000000000000000000ffff");
    std::this_thread::sleep_for(milliseconds(200));
    PartnerProcess second({"open-once", scanner_config(other_ip_, 10, 16)});
    ASSERT_TRUE(second.line_with("opened", std::chrono::seconds(10)));
  }
  capture.stop();
  // Decoded as EtherNet/IP and CIP: the encapsulation, the Forward_Open and the class 1 I/O
  // (which tshark links to its connection by the Forward_Open).
  EXPECT_GT(tshark_count(cap, "enip"), 100);
  EXPECT_GE(tshark_count(cap, "cip.cm.fwo.consize"), 1);
  EXPECT_GT(tshark_count(cap, "cipio"), 10);
  // The TCP/IP Interface and Ethernet Link objects' replies, each attribute decoded.
  EXPECT_GE(tshark_count(cap, "cip.tcpip.encap_inactivity"), 2);
  EXPECT_GE(tshark_count(cap, "cip.tcpip.ip_addr"), 2);
  EXPECT_GE(tshark_count(cap, "cip.elink.interface_speed"), 2);
  // Nothing malformed, no expert error (tshark's own exit status checked: a filter it refused
  // would print nothing too).
  ASSERT_EQ(run_shell("sh -c \"tshark -r " + cap +
                          " -Y '_ws.malformed || _ws.expert.severity >= error' -V 2>/dev/null;"
                          " echo tshark exit \\$?\"",
                      &out),
            0);
  EXPECT_EQ(out, "tshark exit 0\n") << "malformed or expert-error packets:\n"
                                    << out.substr(0, 8000);
  ASSERT_EQ(run_shell("tshark -r " + cap + " -q -z expert 2>/dev/null | cat", &out), 0);
  EXPECT_EQ(out.find("Malformed"), std::string::npos) << out;
  std::cout << "tshark -z expert:\n" << out << "\n";
}

// A fuzz run: the mutation corpus (tests/enip/mutation_corpus.hpp, fixed seed) on TCP 44818,
// UDP 44818 and UDP 2222 of the running daemon.
TEST_F(EnipDaemonWire, FuzzedFramesOnTcpAndUdpNeitherCrashNorWriteTheImage) {
  start_3601();
  const auto& img = image_->raw();
  ImageWords before;
  ASSERT_TRUE(image_->read_outputs(before));
  const std::uint32_t seq = img.output_seq;
  const std::uint64_t heartbeat = image_->heartbeat_value();
  std::mt19937 rng(34);
  int tcp = -1;
  unsigned replies = 0;
  const sockaddr_in encap = ipv4(target_, 44818);
  const sockaddr_in io = ipv4(target_, 2222);
  const int udp = bound_socket(SOCK_DGRAM, scanner_ip_);
  ASSERT_GE(udp, 0);
  for (int round = 0; round < 400; ++round) {
    for (const Bytes& seed : enip::test::mutation_seeds()) {
      const Bytes b = enip::test::mutate(seed, rng);
      if (tcp < 0) tcp = tcp_connect(scanner_ip_, target_, 44818);
      ASSERT_GE(tcp, 0) << "the adapter stopped accepting connections\n" << daemon_->log();
      if (::send(tcp, b.data(), b.size(), MSG_NOSIGNAL) < 0) {
        ::close(tcp);
        tcp = -1;
      }
      ::sendto(udp, b.data(), b.size(), 0, reinterpret_cast<const sockaddr*>(&encap), sizeof encap);
      ::sendto(udp, b.data(), b.size(), 0, reinterpret_cast<const sockaddr*>(&io), sizeof io);
      if (tcp >= 0 && !receive(tcp, milliseconds(0)).empty()) ++replies;
    }
  }
  if (tcp >= 0) ::close(tcp);
  ::close(udp);
  EXPECT_GT(replies, 0u) << "the corpus never got an answer: it did not reach the adapter";
  // Still answered. The adapter may still be working through the corpus' datagrams, or the
  // kernel dropped the first request on a full receive queue (UDP, on a loaded machine): asked
  // again, once a second, for up to 10 s.
  std::string name;
  for (int attempt = 0; attempt < 10 && name.empty(); ++attempt) {
    name = list_identity_name(scanner_ip_);
  }
  EXPECT_EQ(name, "stepmod 3601") << daemon_->log();
  ImageWords after;
  ASSERT_TRUE(image_->read_outputs(after));
  EXPECT_EQ(after, before);
  EXPECT_EQ(img.output_seq, seq) << "an output write happened";
  EXPECT_EQ(image_->heartbeat_value(), heartbeat) << "a PLC heartbeat happened";
  EXPECT_EQ(::kill(daemon_->pid(), 0), 0) << "the daemon is gone";
}

}  // namespace
}  // namespace stepmod::testing
