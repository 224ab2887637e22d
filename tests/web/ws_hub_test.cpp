// The console's WebSocket hub over socketpairs (no civetweb, no daemon): the hello first, replies
// and batches, and the limits: a client that stops reading holds up neither the broadcaster nor
// another client and is closed; an oversized message, a frame left half-sent and a connection
// beyond the cap are closed with their codes.
#include <gtest/gtest.h>

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "web/ws_hub.hpp"

namespace stepmod::web {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

std::string client_frame(std::uint8_t op, const std::string& payload) {
  std::string f(1, static_cast<char>(0x80 | op));
  f.push_back(static_cast<char>(0x80 | payload.size()));  // short payloads only
  f.append("\x01\x02\x03\x04", 4);
  for (std::size_t i = 0; i < payload.size(); ++i) {
    f.push_back(static_cast<char>(payload[i] ^ "\x01\x02\x03\x04"[i & 3]));
  }
  return f;
}

void write_all(int fd, const std::string& bytes) {
  ASSERT_EQ(::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL),
            static_cast<ssize_t>(bytes.size()));
}

struct Frame {
  int op = -1;  // -1: none before the deadline, or the connection ended
  std::string payload;
  int close_code() const {
    return payload.size() >= 2 ? (static_cast<std::uint8_t>(payload[0]) << 8) |
                                     static_cast<std::uint8_t>(payload[1])
                               : -1;
  }
};

// One connection as its client sees it: the client end of a socketpair, read frame by frame.
struct Client {
  int fd = -1;
  int server_fd = -1;
  std::string buf;

  bool need(std::size_t n, Clock::time_point deadline) {
    while (buf.size() < n) {
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
      pollfd p{fd, POLLIN, 0};
      if (left.count() <= 0 || poll(&p, 1, static_cast<int>(left.count())) <= 0) return false;
      char chunk[65536];
      const ssize_t r = recv(fd, chunk, sizeof chunk, 0);
      if (r <= 0) return false;
      buf.append(chunk, static_cast<std::size_t>(r));
    }
    return true;
  }

  Frame next(std::chrono::milliseconds timeout = 5000ms) {
    const auto deadline = Clock::now() + timeout;
    Frame f;
    if (!need(2, deadline)) return f;
    std::size_t len = static_cast<std::uint8_t>(buf[1]) & 0x7F;
    const std::size_t hdr = len == 126 ? 4 : len == 127 ? 10 : 2;
    if (!need(hdr, deadline)) return f;
    if (hdr > 2) {
      len = 0;
      for (std::size_t i = 2; i < hdr; ++i) len = (len << 8) | static_cast<std::uint8_t>(buf[i]);
    }
    if (!need(hdr + len, deadline)) return f;
    f.op = static_cast<std::uint8_t>(buf[0]) & 0x0F;
    f.payload = buf.substr(hdr, len);
    buf.erase(0, hdr + len);
    return f;
  }
};

class HubTest : public ::testing::Test {
 protected:
  void start(WsLimits lim) {
    hub_ = std::make_unique<WsHub>(
        lim, [](std::uintptr_t, std::string_view msg, bool) { return "re:" + std::string(msg); });
  }
  // A served connection; `sndbuf`: the server end's send buffer (small: it fills at once).
  Client& connect(int sndbuf = 0) {
    int sv[2];
    EXPECT_EQ(socketpair(AF_UNIX, SOCK_STREAM, 0, sv), 0);
    if (sndbuf > 0) setsockopt(sv[0], SOL_SOCKET, SO_SNDBUF, &sndbuf, sizeof sndbuf);
    clients_.push_back(std::make_unique<Client>());
    Client& c = *clients_.back();
    c.fd = sv[1];
    c.server_fd = sv[0];
    const auto id = static_cast<std::uintptr_t>(sv[0]);
    threads_.emplace_back([this, sv, id] { hub_->serve(sv[0], id, "test", "hello"); });
    return c;
  }
  void TearDown() override {
    for (auto& c : clients_) shutdown(c->fd, SHUT_RDWR);
    if (hub_) hub_->stop();
    for (auto& t : threads_) t.join();
    for (auto& c : clients_) {
      close(c->fd);
      close(c->server_fd);
    }
  }
  bool sessions_become(std::size_t n) {
    const auto end = Clock::now() + 5s;
    while (Clock::now() < end) {
      if (hub_->sessions() == n) return true;
      std::this_thread::sleep_for(10ms);
    }
    return false;
  }

  std::unique_ptr<WsHub> hub_;
  std::vector<std::unique_ptr<Client>> clients_;
  std::vector<std::thread> threads_;
};

TEST_F(HubTest, HelloFirstThenRepliesBatchesAndACleanClose) {
  start({});
  Client& c = connect();
  EXPECT_EQ(c.next().payload, "hello");
  write_all(c.fd, client_frame(0x1, R"({"op":"x"})"));
  EXPECT_EQ(c.next().payload, R"(re:{"op":"x"})");
  hub_->broadcast("batch 1");
  EXPECT_EQ(c.next().payload, "batch 1");
  write_all(c.fd, client_frame(0x9, "ping"));
  const Frame pong = c.next();
  EXPECT_EQ(pong.op, 0xA);
  EXPECT_EQ(pong.payload, "ping");
  write_all(c.fd, client_frame(0x8, "\x03\xE8"));
  const Frame close_frame = c.next();
  EXPECT_EQ(close_frame.op, 0x8);
  EXPECT_EQ(close_frame.close_code(), 1000);
  shutdown(c.fd, SHUT_WR);
  EXPECT_TRUE(sessions_become(0));
}

TEST_F(HubTest, AClientThatStopsReadingHoldsUpNobodyAndIsClosed) {
  WsLimits lim;
  lim.max_batches = 4;
  lim.send_stall = 300ms;
  start(lim);
  Client& reader = connect();
  Client& stalled = connect(4096);  // takes nothing from here on
  EXPECT_EQ(reader.next().payload, "hello");
  ASSERT_TRUE(sessions_become(2));
  const std::string batch(8000, 'b');
  auto slowest = Clock::duration::zero();
  for (int i = 0; i < 100; ++i) {
    const auto t0 = Clock::now();
    hub_->broadcast(i == 99 ? "last" : batch);
    slowest = std::max(slowest, Clock::now() - t0);
    EXPECT_EQ(reader.next().payload.size(), i == 99 ? 4u : batch.size()) << i;
  }
  // Generous for a loaded machine: a blocking write would be the 300 ms stall or forever.
  EXPECT_LT(slowest, 100ms);
  EXPECT_TRUE(sessions_become(1)) << "the stalled client was not closed";
  (void)stalled;
}

TEST_F(HubTest, AMessageOverTheLimitIsClosedWith1009BeforeItIsRead) {
  WsLimits lim;
  lim.max_message = 1024;
  start(lim);
  Client& c = connect();
  EXPECT_EQ(c.next().payload, "hello");
  // The header of a 1 MB text frame and a little of it: the rest never comes.
  write_all(c.fd, std::string("\x81\xFF\x00\x00\x00\x00\x00\x10\x00\x00mask", 14) +
                      std::string(100, 'a'));
  const Frame f = c.next();
  EXPECT_EQ(f.op, 0x8);
  EXPECT_EQ(f.close_code(), 1009);
  EXPECT_TRUE(sessions_become(0));
}

TEST_F(HubTest, AFrameLeftHalfSentIsClosed) {
  WsLimits lim;
  lim.frame_timeout = 200ms;
  start(lim);
  Client& c = connect();
  EXPECT_EQ(c.next().payload, "hello");
  write_all(c.fd, std::string("\x81\x85", 2));  // and nothing more
  const Frame f = c.next();
  EXPECT_EQ(f.op, 0x8);
  EXPECT_EQ(f.close_code(), 1008);
}

TEST_F(HubTest, BeyondTheCapTheLongestIdleGoesOrTheNewOneIsRefused) {
  WsLimits lim;
  lim.max_sessions = 1;
  lim.evict_idle = 200ms;
  start(lim);
  Client& first = connect();
  EXPECT_EQ(first.next().payload, "hello");
  ASSERT_TRUE(sessions_become(1));
  Client& busy = connect();  // `first` has been idle for less than 200 ms: refused
  Frame f = busy.next();
  if (f.payload == "hello") f = busy.next();
  EXPECT_EQ(f.close_code(), 1013);
  std::this_thread::sleep_for(300ms);
  Client& later = connect();  // now `first` is idle long enough: it goes
  EXPECT_EQ(later.next().payload, "hello");
  const Frame evicted = first.next();
  EXPECT_EQ(evicted.op, 0x8);
  EXPECT_EQ(evicted.close_code(), 1008);
}

}  // namespace
}  // namespace stepmod::web
