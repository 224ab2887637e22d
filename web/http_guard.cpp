#include "web/http_guard.hpp"

#include <sys/socket.h>

#include <cstdio>

namespace stepmod::web {

void HttpGuard::opened(const void* conn) {
  const auto now = std::chrono::steady_clock::now();
  std::lock_guard lock(m_);
  waiting_[conn] = now;
  // The longest waiting go first; one whose socket is not found stays (counted, not shut).
  auto candidates = waiting_.size() > max_ ? waiting_.size() - 1 : 0;
  while (waiting_.size() > max_ && candidates-- > 0) {
    auto oldest = waiting_.end();
    for (auto it = waiting_.begin(); it != waiting_.end(); ++it) {
      if (it->first != conn && (oldest == waiting_.end() || it->second < oldest->second)) {
        oldest = it;
      }
    }
    const int fd = find_(oldest->first);
    if (fd < 0) {
      oldest->second = now;  // tried: the next one's turn
      continue;
    }
    shutdown(fd, SHUT_RDWR);  // its worker's read ends at once, and civetweb closes it
    waiting_.erase(oldest);
    ++dropped_;
  }
  if (dropped_ > 0 && now - last_log_ >= std::chrono::seconds(10)) {
    std::fprintf(stderr,
                 "stepmod-web: %zu connection(s) closed before sending their request (more than "
                 "%zu waiting)\n",
                 dropped_, max_);
    dropped_ = 0;
    last_log_ = now;
  }
}

void HttpGuard::request_read(const void* conn) {
  std::lock_guard lock(m_);
  waiting_.erase(conn);
}

std::size_t HttpGuard::waiting() const {
  std::lock_guard lock(m_);
  return waiting_.size();
}

bool LogThrottle::pass(unsigned& skipped) {
  const auto now = std::chrono::steady_clock::now();
  std::lock_guard lock(m_);
  if (last_ != std::chrono::steady_clock::time_point{} && now - last_ < std::chrono::seconds(1)) {
    ++skipped_;
    return false;
  }
  last_ = now;
  skipped = skipped_;
  skipped_ = 0;
  return true;
}

}  // namespace stepmod::web
