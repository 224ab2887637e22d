// The board's interface as Linux has it (fieldbus/enip/net_interface_linux.cpp): the parsers of
// /proc/net/route and /etc/resolv.conf on their texts, then the loopback read for real.
#include "fieldbus/enip/net_interface_linux.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <string>

#include "fieldbus/enip/adapter_sockets.hpp"

namespace stepmod::enip {
namespace {

constexpr const char* kRoute =
    "Iface\tDestination\tGateway \tFlags\tRefCnt\tUse\tMetric\tMask\t\tMTU\tWindow\tIRTT\n"
    "wlan0\t00000000\t0102A8C0\t0003\t0\t0\t600\t00000000\t0\t0\t0\n"
    "eth0\t0001A8C0\t00000000\t0001\t0\t0\t100\t00FFFFFF\t0\t0\t0\n"
    "eth0\t00000000\t0101A8C0\t0003\t0\t0\t100\t00000000\t0\t0\t0\n";

void send_one_datagram_on_the_loopback() {
  const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(s, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(9);  // discard
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const char byte = 0;
  ::sendto(s, &byte, 1, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  ::close(s);
}

TEST(EnipNetInterface, Ipv4TextAndSocketAddresses) {
  EXPECT_EQ(parse_ipv4("192.168.1.10"), 0xC0A8010Au);
  EXPECT_EQ(parse_ipv4("192.168.1.10 trailing"), 0u);  // not only an address
  EXPECT_EQ(parse_ipv4("2001:db8::1"), 0u);
  EXPECT_EQ(parse_ipv4(""), 0u);
  EXPECT_EQ(parse_ipv4(std::string(40, '1')), 0u);  // longer than any address: not read
  const sockaddr_in a = ipv4_address(0x0A000005u, 44818);
  EXPECT_EQ(ipv4_of(reinterpret_cast<const sockaddr*>(&a)), 0x0A000005u);
  sockaddr_in6 six{};
  six.sin6_family = AF_INET6;
  EXPECT_EQ(ipv4_of(reinterpret_cast<const sockaddr*>(&six)), 0u);
  EXPECT_EQ(ipv4_of(nullptr), 0u);
}

TEST(EnipNetInterface, TheDefaultGatewayOfTheInterface) {
  EXPECT_EQ(default_gateway(kRoute, "eth0"), 0xC0A80101u);   // 192.168.1.1
  EXPECT_EQ(default_gateway(kRoute, "wlan0"), 0xC0A80201u);  // 192.168.2.1
  EXPECT_EQ(default_gateway(kRoute, "eth1"), 0u);            // none
  EXPECT_EQ(default_gateway("", "eth0"), 0u);
  EXPECT_EQ(default_gateway("Iface\nno fields\neth0 zz 0101A8C0 0003\n", "eth0"), 0u);
  // A route to a network (not the default) through a gateway is not the default gateway.
  EXPECT_EQ(default_gateway("h\neth0\t000A0A0A\t0101A8C0\t0003\n", "eth0"), 0u);
}

TEST(EnipNetInterface, NameServersAndDomainFromResolvConf) {
  NetInterface n;
  read_resolv_conf(
      "# generated\nsearch lan corp\nnameserver 2001:db8::1\nnameserver 10.0.0.1\n"
      "nameserver 10.0.0.2\nnameserver 10.0.0.3\n",
      n);
  EXPECT_EQ(n.name_server, 0x0A000001u);  // the IPv6 one has no place in the attribute
  EXPECT_EQ(n.name_server_2, 0x0A000002u);
  EXPECT_EQ(n.domain.view(), "lan");
  NetInterface d;
  read_resolv_conf("search lan\ndomain plant.example\n", d);
  EXPECT_EQ(d.domain.view(), "plant.example");  // the last of "domain" and "search" wins
  NetInterface s;
  read_resolv_conf("domain plant.example\r\nsearch corp lan\r\nnameserver 10.0.0.9\r\n", s);
  EXPECT_EQ(s.domain.view(), "corp");
  EXPECT_EQ(s.name_server, 0x0A000009u) << "a CRLF line";
  NetInterface long_name;
  read_resolv_conf("domain " + std::string(60, 'x') + "\n", long_name);
  EXPECT_EQ(long_name.domain.length, 48u);  // CIP's limit
  NetInterface none;
  read_resolv_conf("", none);
  EXPECT_EQ(none.name_server, 0u);
  EXPECT_EQ(none.domain.length, 0u);
}

TEST(EnipNetInterface, TheLoopbackAsLinuxHasIt) {
  send_one_datagram_on_the_loopback();  // so that its counters have counted something
  LinuxNetworkPort port;
  NetInterface n;
  ASSERT_TRUE(port.describe(0x7F000001u, n));
  EXPECT_EQ(n.label.view(), "lo");
  EXPECT_EQ(n.ip, 0x7F000001u);
  EXPECT_EQ(n.mask, 0xFF000000u);
  EXPECT_TRUE(n.admin_up);
  EXPECT_EQ(n.medium, Medium::kInternal);
  EXPECT_EQ(n.mac, (std::array<std::uint8_t, 6>{}));
  EXPECT_EQ(n.gateway, 0u);
  std::array<char, 65> host{};
  ASSERT_EQ(::gethostname(host.data(), host.size() - 1), 0);
  EXPECT_EQ(n.host_name.view(), std::string(host.data()).substr(0, 64));
  EXPECT_GT(n.counters.interface[6], 0u) << "the loopback has sent nothing?";
}

TEST(EnipNetInterface, AnAddressInAnInterfacesNetworkIsThatInterface) {
  LinuxNetworkPort port;
  NetInterface n;
  ASSERT_TRUE(port.describe(0x7F004D01u, n));  // 127.0.77.1: answered by the loopback
  EXPECT_EQ(n.label.view(), "lo");
  EXPECT_EQ(n.ip, 0x7F004D01u);  // the address the request came in on
}

TEST(EnipNetInterface, AnAddressNoInterfaceHasIsNotDescribed) {
  LinuxNetworkPort port;
  NetInterface n;
  EXPECT_FALSE(port.describe(0x00000001u, n));  // 0.0.0.1: in no interface's network
  EXPECT_FALSE(port.describe(0, n));
}

}  // namespace
}  // namespace stepmod::enip
