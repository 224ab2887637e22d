#pragma once
// T→O production of one class 1 connection (docs/ethernetip-design.md, "Class 1 I/O"): the
// packet due now with the input words, its encapsulation sequence counting packets from 1 (a
// scanner takes only a sequence newer than the last it saw, starting from 0), its CIP sequence
// count +1 whenever the words differ from those this connection last carried. No sockets.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "fieldbus/enip/connection_table.hpp"

namespace stepmod::enip {

// The largest assembly (the 3202's 16 DINTs).
inline constexpr std::size_t kMaxAssemblyBytes = 64;
// A T→O packet: the CPF of two items (20 bytes) and the words.
inline constexpr std::size_t kMaxIoPacketBytes = 20 + kMaxAssemblyBytes;

class TtoProducer {
 public:
  // Writes the packet of `c`, the connection in slot `slot` of IoConnections::slots(), carrying
  // `input` (at most kMaxAssemblyBytes), and advances `c`'s schedule; the size, 0 when nothing
  // could be written (the schedule still advances: a bad tick never makes a burst).
  std::size_t produce(std::size_t slot, IoConnection& c, std::span<const std::uint8_t> input,
                      std::int64_t now_ns, std::span<std::uint8_t> out) noexcept;

 private:
  struct Last {
    std::uint32_t ot_id = 0;  // the connection this state is of (ids are never reused while open)
    std::uint16_t cip_sequence = 0;
    std::size_t size = 0;
    std::array<std::uint8_t, kMaxAssemblyBytes> data{};
  };
  std::array<Last, kMaxIoConnections> last_{};
};

}  // namespace stepmod::enip
