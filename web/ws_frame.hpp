#pragma once
// The console's own WebSocket framing (RFC 6455), so that every limit is checked before a byte is
// buffered: civetweb 1.15 allocates and reads a whole frame of any announced length (up to 2 GB)
// before its data callback sees it, and retries a half-sent frame forever. FrameReader takes the
// bytes of one client connection and yields complete messages and control frames; a message
// whose frames announce more than `max_message` bytes is refused from its frame header alone
// (close 1009), before its payload is read.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace stepmod::web {

enum class WsOp : std::uint8_t {
  kContinuation = 0x0,
  kText = 0x1,
  kBinary = 0x2,
  kClose = 0x8,
  kPing = 0x9,
  kPong = 0xA,
};

// Close codes the console sends (RFC 6455 section 7.4.1).
inline constexpr std::uint16_t kCloseNormal = 1000;
inline constexpr std::uint16_t kCloseGoingAway = 1001;
inline constexpr std::uint16_t kCloseProtocol = 1002;
inline constexpr std::uint16_t kClosePolicy = 1008;
inline constexpr std::uint16_t kCloseTooBig = 1009;
inline constexpr std::uint16_t kCloseTryLater = 1013;

struct WsEvent {
  enum class Kind { kNeedMore, kMessage, kPing, kPong, kClose, kError };
  Kind kind = Kind::kNeedMore;
  WsOp op = WsOp::kText;   // kMessage: kText or kBinary
  std::string payload;     // the message, the ping's data, or the close frame's reason
  std::uint16_t code = 0;  // kClose: the peer's code (1005 when none); kError: ours to send
};

class FrameReader {
 public:
  explicit FrameReader(std::size_t max_message) : max_(max_message) {}

  // How many bytes the reader takes now (the caller reads at most this many from the socket).
  std::size_t room() const;
  void feed(const char* data, std::size_t n) { buf_.append(data, n); }
  // The next complete message or control frame from the bytes fed so far, kNeedMore, or
  // kError with the close code (after an error the connection must be closed: the frame
  // boundaries are lost).
  WsEvent next();
  // Whether a frame or a fragmented message has begun and is not complete.
  bool partial() const { return !buf_.empty() || in_message_; }

 private:
  WsEvent frame(std::uint8_t op, bool fin, std::string payload);

  std::size_t max_;
  std::string buf_;
  std::string message_;
  WsOp message_op_ = WsOp::kText;
  bool in_message_ = false;
};

// A server frame (unmasked, FIN set) carrying `payload`.
std::string ws_frame(WsOp op, std::string_view payload);
// A close frame with `code` and a short reason (cut to fit the 125-byte control frame limit).
std::string ws_close_frame(std::uint16_t code, std::string_view reason);
// Whether `s` is well-formed UTF-8 (no overlong forms, no surrogates, nothing above U+10FFFF).
bool valid_utf8(std::string_view s);

}  // namespace stepmod::web
