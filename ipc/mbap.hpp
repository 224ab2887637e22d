#pragma once
// Modbus/TCP framing (MBAP header + PDU), checked as the Modbus/TCP specification (V1.0b)
// defines it: no sockets here (ipc/modbus_server does the TCP side), so every rule is
// unit-tested on bytes.
//
//   transaction id (2) | protocol id (2) = 0 | length (2) = 1 + PDU bytes | unit id (1) | PDU
//
// A frame is exactly what its length field says: 2 <= length <= 254 (a PDU of 1..253 bytes).
// A function code >= 0x80 is an exception code, which a client never sends.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "ipc/modbus_map.hpp"

namespace stepmod::ipc {

inline constexpr std::size_t kMbapHeaderBytes = 7;
inline constexpr std::size_t kMbapMaxLength = 254;  // unit id + a 253-byte PDU
inline constexpr std::size_t kMbapMaxAdu = 6 + kMbapMaxLength;

struct MbapFrame {
  std::uint16_t transaction = 0;
  std::uint8_t unit = 0;
  std::span<const std::uint8_t> pdu;  // function code and data
  std::size_t size = 0;               // bytes of the whole frame
};

enum class MbapStatus {
  kIncomplete,   // not yet the whole frame its length field announces: wait for more bytes
  kFrame,        // a whole frame, in `frame`
  kBadProtocol,  // protocol id not 0: not Modbus; close the connection
  kBadLength,    // length field outside 2..254: the frame's end is unknown; close
  kBadFunction,  // function code >= 0x80: close (never an exception reply to an exception)
};

// Looks at the front of `buf` (a connection's received bytes).
MbapStatus parse_mbap(std::span<const std::uint8_t> buf, MbapFrame& frame) noexcept;

// Appends the response to `request` to `out`: the values read, the echo of a write, or the
// exception of `r`.
void append_response(std::vector<std::uint8_t>& out, const MbapFrame& request,
                     const ModbusResult& r);
// Appends an exception response (function | 0x80, code).
void append_exception(std::vector<std::uint8_t>& out, const MbapFrame& request,
                      ModbusException code);

}  // namespace stepmod::ipc
