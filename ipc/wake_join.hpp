#pragma once
// Ends a server thread that polls an eventfd beside its sockets (the Modbus server, the
// EtherNet/IP adapter): one write wakes its poll(), it closes its sockets and returns, and the
// caller waits for it. Nothing when the thread is not running (stop() is idempotent).
#include <unistd.h>

#include <cstdint>
#include <thread>

namespace stepmod::ipc {

inline void wake_and_join(int wake_fd, std::thread& thread) noexcept {
  if (!thread.joinable()) return;
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t n = ::write(wake_fd, &one, sizeof one);
  thread.join();
}

}  // namespace stepmod::ipc
