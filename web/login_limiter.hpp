#pragma once
// Login attempts per client address: a burst of `burst` wrong tokens, then one try per
// `interval` (a token bucket that only wrong tokens drain). A try beyond that is refused without
// looking at the token (429), so guessing runs at one try per `interval` per address instead of
// thousands a second. Every wrong token is logged, and the first refused try of a run and the
// count of refused tries when the next one is let through (docs/hardening.md).
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <unordered_map>

namespace stepmod::web {

class LoginLimiter {
 public:
  using Clock = std::chrono::steady_clock;
  LoginLimiter(unsigned burst = 5, std::chrono::milliseconds interval = std::chrono::seconds(2),
               std::size_t max_clients = 4096)
      : burst_(burst), interval_(interval), max_clients_(max_clients) {}

  // 0 when `client` may try now, else the milliseconds until it may.
  std::int64_t wait_ms(const std::string& client, Clock::time_point now = Clock::now());
  // A wrong token from `client` (logged).
  void failed(const std::string& client, Clock::time_point now = Clock::now());
  // The token was right: the count of wrong ones in a row starts again.
  void succeeded(const std::string& client);

 private:
  struct Bucket {
    double tries;  // tries left (refilled one per interval, up to burst)
    Clock::time_point at;
    std::uint64_t wrong = 0;    // wrong tokens in a row
    std::uint64_t refused = 0;  // tries refused since the last one let through
  };
  Bucket& bucket(const std::string& client, Clock::time_point now);

  unsigned burst_;
  std::chrono::milliseconds interval_;
  std::size_t max_clients_;
  std::mutex m_;
  std::unordered_map<std::string, Bucket> clients_;
};

}  // namespace stepmod::web
