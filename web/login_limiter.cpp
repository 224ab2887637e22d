#include "web/login_limiter.hpp"

#include <cstdio>

namespace stepmod::web {

LoginLimiter::Bucket& LoginLimiter::bucket(const std::string& client, Clock::time_point now) {
  auto it = clients_.find(client);
  if (it == clients_.end()) {
    if (clients_.size() >= max_clients_) {
      // Forget the clients whose bucket is full again: they are where a new one starts.
      std::erase_if(clients_, [&](const auto& e) {
        return e.second.tries + std::chrono::duration<double>(now - e.second.at) / interval_ >=
               burst_;
      });
    }
    if (clients_.size() >= max_clients_) clients_.clear();  // a flood of addresses: start over
    it = clients_.emplace(client, Bucket{static_cast<double>(burst_), now}).first;
  }
  Bucket& b = it->second;
  const double refill = std::chrono::duration<double>(now - b.at) / interval_;
  b.tries = std::min(static_cast<double>(burst_), b.tries + refill);
  b.at = now;
  return b;
}

std::int64_t LoginLimiter::wait_ms(const std::string& client, Clock::time_point now) {
  std::lock_guard lock(m_);
  Bucket& b = bucket(client, now);
  if (b.tries >= 1.0) {
    if (b.refused > 0) {
      std::fprintf(stderr, "stepmod-web: login from %s: %llu tries were refused (rate limit)\n",
                   client.c_str(), static_cast<unsigned long long>(b.refused));
      b.refused = 0;
    }
    return 0;
  }
  const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(
      std::chrono::duration<double>(1.0 - b.tries) * interval_.count() / 1000.0);
  if (b.refused++ == 0) {
    std::fprintf(stderr,
                 "stepmod-web: login from %s refused: %llu wrong tokens, one try per %lld ms "
                 "from now on\n",
                 client.c_str(), static_cast<unsigned long long>(b.wrong),
                 static_cast<long long>(interval_.count()));
  }
  return wait.count() + 1;
}

void LoginLimiter::failed(const std::string& client, Clock::time_point now) {
  std::lock_guard lock(m_);
  Bucket& b = bucket(client, now);
  b.tries = std::max(0.0, b.tries - 1.0);
  ++b.wrong;
  std::fprintf(stderr, "stepmod-web: login from %s: wrong token (%llu in a row)\n", client.c_str(),
               static_cast<unsigned long long>(b.wrong));
}

void LoginLimiter::succeeded(const std::string& client) {
  std::lock_guard lock(m_);
  const auto it = clients_.find(client);
  if (it != clients_.end()) it->second.wrong = 0;
}

}  // namespace stepmod::web
