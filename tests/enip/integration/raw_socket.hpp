#pragma once
// Plain sockets bound to a chosen loopback address, for the EtherNet/IP tests that speak to the
// adapter byte by byte (ListIdentity, the allow list, the fuzz run): no client library between.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace stepmod::testing {

inline sockaddr_in ipv4(const std::string& ip, std::uint16_t port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  ::inet_pton(AF_INET, ip.c_str(), &a.sin_addr);
  return a;
}

// A socket of `type` bound to `local` (port 0: the kernel's choice); -1 on failure.
inline int bound_socket(int type, const std::string& local) {
  const int fd = ::socket(AF_INET, type | SOCK_CLOEXEC, 0);
  const sockaddr_in a = ipv4(local, 0);
  if (fd >= 0 && ::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// Waits up to `timeout` for bytes on `fd` and returns what one read gives (empty: none, or the
// peer closed).
inline std::vector<std::uint8_t> receive(int fd, std::chrono::milliseconds timeout) {
  pollfd p{fd, POLLIN, 0};
  std::vector<std::uint8_t> b(2048);
  if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return {};
  const ssize_t n = ::recv(fd, b.data(), b.size(), MSG_DONTWAIT);
  b.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  return b;
}

// One UDP datagram from `local` to `target`:`port`, and the reply (empty: none in `timeout`).
inline std::vector<std::uint8_t> udp_exchange(const std::string& local, const std::string& target,
                                              std::uint16_t port,
                                              const std::vector<std::uint8_t>& request,
                                              std::chrono::milliseconds timeout) {
  const int fd = bound_socket(SOCK_DGRAM, local);
  if (fd < 0) return {};
  const sockaddr_in to = ipv4(target, port);
  ::sendto(fd, request.data(), request.size(), 0, reinterpret_cast<const sockaddr*>(&to),
           sizeof to);
  std::vector<std::uint8_t> reply = receive(fd, timeout);
  ::close(fd);
  return reply;
}

// A TCP connection from `local` to `target`:`port`; -1 when refused.
inline int tcp_connect(const std::string& local, const std::string& target, std::uint16_t port) {
  const int fd = bound_socket(SOCK_STREAM, local);
  const sockaddr_in to = ipv4(target, port);
  if (fd >= 0 && ::connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof to) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

}  // namespace stepmod::testing
