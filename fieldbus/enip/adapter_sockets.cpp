#include "fieldbus/enip/adapter_sockets.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <sys/socket.h>
#include <sys/timerfd.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <limits>

#include "ipc/shm_object.hpp"

namespace stepmod::enip {

int open_bound_socket(int type, const std::string& address, std::uint16_t port) {
  const char* kind = type == SOCK_STREAM ? "TCP" : "UDP";
  const std::string where = std::string(kind) + " " + address + ":" + std::to_string(port);
  in_addr ip{};
  if (::inet_pton(AF_INET, address.c_str(), &ip) != 1) {
    throw ipc::IpcError("ethernetip: '" + address + "' is not a numeric IPv4 address");
  }
  const int fd = ::socket(AF_INET, type | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) throw ipc::IpcError("ethernetip: socket: " + std::string(std::strerror(errno)));
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in a = ipv4_address(ntohl(ip.s_addr), port);
  bool ok = ::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0;
  if (ok && type == SOCK_STREAM) ok = ::listen(fd, 16) == 0;
  if (!ok) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw ipc::IpcError("ethernetip: cannot bind " + where + ": " + why);
  }
  return fd;
}

int open_broadcast_socket(std::uint16_t port, std::string& why) noexcept {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    why = std::strerror(errno);
    return -1;
  }
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  want_packet_info(fd);
  const sockaddr_in a = ipv4_address(INADDR_ANY, port);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
    why = "cannot bind UDP 0.0.0.0:" + std::to_string(port) + ": " + std::strerror(errno);
    ::close(fd);
    return -1;
  }
  return fd;
}

void want_packet_info(int fd) noexcept {
  const int one = 1;
  ::setsockopt(fd, IPPROTO_IP, IP_PKTINFO, &one, sizeof one);
}

long receive_datagram(int fd, std::span<std::uint8_t> buf, Arrival& arrival) noexcept {
  iovec iov{buf.data(), buf.size()};
  alignas(cmsghdr) std::uint8_t control[CMSG_SPACE(sizeof(in_pktinfo))];
  msghdr m{};
  m.msg_name = &arrival.from;
  m.msg_namelen = sizeof arrival.from;
  m.msg_iov = &iov;
  m.msg_iovlen = 1;
  m.msg_control = control;
  m.msg_controllen = sizeof control;
  const ssize_t n = ::recvmsg(fd, &m, MSG_DONTWAIT | MSG_TRUNC);
  if (n < 0) return -1;
  arrival.ifindex = 0;
  arrival.destination = 0;
  for (cmsghdr* c = CMSG_FIRSTHDR(&m); c != nullptr; c = CMSG_NXTHDR(&m, c)) {
    if (c->cmsg_level != IPPROTO_IP || c->cmsg_type != IP_PKTINFO) continue;
    in_pktinfo info{};
    std::memcpy(&info, CMSG_DATA(c), sizeof info);
    arrival.ifindex = static_cast<unsigned>(info.ipi_ifindex);
    arrival.destination = ntohl(info.ipi_addr.s_addr);
  }
  return n;
}

std::vector<InterfaceAddress> interface_addresses() {
  std::vector<InterfaceAddress> out;
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) return out;
  for (const ifaddrs* i = list; i != nullptr; i = i->ifa_next) {
    if (i->ifa_addr == nullptr || i->ifa_addr->sa_family != AF_INET) continue;
    InterfaceAddress a;
    a.ifindex = ::if_nametoindex(i->ifa_name);
    a.address = ipv4_of(i->ifa_addr);
    if ((i->ifa_flags & IFF_BROADCAST) != 0) a.broadcast = ipv4_of(i->ifa_broadaddr);
    out.push_back(a);
  }
  ::freeifaddrs(list);
  return out;
}

int open_timer() {
  const int fd = ::timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
  if (fd < 0) throw ipc::IpcError("ethernetip: timerfd: " + std::string(std::strerror(errno)));
  return fd;
}

void arm_timer(int timer, std::int64_t at_ns) noexcept {
  itimerspec t{};
  if (at_ns != std::numeric_limits<std::int64_t>::max()) {
    // 0 would disarm: a time already passed is written as the earliest possible one.
    const std::int64_t at = at_ns > 0 ? at_ns : 1;
    t.it_value.tv_sec = static_cast<time_t>(at / 1'000'000'000);
    t.it_value.tv_nsec = static_cast<long>(at % 1'000'000'000);
  }
  ::timerfd_settime(timer, TFD_TIMER_ABSTIME, &t, nullptr);
}

sockaddr_in ipv4_address(std::uint32_t ip_host_order, std::uint16_t port) noexcept {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(ip_host_order);
  return a;
}

std::uint32_t parse_ipv4(std::string_view text) noexcept {
  std::array<char, INET_ADDRSTRLEN> z{};  // inet_pton wants it NUL-terminated
  if (text.size() >= z.size()) return 0;
  std::memcpy(z.data(), text.data(), text.size());
  in_addr a{};
  return ::inet_pton(AF_INET, z.data(), &a) == 1 ? ntohl(a.s_addr) : 0;
}

std::uint32_t ipv4_of(const sockaddr* sa) noexcept {
  if (sa == nullptr || sa->sa_family != AF_INET) return 0;
  return ntohl(reinterpret_cast<const sockaddr_in*>(sa)->sin_addr.s_addr);
}

bool send_whole(int fd, std::span<const std::uint8_t> bytes) noexcept {
  const ssize_t n = ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  return n >= 0 && static_cast<std::size_t>(n) == bytes.size();
}

}  // namespace stepmod::enip
