#pragma once
// Class 1 I/O packets on UDP 2222 (docs/ethernetip-design.md, "Class 1 I/O"): a CPF of a
// sequenced address item and a connected data item. O→T is parsed and checked against its
// connection's shape; T→O is written. No sockets and no connection state here.
//
//   0x8002 (8): connection id u32, encapsulation sequence u32
//   0x00B1 (n): CIP sequence count u16, [run/idle header u32: O→T of an owner], the words
#include <cstddef>
#include <cstdint>
#include <span>

namespace stepmod::enip {

// What an O→T packet of one connection must look like.
struct IoShape {
  bool run_idle_header = true;  // an owner's O→T carries it; a heartbeat does not
  std::size_t data_bytes = 0;   // the assembly's size (0 for a heartbeat)
};

struct IoPacket {
  std::uint32_t connection_id = 0;
  std::uint32_t encap_sequence = 0;
  std::uint16_t cip_sequence = 0;
  bool run = false;  // the run/idle header's bit 0 (false without a header)
  std::span<const std::uint8_t> data;
};

enum class IoParse {
  kOk,
  kMalformed,  // not a CPF of exactly a sequenced address and a connected data item
  kWrongSize,  // the data is not the connection's size
};

IoParse parse_o_to_t(std::span<const std::uint8_t> datagram, const IoShape& shape,
                     IoPacket& out) noexcept;

// Writes a T→O packet with `data` (no run/idle header); its size, 0 when `out` is too small.
std::size_t encode_t_to_o(std::span<std::uint8_t> out, std::uint32_t connection_id,
                          std::uint32_t encap_sequence, std::uint16_t cip_sequence,
                          std::span<const std::uint8_t> data) noexcept;

// Serial number arithmetic on the 32-bit encapsulation sequence: `seq` is newer than `last`
// when it is ahead by less than half the range (so the count may wrap).
constexpr bool sequence_newer(std::uint32_t seq, std::uint32_t last) noexcept {
  return seq != last && static_cast<std::uint32_t>(seq - last) < 0x80000000u;
}

}  // namespace stepmod::enip
