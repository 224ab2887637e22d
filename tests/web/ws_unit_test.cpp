// stepmod-web's defences that need no daemon and no browser: the WebSocket framing and its
// limits, UTF-8, the host/origin names, the login rate limit, the request parser, and the hub's
// per-client queues (over socketpairs: a client that does not read never holds up another).
#include <gtest/gtest.h>

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>

#include "web/login_limiter.hpp"
#include "web/origin.hpp"
#include "web/requests.hpp"
#include "web/ws_frame.hpp"
#include "web/ws_hub.hpp"

namespace stepmod::web {
namespace {

using namespace std::chrono_literals;

// A client frame: masked with a key that is not zero, as a browser's.
std::string client_frame(std::uint8_t op, const std::string& payload, bool fin = true) {
  std::string f(1, static_cast<char>((fin ? 0x80 : 0) | op));
  const std::size_t n = payload.size();
  if (n < 126) {
    f.push_back(static_cast<char>(0x80 | n));
  } else if (n <= 0xFFFF) {
    f.push_back(static_cast<char>(0x80 | 126));
    f.push_back(static_cast<char>(n >> 8));
    f.push_back(static_cast<char>(n & 0xFF));
  } else {
    f.push_back(static_cast<char>(0x80 | 127));
    for (int s = 56; s >= 0; s -= 8) f.push_back(static_cast<char>((n >> s) & 0xFF));
  }
  const char key[4] = {0x12, 0x34, 0x56, 0x78};
  f.append(key, 4);
  for (std::size_t i = 0; i < n; ++i) f.push_back(static_cast<char>(payload[i] ^ key[i & 3]));
  return f;
}

WsEvent first_event(FrameReader& r, const std::string& bytes) {
  r.feed(bytes.data(), bytes.size());
  return r.next();
}

TEST(WsFrame, AMaskedTextFrameIsAMessage) {
  FrameReader r(64 * 1024);
  const WsEvent e = first_event(r, client_frame(0x1, R"({"op": "keepalive"})"));
  ASSERT_EQ(e.kind, WsEvent::Kind::kMessage);
  EXPECT_EQ(e.op, WsOp::kText);
  EXPECT_EQ(e.payload, R"({"op": "keepalive"})");
  EXPECT_FALSE(r.partial());
}

TEST(WsFrame, FragmentsMakeOneMessageAndControlFramesPassBetween) {
  FrameReader r(64 * 1024);
  r.feed(client_frame(0x1, "ab", false).data(), 8);
  EXPECT_EQ(r.next().kind, WsEvent::Kind::kNeedMore);
  EXPECT_TRUE(r.partial());
  const std::string rest = client_frame(0x9, "p") + client_frame(0x0, "cd");
  r.feed(rest.data(), rest.size());
  EXPECT_EQ(r.next().kind, WsEvent::Kind::kPing);
  const WsEvent e = r.next();
  ASSERT_EQ(e.kind, WsEvent::Kind::kMessage);
  EXPECT_EQ(e.payload, "abcd");
}

TEST(WsFrame, AnOversizedMessageIsRefusedFromItsHeaderAlone) {
  FrameReader r(64 * 1024);
  // Only the header of a 64 MB frame: refused before a byte of it is buffered.
  const std::string header = client_frame(0x1, std::string(70000, 'a')).substr(0, 14);
  std::string big(1, '\x81');
  big += std::string("\xFF\x00\x00\x00\x00\x04\x00\x00\x00", 9) + "mask";
  for (const std::string& h : {header, big}) {
    FrameReader rr(64 * 1024);
    const WsEvent e = first_event(rr, h);
    EXPECT_EQ(e.kind, WsEvent::Kind::kError);
    EXPECT_EQ(e.code, kCloseTooBig);
  }
  // Fragments that add up to more than the limit: the same.
  r.feed(client_frame(0x1, std::string(40000, 'a'), false).data(), 40008);
  EXPECT_EQ(r.next().kind, WsEvent::Kind::kNeedMore);
  const WsEvent e = first_event(r, client_frame(0x0, std::string(30000, 'b')).substr(0, 8));
  EXPECT_EQ(e.code, kCloseTooBig);
  EXPECT_EQ(FrameReader(10).room(), 24u);
}

TEST(WsFrame, ProtocolErrorsCloseWith1002) {
  std::string unmasked = ws_frame(WsOp::kText, "hi");
  std::string rsv = client_frame(0x1, "hi");
  rsv[0] = static_cast<char>(rsv[0] | 0x40);
  const std::string cases[] = {unmasked,
                               rsv,
                               client_frame(0x0, "x"),
                               client_frame(0x3, "x"),
                               client_frame(0x9, std::string(126, 'p')),
                               client_frame(0x8, "x")};
  for (const std::string& bytes : cases) {
    FrameReader r(64 * 1024);
    const WsEvent e = first_event(r, bytes);
    EXPECT_EQ(e.kind, WsEvent::Kind::kError);
    EXPECT_EQ(e.code, kCloseProtocol) << e.payload;
  }
}

TEST(WsFrame, CloseCarriesItsCodeAndServerFramesTheirLength) {
  FrameReader r(64 * 1024);
  const WsEvent e = first_event(r, client_frame(0x8, std::string("\x03\xE9", 2) + "bye"));
  ASSERT_EQ(e.kind, WsEvent::Kind::kClose);
  EXPECT_EQ(e.code, 1001);
  EXPECT_EQ(ws_frame(WsOp::kText, std::string(125, 'a')).size(), 127u);
  EXPECT_EQ(ws_frame(WsOp::kText, std::string(126, 'a')).substr(0, 4),
            std::string("\x81\x7E\x00\x7E", 4));
  EXPECT_EQ(ws_frame(WsOp::kText, std::string(70000, 'a')).size(), 70010u);
  EXPECT_EQ(ws_close_frame(1009, "too big"), std::string("\x88\x09\x03\xF1too big", 11));
}

TEST(WsFrame, Utf8IsCheckedStrictly) {
  EXPECT_TRUE(valid_utf8("plain"));
  EXPECT_TRUE(valid_utf8("\xE2\x82\xAC steps/s\xC2\xB2 \xF0\x9F\x98\x80"));
  for (const char* bad : {"\xFF", "\xC0\xAF", "\xE0\x80\xAF", "\xED\xA0\x80", "\xE2\x82",
                          "\xF4\x90\x80\x80", "\x80", "a\xC3"}) {
    EXPECT_FALSE(valid_utf8(bad)) << bad;
  }
}

TEST(WebHosts, OnlyTheConsolesOwnNamesAndOrigin) {
  const HostPolicy p("127.0.0.1", 8610, {"board.local", "10.0.0.5:9000", "fe80::1"});
  EXPECT_TRUE(p.host_ok("127.0.0.1:8610"));
  EXPECT_TRUE(p.host_ok("LOCALHOST:8610"));
  EXPECT_TRUE(p.host_ok("[::1]:8610"));
  EXPECT_TRUE(p.host_ok("board.local:8610"));
  EXPECT_TRUE(p.host_ok("10.0.0.5:9000"));
  EXPECT_TRUE(p.host_ok("[fe80::1]:8610"));
  EXPECT_FALSE(p.host_ok("127.0.0.1:8611"));
  EXPECT_FALSE(p.host_ok("evil.example:8610"));
  EXPECT_FALSE(p.host_ok("127.0.0.1"));
  EXPECT_FALSE(p.host_ok(nullptr));
  EXPECT_TRUE(p.origin_ok("http://127.0.0.1:8610", "127.0.0.1:8610"));
  EXPECT_FALSE(p.origin_ok("http://127.0.0.1:8629", "127.0.0.1:8610"));  // another port: a site
  EXPECT_FALSE(p.origin_ok("http://localhost:8610", "127.0.0.1:8610"));
  EXPECT_FALSE(p.origin_ok("null", "127.0.0.1:8610"));
  EXPECT_FALSE(p.origin_ok(nullptr, "127.0.0.1:8610"));
  EXPECT_FALSE(p.origin_ok("http://evil.example:8610", "evil.example:8610"));  // DNS rebinding
  EXPECT_TRUE(HostPolicy("0.0.0.0", 8610, {}).host_ok("127.0.0.1:8610"));      // an interface's
}

TEST(WebLogin, WrongTokensAreLimitedPerClient) {
  LoginLimiter l(3, 2s);
  const auto t0 = LoginLimiter::Clock::now();
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(l.wait_ms("10.0.0.1", t0), 0);
    l.failed("10.0.0.1", t0);
  }
  EXPECT_GT(l.wait_ms("10.0.0.1", t0), 1900);
  EXPECT_EQ(l.wait_ms("10.0.0.2", t0), 0);  // another client is not held up
  EXPECT_GT(l.wait_ms("10.0.0.1", t0 + 1s), 0);
  EXPECT_EQ(l.wait_ms("10.0.0.1", t0 + 2s), 0);  // one try per interval
  l.failed("10.0.0.1", t0 + 2s);
  EXPECT_GT(l.wait_ms("10.0.0.1", t0 + 2s), 0);
}

TEST(WebRequests, EveryBadMessageGetsAnErrorAndNoDumpThrows) {
  const struct {
    std::string msg;
    bool text;
    const char* why;
  } cases[] = {{"{\"op\": \"\xFF\"}", true, "UTF-8"}, {"not json", true, "not JSON"},
               {"[1]", true, "JSON object"},          {"{\"op\": 1}", true, "JSON object"},
               {"{}", true, "JSON object"},           {"{\"op\": \"take\"}", false, "binary"}};
  for (const auto& c : cases) {
    nlohmann::json req;
    nlohmann::json err;
    EXPECT_FALSE(parse_request(c.msg, c.text, req, err)) << c.msg;
    EXPECT_NE(safe_dump(err).find(c.why), std::string::npos) << safe_dump(err);
  }
  nlohmann::json req;
  nlohmann::json err;
  EXPECT_TRUE(parse_request(R"({"op": "take"})", true, req, err));
  EXPECT_EQ(req["op"], "take");
  EXPECT_EQ(safe_dump(nlohmann::json{{"text", "bad \xFF byte"}}),
            "{\"text\":\"bad \xEF\xBF\xBD byte\"}");
}

}  // namespace
}  // namespace stepmod::web
