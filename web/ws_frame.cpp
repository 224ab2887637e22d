#include "web/ws_frame.hpp"

namespace stepmod::web {
namespace {

constexpr std::size_t kMaxHeader = 14;  // 2 + 8 (64-bit length) + 4 (mask)

WsEvent error(std::uint16_t code, std::string why) {
  WsEvent e;
  e.kind = WsEvent::Kind::kError;
  e.code = code;
  e.payload = std::move(why);
  return e;
}

WsEvent event(WsEvent::Kind kind, std::string payload) {
  WsEvent e;
  e.kind = kind;
  e.payload = std::move(payload);
  return e;
}

bool known(std::uint8_t op) {
  return op <= 0x2 || (op >= 0x8 && op <= 0xA);
}

// A UTF-8 sequence's continuation bytes: 10xxxxxx.
bool cont(unsigned char c) {
  return (c & 0xC0) == 0x80;
}

}  // namespace

std::size_t FrameReader::room() const {
  const std::size_t cap = max_ + kMaxHeader;
  return buf_.size() >= cap ? 0 : cap - buf_.size();
}

WsEvent FrameReader::next() {
  for (;;) {
    if (buf_.size() < 2) return {};
    const auto b0 = static_cast<std::uint8_t>(buf_[0]);
    const auto b1 = static_cast<std::uint8_t>(buf_[1]);
    const bool fin = (b0 & 0x80) != 0;
    const std::uint8_t op = b0 & 0x0F;
    const bool control = (op & 0x8) != 0;
    if ((b0 & 0x70) != 0) return error(kCloseProtocol, "reserved bits set (no extension agreed)");
    if ((b1 & 0x80) == 0) return error(kCloseProtocol, "a client's frames must be masked");
    if (!known(op)) return error(kCloseProtocol, "unknown opcode " + std::to_string(op));
    std::uint64_t len = b1 & 0x7F;
    if (control && (!fin || len > 125)) {
      return error(kCloseProtocol, "a control frame must be whole and at most 125 bytes");
    }
    std::size_t hdr = 2;
    if (len == 126 || len == 127) {
      const std::size_t ext = len == 126 ? 2 : 8;
      if (buf_.size() < 2 + ext) return {};
      len = 0;
      for (std::size_t i = 0; i < ext; ++i)
        len = (len << 8) | static_cast<std::uint8_t>(buf_[2 + i]);
      hdr += ext;
    }
    if (!control) {
      if (op == 0 && !in_message_) return error(kCloseProtocol, "a continuation without a message");
      if (op != 0 && in_message_)
        return error(kCloseProtocol, "a new message inside a fragmented one");
      const std::size_t already = op == 0 ? message_.size() : 0;
      if (len > max_ - already) {
        return error(kCloseTooBig, "a message larger than " + std::to_string(max_) + " bytes");
      }
    }
    hdr += 4;  // the mask key
    if (buf_.size() < hdr + len) return {};
    std::string payload = buf_.substr(hdr, static_cast<std::size_t>(len));
    for (std::size_t i = 0; i < payload.size(); ++i) payload[i] ^= buf_[hdr - 4 + (i & 3)];
    buf_.erase(0, hdr + static_cast<std::size_t>(len));
    WsEvent e = frame(op, fin, std::move(payload));
    if (e.kind != WsEvent::Kind::kNeedMore) return e;  // else a fragment: go on
  }
}

WsEvent FrameReader::frame(std::uint8_t op, bool fin, std::string payload) {
  switch (static_cast<WsOp>(op)) {
    case WsOp::kPing:
      return event(WsEvent::Kind::kPing, std::move(payload));
    case WsOp::kPong:
      return event(WsEvent::Kind::kPong, std::move(payload));
    case WsOp::kClose: {
      if (payload.size() == 1) return error(kCloseProtocol, "a close frame of 1 byte");
      WsEvent e = event(WsEvent::Kind::kClose, payload.size() >= 2 ? payload.substr(2) : "");
      e.code = payload.size() >= 2
                   ? static_cast<std::uint16_t>((static_cast<std::uint8_t>(payload[0]) << 8) |
                                                static_cast<std::uint8_t>(payload[1]))
                   : 1005;
      return e;
    }
    case WsOp::kContinuation:
      message_ += payload;
      break;
    default:  // text or binary: the first frame of a message
      message_ = std::move(payload);
      message_op_ = static_cast<WsOp>(op);
      in_message_ = true;
      break;
  }
  if (!fin) return {};
  in_message_ = false;
  WsEvent e = event(WsEvent::Kind::kMessage, std::move(message_));
  e.op = message_op_;
  message_.clear();
  return e;
}

std::string ws_frame(WsOp op, std::string_view payload) {
  std::string f;
  f.reserve(payload.size() + 10);
  f.push_back(static_cast<char>(0x80 | static_cast<std::uint8_t>(op)));
  const std::uint64_t n = payload.size();
  if (n < 126) {
    f.push_back(static_cast<char>(n));
  } else if (n <= 0xFFFF) {
    f.push_back(126);
    for (int s = 8; s >= 0; s -= 8) f.push_back(static_cast<char>((n >> s) & 0xFF));
  } else {
    f.push_back(127);
    for (int s = 56; s >= 0; s -= 8) f.push_back(static_cast<char>((n >> s) & 0xFF));
  }
  f.append(payload);
  return f;
}

std::string ws_close_frame(std::uint16_t code, std::string_view reason) {
  std::string p;
  p.push_back(static_cast<char>(code >> 8));
  p.push_back(static_cast<char>(code & 0xFF));
  p.append(reason.substr(0, 123));
  return ws_frame(WsOp::kClose, p);
}

bool valid_utf8(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    std::size_t n = 0;
    std::uint32_t cp = 0;
    if (c < 0x80) {
      ++i;
      continue;
    } else if ((c & 0xE0) == 0xC0) {
      n = 1, cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      n = 2, cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      n = 3, cp = c & 0x07;
    } else {
      return false;
    }
    if (i + n >= s.size()) return false;  // the sequence is cut short
    for (std::size_t k = 1; k <= n; ++k) {
      const auto d = static_cast<unsigned char>(s[i + k]);
      if (!cont(d)) return false;
      cp = (cp << 6) | (d & 0x3F);
    }
    static constexpr std::uint32_t kMin[] = {0, 0x80, 0x800, 0x10000};
    if (cp < kMin[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += n + 1;
  }
  return true;
}

}  // namespace stepmod::web
