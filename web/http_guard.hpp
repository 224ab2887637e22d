#pragma once
// Connections that hold a civetweb worker thread before their request is in. civetweb gives every
// connection a thread of its pool until the request is read (at most request_timeout_ms), so a
// few dozen idle or slowly sending connections ("slowloris") used to take every thread and lock
// the operator out. The guard counts them; beyond `max_waiting` the one waiting longest is shut
// down, which frees its thread at once. A browser sends its request as soon as it connects, so
// the idle ones go first (docs/web-console.md, "Limits").
#include <chrono>
#include <cstddef>
#include <functional>
#include <map>
#include <mutex>

namespace stepmod::web {

class HttpGuard {
 public:
  // The socket of a waiting connection (-1: not known), called with the guard's lock held, so
  // that the connection is still open (civetweb has not run its close callback).
  using FindSocket = std::function<int(const void* conn)>;
  HttpGuard(std::size_t max_waiting, FindSocket find) : max_(max_waiting), find_(std::move(find)) {}

  // A worker took connection `conn`: it waits for its request.
  void opened(const void* conn);
  // Its request is in: it no longer waits. Call before anything else of the request is done.
  void request_read(const void* conn);
  // civetweb closes it (its connection_close callback, before the socket is closed).
  void closed(const void* conn) { request_read(conn); }
  std::size_t waiting() const;

 private:
  std::size_t max_;
  FindSocket find_;
  mutable std::mutex m_;
  std::map<const void*, std::chrono::steady_clock::time_point> waiting_;
  std::size_t dropped_ = 0;  // since the last log line
  std::chrono::steady_clock::time_point last_log_{};
};

// At most one log line a second for a kind of refusal, so that a flood fills no disk: pass()
// says whether to log now and how many were not logged since the last line.
class LogThrottle {
 public:
  bool pass(unsigned& skipped);

 private:
  std::mutex m_;
  std::chrono::steady_clock::time_point last_{};
  unsigned skipped_ = 0;
};

}  // namespace stepmod::web
