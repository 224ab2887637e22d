#include "fieldbus/enip/adapter_sockets.hpp"

#include <arpa/inet.h>
#include <sys/socket.h>
#include <sys/timerfd.h>
#include <unistd.h>

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

bool send_whole(int fd, std::span<const std::uint8_t> bytes) noexcept {
  const ssize_t n = ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  return n >= 0 && static_cast<std::size_t>(n) == bytes.size();
}

}  // namespace stepmod::enip
