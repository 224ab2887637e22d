#pragma once
// The adapter's sockets (docs/ethernetip-design.md, "Where it sits in stepmod"): non-blocking,
// close-on-exec, SO_REUSEADDR so that a restarted daemon binds at once, and the timerfd that
// wakes the I/O thread when the connection table has something due.
#include <netinet/in.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fieldbus/enip/broadcast.hpp"

namespace stepmod::enip {

// A socket of `type` (SOCK_STREAM: listening; SOCK_DGRAM) bound to `address`:`port`. Throws
// ipc::IpcError naming the address and why.
int open_bound_socket(int type, const std::string& address, std::uint16_t port);

// A UDP socket on 0.0.0.0:`port` for the broadcasts a socket bound to one address does not
// receive (SO_REUSEADDR: it shares the port with the adapters of a rack and the unicast socket;
// IP_PKTINFO). -1 when it cannot be bound, with `why` set: the adapter then runs without it.
int open_broadcast_socket(std::uint16_t port, std::string& why) noexcept;
// Asks IP_PKTINFO of a UDP socket: receive_datagram() then tells each datagram's interface and
// destination address.
void want_packet_info(int fd) noexcept;

// Where a datagram came from and how it arrived (ifindex and destination 0 without IP_PKTINFO).
struct Arrival {
  sockaddr_in from{};
  unsigned ifindex = 0;
  std::uint32_t destination = 0;  // host byte order
};
// One datagram waiting on `fd` into `buf`: its whole size (larger than `buf` when it did not
// fit), or -1 when none waits.
long receive_datagram(int fd, std::span<std::uint8_t> buf, Arrival& arrival) noexcept;

// The machine's IPv4 addresses now (getifaddrs); empty when it cannot tell.
std::vector<InterfaceAddress> interface_addresses();

// A CLOCK_MONOTONIC timerfd, non-blocking. Throws ipc::IpcError.
int open_timer();
// Arms `timer` to fire once at `at_ns` (CLOCK_MONOTONIC; in the past: at once); INT64_MAX
// disarms it.
void arm_timer(int timer, std::int64_t at_ns) noexcept;

sockaddr_in ipv4_address(std::uint32_t ip_host_order, std::uint16_t port) noexcept;
// An IPv4 address's text ("192.168.1.10") in host byte order; 0 when it is not one.
std::uint32_t parse_ipv4(std::string_view text) noexcept;
// The IPv4 address of `sa` in host byte order; 0 when there is none or it is not IPv4.
std::uint32_t ipv4_of(const sockaddr* sa) noexcept;

// Sends all of `bytes` on a non-blocking stream socket; false when it could not (the peer does
// not read, or is gone): the caller closes it rather than wait.
bool send_whole(int fd, std::span<const std::uint8_t> bytes) noexcept;

}  // namespace stepmod::enip
