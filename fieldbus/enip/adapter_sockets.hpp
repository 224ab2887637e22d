#pragma once
// The adapter's sockets (docs/ethernetip-design.md, "Where it sits in stepmod"): non-blocking,
// close-on-exec, SO_REUSEADDR so that a restarted daemon binds at once, and the timerfd that
// wakes the I/O thread when the connection table has something due.
#include <netinet/in.h>

#include <cstdint>
#include <span>
#include <string>

namespace stepmod::enip {

// A socket of `type` (SOCK_STREAM: listening; SOCK_DGRAM) bound to `address`:`port`. Throws
// ipc::IpcError naming the address and why.
int open_bound_socket(int type, const std::string& address, std::uint16_t port);

// A CLOCK_MONOTONIC timerfd, non-blocking. Throws ipc::IpcError.
int open_timer();
// Arms `timer` to fire once at `at_ns` (CLOCK_MONOTONIC; in the past: at once); INT64_MAX
// disarms it.
void arm_timer(int timer, std::int64_t at_ns) noexcept;

sockaddr_in ipv4_address(std::uint32_t ip_host_order, std::uint16_t port) noexcept;

// Sends all of `bytes` on a non-blocking stream socket; false when it could not (the peer does
// not read, or is gone): the caller closes it rather than wait.
bool send_whole(int fd, std::span<const std::uint8_t> bytes) noexcept;

}  // namespace stepmod::enip
