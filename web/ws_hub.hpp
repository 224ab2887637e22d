#pragma once
// The console's WebSocket connections: each one's frames are read by its own thread (the civetweb
// worker that accepted it, which WebSocket connections keep anyway) through FrameReader, with
// every limit checked before a byte is buffered; everything sent to the clients goes through a
// bounded queue per client, written without blocking by one sender thread. So a client that stops
// reading never stalls the broadcaster (the sampler) or another client: its oldest batches are
// dropped, and it is closed when it takes no byte for `send_stall` or its queue passes
// `max_queued` (docs/web-console.md, "Limits").
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "web/ws_frame.hpp"

namespace stepmod::web {

struct WsLimits {
  std::size_t max_message = 64 * 1024;            // a larger message is refused: close 1009
  std::chrono::milliseconds frame_timeout{5000};  // a begun frame or message must end within
  std::size_t max_sessions = 16;  // beyond: the longest idle closed, or the new one refused
  std::chrono::milliseconds evict_idle{1000};  // ... if it received nothing for this long
  std::size_t max_batches = 25;      // batches queued per client (1 s of them): older ones dropped
  std::size_t max_queued = 1 << 20;  // bytes queued per client: beyond, it is closed
  std::chrono::milliseconds send_stall{5000};    // output waiting, no byte taken this long: closed
  std::chrono::milliseconds close_linger{1000};  // a closing connection's close frame, then gone
};

class WsHub {
 public:
  // A text (or binary, text == false) message of connection `id`: the reply to send (empty: none).
  using Handler = std::function<std::string(std::uintptr_t id, std::string_view msg, bool text)>;

  WsHub(WsLimits limits, Handler handler);
  ~WsHub();
  WsHub(const WsHub&) = delete;
  WsHub& operator=(const WsHub&) = delete;

  // Serves the connection on socket `fd` on the calling thread until it ends (peer gone, an error,
  // a limit, stop()); `first` is sent first. The socket is shut down on return (not closed: its
  // owner, civetweb, closes it). `peer` names it in the log.
  void serve(int fd, std::uintptr_t id, const std::string& peer, const std::string& first);
  // Queues a batch for every client (never blocks on one).
  void broadcast(const std::string& text);
  // Closes every connection and ends the sender; serve() returns at once from then on.
  void stop();
  std::size_t sessions() const;

 private:
  using Clock = std::chrono::steady_clock;
  struct Out {
    std::string bytes;
    bool batch;
  };
  struct Session {
    int fd;
    std::uintptr_t id;
    std::string peer;
    Clock::time_point last_rx;  // the last frame received (the idle measure for eviction)
    Clock::time_point last_tx;  // the socket last took bytes, or output became pending
    std::deque<Out> out;
    std::size_t sent = 0;  // bytes of out.front() already written
    std::size_t bytes = 0;
    std::size_t batches = 0;
    bool closing = false;  // a close frame is queued: shut down once sent or at close_by
    Clock::time_point close_by{};
    bool fin_sent = false;  // closing, and the close frame written: our side shut for writing
    bool dead = false;      // shut down: the reader ends, nobody touches fd again
  };
  using SessionPtr = std::shared_ptr<Session>;

  SessionPtr add(int fd, std::uintptr_t id, const std::string& peer);
  void read_loop(const SessionPtr& s);
  bool on_event(const SessionPtr& s, WsEvent& ev);
  void finish(const SessionPtr& s, std::uint16_t code, const std::string& why);
  void remove(const SessionPtr& s);
  void send(const SessionPtr& s, std::string frame, bool batch);
  void sender_loop();
  // With m_ held:
  void enqueue(Session& s, std::string frame, bool batch, Clock::time_point now);
  void close_session(Session& s, std::uint16_t code, const std::string& why, Clock::time_point now);
  void kill(Session& s, const std::string& why);
  void flush(Session& s, Clock::time_point now);
  void tend(Session& s, Clock::time_point now, std::vector<int>& writable);
  void wake();

  WsLimits lim_;
  Handler handler_;
  mutable std::mutex m_;
  std::map<std::uintptr_t, SessionPtr> sessions_;
  bool stopping_ = false;
  int wake_fd_ = -1;  // an eventfd: output was queued
  std::thread sender_;
};

}  // namespace stepmod::web
