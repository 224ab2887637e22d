#pragma once
// The EtherNet/IP encapsulation header (docs/ethernetip-design.md, "Encapsulation"), on TCP and
// UDP 44818. No sockets here: every rule is unit-tested on bytes.
//
//   command u16 | length u16 (bytes after the header) | session u32 | status u32 |
//   sender context [8] (echoed in the reply) | options u32 (shall be 0)
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "fieldbus/enip/wire.hpp"

namespace stepmod::enip {

inline constexpr std::size_t kEncapHeaderBytes = 24;
// The largest frame we accept or send. Our largest request, a Large_Forward_Open inside an
// Unconnected_Send with a keyed path, is under 150 bytes; the spec's 65,511 would only let a
// peer make us buffer for a frame we could not use.
inline constexpr std::size_t kEncapMaxFrame = 600;
inline constexpr std::size_t kEncapMaxData = kEncapMaxFrame - kEncapHeaderBytes;

namespace encap_cmd {
inline constexpr std::uint16_t kNop = 0x0000;
inline constexpr std::uint16_t kListServices = 0x0004;
inline constexpr std::uint16_t kListIdentity = 0x0063;
inline constexpr std::uint16_t kListInterfaces = 0x0064;
inline constexpr std::uint16_t kRegisterSession = 0x0065;
inline constexpr std::uint16_t kUnRegisterSession = 0x0066;
inline constexpr std::uint16_t kSendRRData = 0x006F;
inline constexpr std::uint16_t kSendUnitData = 0x0070;
}  // namespace encap_cmd

// The status field of a reply.
enum class EncapStatus : std::uint32_t {
  kSuccess = 0x0000,
  kInvalidCommand = 0x0001,      // unknown command, or RegisterSession twice on one connection
  kInsufficientMemory = 0x0002,  // no free session
  kIncorrectData = 0x0003,
  kInvalidSession = 0x0064,
  kInvalidLength = 0x0065,
  kUnsupportedProtocol = 0x0069,
};

struct EncapHeader {
  std::uint16_t command = 0;
  std::uint16_t length = 0;
  std::uint32_t session = 0;
  std::uint32_t status = 0;
  std::array<std::uint8_t, 8> context{};
  std::uint32_t options = 0;
};

struct EncapFrame {
  EncapHeader header;
  std::span<const std::uint8_t> data;  // `header.length` bytes of command-specific data
  std::size_t size = 0;                // bytes of the whole frame (header + data)
};

enum class EncapParse {
  kIncomplete,  // TCP: wait for more bytes (on UDP: a truncated datagram, drop it)
  kFrame,       // a whole frame, in `frame`
  kDiscard,     // a whole frame the spec says to ignore (options or status not 0): skip
                // `frame.size` bytes, send nothing
  kTooLong,     // length beyond kEncapMaxData: its end cannot be trusted; close (TCP) or drop
};

// Looks at the front of `buf` (a TCP connection's received bytes, or one UDP datagram).
EncapParse parse_encap(std::span<const std::uint8_t> buf, EncapFrame& frame) noexcept;

// A command this adapter knows (an unknown one gets kInvalidCommand on TCP).
bool is_known_command(std::uint16_t command) noexcept;
// Commands served over UDP 44818: ListIdentity, ListServices, ListInterfaces (others dropped).
bool allowed_on_udp(std::uint16_t command) noexcept;

// Writes the header of the reply to `request`: the same command and context, `data_length`
// bytes to follow, `session` and `status`, options 0.
void put_reply_header(Writer& w, const EncapHeader& request, std::uint16_t data_length,
                      std::uint32_t session, EncapStatus status) noexcept;

// A reply that is a header alone (an error status, no data); returns its size, 0 when `out` is
// too small.
std::size_t encode_status_reply(std::span<std::uint8_t> out, const EncapHeader& request,
                                EncapStatus status) noexcept;

}  // namespace stepmod::enip
