#include "web/ws_hub.hpp"

#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <system_error>

namespace stepmod::web {
namespace {

long long ms(std::chrono::steady_clock::duration d) {
  return std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
}

void log(const std::string& peer, const std::string& what) {
  std::fprintf(stderr, "stepmod-web: WebSocket from %s: %s\n", peer.c_str(), what.c_str());
}

bool would_block(int e) {
  return e == EAGAIN || e == EWOULDBLOCK || e == EINTR;
}

}  // namespace

WsHub::WsHub(WsLimits limits, Handler handler) : lim_(limits), handler_(std::move(handler)) {
  wake_fd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake_fd_ < 0) throw std::system_error(errno, std::generic_category(), "eventfd");
  sender_ = std::thread([this] { sender_loop(); });
}

WsHub::~WsHub() {
  stop();
  close(wake_fd_);
}

void WsHub::stop() {
  {
    std::lock_guard lock(m_);
    if (!stopping_) {
      stopping_ = true;
      for (auto& entry : sessions_) kill(*entry.second, "");
    }
  }
  wake();
  if (sender_.joinable()) sender_.join();
}

std::size_t WsHub::sessions() const {
  std::lock_guard lock(m_);
  std::size_t n = 0;
  for (const auto& entry : sessions_) n += entry.second->dead ? 0 : 1;
  return n;
}

void WsHub::serve(int fd, std::uintptr_t id, const std::string& peer, const std::string& first) {
  const SessionPtr s = add(fd, id, peer);
  send(s, ws_frame(WsOp::kText, first), false);
  read_loop(s);
  remove(s);
}

void WsHub::broadcast(const std::string& text) {
  const std::string frame = ws_frame(WsOp::kText, text);
  {
    std::lock_guard lock(m_);
    const auto now = Clock::now();
    for (auto& entry : sessions_) enqueue(*entry.second, frame, true, now);
  }
  wake();
}

WsHub::SessionPtr WsHub::add(int fd, std::uintptr_t id, const std::string& peer) {
  const auto now = Clock::now();
  auto s = std::make_shared<Session>();
  s->fd = fd;
  s->id = id;
  s->peer = peer;
  s->last_rx = s->last_tx = now;
  std::lock_guard lock(m_);
  if (stopping_) {
    kill(*s, "");
    return s;
  }
  std::size_t live = 0;  // the ones closing or gone are not counted
  for (const auto& entry : sessions_) live += entry.second->dead || entry.second->closing ? 0 : 1;
  if (live >= lim_.max_sessions) {
    Session* idle = nullptr;
    for (auto& entry : sessions_) {
      Session& o = *entry.second;
      if (!o.dead && !o.closing && (idle == nullptr || o.last_rx < idle->last_rx)) idle = &o;
    }
    if (idle != nullptr && now - idle->last_rx >= lim_.evict_idle) {
      close_session(*idle, kClosePolicy, "too many connections: the longest idle one is closed",
                    now);
    } else {
      close_session(*s, kCloseTryLater, "too many connections", now);
    }
  }
  sessions_[id] = s;
  return s;
}

void WsHub::remove(const SessionPtr& s) {
  std::lock_guard lock(m_);
  kill(*s, "");  // civetweb's own read loop, entered on return, then ends at once
  const auto it = sessions_.find(s->id);
  if (it != sessions_.end() && it->second == s) sessions_.erase(it);
}

void WsHub::read_loop(const SessionPtr& s) {
  FrameReader reader(lim_.max_message);
  std::string buf(16 * 1024, '\0');
  Clock::time_point partial_since{};  // when the frame being read began (epoch: none)
  for (;;) {
    bool closing = false;
    {
      std::lock_guard lock(m_);
      if (s->dead) return;
      closing = s->closing;
    }
    const std::size_t want = closing ? buf.size() : std::min(buf.size(), reader.room());
    if (want == 0) {
      finish(s, kCloseTooBig, "a message beyond the limit");
      continue;
    }
    pollfd p{s->fd, POLLIN, 0};
    if (poll(&p, 1, 100) > 0) {
      const ssize_t n = recv(s->fd, buf.data(), want, MSG_DONTWAIT);
      if (n == 0 || (n < 0 && !would_block(errno))) return;  // the peer is gone
      if (n > 0 && !closing) reader.feed(buf.data(), static_cast<std::size_t>(n));
    }
    if (closing) continue;  // our close frame is on its way: input is read and dropped
    for (WsEvent ev = reader.next(); ev.kind != WsEvent::Kind::kNeedMore; ev = reader.next()) {
      if (!on_event(s, ev)) break;
    }
    const auto now = Clock::now();
    if (!reader.partial()) {
      partial_since = {};
    } else if (partial_since == Clock::time_point{}) {
      partial_since = now;
    } else if (now - partial_since > lim_.frame_timeout) {
      finish(
          s, kClosePolicy,
          "a frame not complete " + std::to_string(ms(lim_.frame_timeout)) + " ms after it began");
    }
  }
}

// Returns false when the connection is closing (the events after it are not looked at).
bool WsHub::on_event(const SessionPtr& s, WsEvent& ev) {
  {
    std::lock_guard lock(m_);
    s->last_rx = Clock::now();
  }
  switch (ev.kind) {
    case WsEvent::Kind::kMessage: {
      std::string reply;
      try {
        reply = handler_(s->id, ev.payload, ev.op == WsOp::kText);
      } catch (const std::exception& e) {  // a handler bug: the connection goes, the process stays
        finish(s, 1011, std::string("internal error: ") + e.what());
        return false;
      }
      if (!reply.empty()) send(s, ws_frame(WsOp::kText, reply), false);
      return true;
    }
    case WsEvent::Kind::kPing:
      send(s, ws_frame(WsOp::kPong, ev.payload), false);
      return true;
    case WsEvent::Kind::kPong:
      return true;
    case WsEvent::Kind::kClose:
      finish(s, kCloseNormal, "");
      return false;
    default:  // kError
      finish(s, ev.code, ev.payload);
      return false;
  }
}

void WsHub::finish(const SessionPtr& s, std::uint16_t code, const std::string& why) {
  {
    std::lock_guard lock(m_);
    close_session(*s, code, why, Clock::now());
  }
  wake();
}

void WsHub::send(const SessionPtr& s, std::string frame, bool batch) {
  {
    std::lock_guard lock(m_);
    enqueue(*s, std::move(frame), batch, Clock::now());
  }
  wake();
}

void WsHub::enqueue(Session& s, std::string frame, bool batch, Clock::time_point now) {
  if (s.dead || s.closing) return;
  if (s.out.empty()) s.last_tx = now;  // the stall clock starts when output is waiting
  if (batch && s.batches >= lim_.max_batches) {
    // The oldest batch not begun on the wire goes: a slow page sees fresh data, not old.
    for (auto it = s.out.begin() + (s.sent > 0 ? 1 : 0); it != s.out.end(); ++it) {
      if (!it->batch) continue;
      s.bytes -= it->bytes.size();
      --s.batches;
      s.out.erase(it);
      break;
    }
  }
  s.bytes += frame.size();
  s.batches += batch ? 1 : 0;
  s.out.push_back({std::move(frame), batch});
  if (s.bytes > lim_.max_queued) {
    kill(s, "closed: more than " + std::to_string(lim_.max_queued) + " bytes waiting for it");
  }
}

void WsHub::close_session(Session& s, std::uint16_t code, const std::string& why,
                          Clock::time_point now) {
  if (s.dead || s.closing) return;
  if (!why.empty()) log(s.peer, "closed (" + std::to_string(code) + " " + why + ")");
  enqueue(s, ws_close_frame(code, why), false, now);
  s.closing = true;
  s.close_by = now + lim_.close_linger;
}

void WsHub::kill(Session& s, const std::string& why) {
  if (s.dead) return;
  if (!why.empty()) log(s.peer, why);
  s.dead = true;
  shutdown(s.fd, SHUT_RDWR);
}

void WsHub::flush(Session& s, Clock::time_point now) {
  while (!s.out.empty() && !s.dead) {
    const Out& o = s.out.front();
    const ssize_t n =
        ::send(s.fd, o.bytes.data() + s.sent, o.bytes.size() - s.sent, MSG_DONTWAIT | MSG_NOSIGNAL);
    if (n < 0) {
      if (!would_block(errno)) kill(s, "");  // the peer is gone
      return;
    }
    s.last_tx = now;
    s.sent += static_cast<std::size_t>(n);
    if (s.sent < o.bytes.size()) return;  // the socket is full
    s.bytes -= o.bytes.size();
    s.batches -= o.batch ? 1 : 0;
    s.out.pop_front();
    s.sent = 0;
  }
}

void WsHub::tend(Session& s, Clock::time_point now, std::vector<int>& writable) {
  flush(s, now);
  if (s.dead) return;
  if (!s.out.empty()) {
    if (now - s.last_tx > lim_.send_stall) {
      kill(s, "closed: it took no data for " + std::to_string(ms(now - s.last_tx)) + " ms");
      return;
    }
    writable.push_back(s.fd);
  } else if (s.closing && !s.fin_sent) {
    shutdown(s.fd, SHUT_WR);  // after the close frame: the peer answers, then its end
    s.fin_sent = true;
  }
  if (s.closing && now >= s.close_by) kill(s, "");
}

void WsHub::sender_loop() {
  std::vector<int> writable;
  std::vector<pollfd> fds;
  for (;;) {
    writable.clear();
    {
      std::lock_guard lock(m_);
      if (stopping_) return;
      const auto now = Clock::now();
      for (auto& entry : sessions_) {
        if (!entry.second->dead) tend(*entry.second, now, writable);
      }
    }
    // Descriptors of sessions ended meanwhile are only polled: a spurious wake at worst.
    fds.assign(1, pollfd{wake_fd_, POLLIN, 0});
    for (const int fd : writable) fds.push_back(pollfd{fd, POLLOUT, 0});
    poll(fds.data(), fds.size(), 100);
    std::uint64_t v = 0;
    [[maybe_unused]] const ssize_t r = read(wake_fd_, &v, sizeof v);
  }
}

void WsHub::wake() {
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t r = write(wake_fd_, &one, sizeof one);
}

}  // namespace stepmod::web
