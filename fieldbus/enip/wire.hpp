#pragma once
// Little-endian reading and writing over caller-owned buffers, for the EtherNet/IP parsers
// (docs/ethernetip-design.md). CIP carries every integer little-endian; only the socket address
// of ListIdentity is big-endian (it is a struct sockaddr_in on the wire).
//
// A read past the end does not read: it returns 0, empty spans from then on, and clears ok().
// A parser reads its fields and checks ok() once, so a short packet can never be read beyond
// its end whichever field is the first to run out. A write past the end likewise writes nothing
// and clears ok(): the caller's reply is then dropped, never truncated.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace stepmod::enip {

// What Reader and Writer share: the position in a buffer of `size` bytes and the ok flag, which
// the first access that does not fit clears for good.
class WireCursor {
 public:
  bool ok() const noexcept { return ok_; }

 protected:
  explicit WireCursor(std::size_t size) noexcept : size_(size) {}
  // Whether `n` more bytes fit (and ok() still holds); the caller then advances pos_ itself.
  bool has(std::size_t n) noexcept {
    if (ok_ && n <= size_ - pos_) return true;
    ok_ = false;
    return false;
  }
  std::size_t size_;
  std::size_t pos_ = 0;
  bool ok_ = true;
};

class Reader : public WireCursor {
 public:
  explicit Reader(std::span<const std::uint8_t> buf) noexcept : WireCursor(buf.size()), buf_(buf) {}

  std::uint8_t u8() noexcept { return has(1) ? buf_[pos_++] : 0; }
  std::uint16_t u16() noexcept {
    if (!has(2)) return 0;
    const auto v = static_cast<std::uint16_t>(buf_[pos_] | (buf_[pos_ + 1] << 8));
    pos_ += 2;
    return v;
  }
  std::uint32_t u32() noexcept {
    if (!has(4)) return 0;
    const std::uint32_t lo = u16();
    const std::uint32_t hi = u16();
    return lo | (hi << 16);
  }
  // The next `n` bytes (empty, and !ok(), when fewer remain).
  std::span<const std::uint8_t> bytes(std::size_t n) noexcept {
    if (!has(n)) return {};
    const auto s = buf_.subspan(pos_, n);
    pos_ += n;
    return s;
  }
  void skip(std::size_t n) noexcept { (void)bytes(n); }

  std::size_t pos() const noexcept { return pos_; }
  std::size_t remaining() const noexcept { return size_ - pos_; }
  std::span<const std::uint8_t> rest() const noexcept { return buf_.subspan(pos_); }

 private:
  std::span<const std::uint8_t> buf_;
};

class Writer : public WireCursor {
 public:
  explicit Writer(std::span<std::uint8_t> out) noexcept : WireCursor(out.size()), out_(out) {}

  void u8(std::uint8_t v) noexcept {
    if (has(1)) put(v);
  }
  // Multi-byte values are written whole or not at all (has() first, then the bytes).
  void u16(std::uint16_t v) noexcept {
    if (!has(2)) return;
    put(static_cast<std::uint8_t>(v & 0xFFu));
    put(static_cast<std::uint8_t>(v >> 8));
  }
  void u32(std::uint32_t v) noexcept {
    if (!has(4)) return;
    u16(static_cast<std::uint16_t>(v & 0xFFFFu));
    u16(static_cast<std::uint16_t>(v >> 16));
  }
  void be16(std::uint16_t v) noexcept {
    if (!has(2)) return;
    put(static_cast<std::uint8_t>(v >> 8));
    put(static_cast<std::uint8_t>(v & 0xFFu));
  }
  void be32(std::uint32_t v) noexcept {
    if (!has(4)) return;
    be16(static_cast<std::uint16_t>(v >> 16));
    be16(static_cast<std::uint16_t>(v & 0xFFFFu));
  }
  void bytes(std::span<const std::uint8_t> b) noexcept {
    if (!has(b.size())) return;
    for (const std::uint8_t v : b) out_[pos_++] = v;
  }
  // CIP SHORT_STRING: USINT length, the characters (at most 255, as its length says).
  void short_string(std::string_view s) noexcept {
    if (s.size() > 0xFF || !has(1 + s.size())) {
      ok_ = false;
      return;
    }
    u8(static_cast<std::uint8_t>(s.size()));
    for (const char c : s) put(static_cast<std::uint8_t>(c));
  }
  void zeros(std::size_t n) noexcept {
    if (!has(n)) return;
    for (std::size_t i = 0; i < n; ++i) out_[pos_++] = 0;
  }
  // Overwrites the u16 at `at` (a length field written before its contents were known).
  void patch_u16(std::size_t at, std::uint16_t v) noexcept {
    if (!ok_ || at + 2 > pos_) {
      ok_ = false;
      return;
    }
    out_[at] = static_cast<std::uint8_t>(v & 0xFFu);
    out_[at + 1] = static_cast<std::uint8_t>(v >> 8);
  }

  std::size_t size() const noexcept { return pos_; }
  std::span<const std::uint8_t> written() const noexcept { return out_.first(pos_); }

 private:
  void put(std::uint8_t v) noexcept { out_[pos_++] = v; }  // after has()
  std::span<std::uint8_t> out_;
};

}  // namespace stepmod::enip
