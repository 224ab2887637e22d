#pragma once
// The common packet format (CPF) that SendRRData, SendUnitData, ListIdentity and class 1 I/O
// carry: an item count, then items of (type u16, length u16, data). Parsed into a fixed array of
// views into the packet: nothing is copied or allocated.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "fieldbus/enip/wire.hpp"

namespace stepmod::enip {

namespace cpf_item {
inline constexpr std::uint16_t kNullAddress = 0x0000;
inline constexpr std::uint16_t kListIdentity = 0x000C;
inline constexpr std::uint16_t kConnectedAddress = 0x00A1;
inline constexpr std::uint16_t kConnectedData = 0x00B1;
inline constexpr std::uint16_t kUnconnectedData = 0x00B2;
inline constexpr std::uint16_t kListServices = 0x0100;
inline constexpr std::uint16_t kSockaddrOtoT = 0x8000;
inline constexpr std::uint16_t kSockaddrTtoO = 0x8001;
inline constexpr std::uint16_t kSequencedAddress = 0x8002;
}  // namespace cpf_item

// An address item, a data item and the two socket address items of a Forward_Open: no packet
// we serve has more.
inline constexpr std::size_t kCpfMaxItems = 4;

struct CpfItem {
  std::uint16_t type = 0;
  std::span<const std::uint8_t> data;
};

struct Cpf {
  std::array<CpfItem, kCpfMaxItems> items{};
  std::size_t count = 0;
};

enum class CpfParse {
  kOk,
  kTruncated,      // the count or an item runs past the end of the packet
  kTooManyItems,   // more than kCpfMaxItems (or none)
  kTrailingBytes,  // bytes after the last item
};

// `buf` is exactly the CPF (the packet's end is the CPF's end).
CpfParse parse_cpf(std::span<const std::uint8_t> buf, Cpf& cpf) noexcept;

// SendRRData and SendUnitData: interface handle u32 (0 = CIP), timeout u16, then a CPF.
struct SendData {
  std::uint32_t interface_handle = 0;
  std::uint16_t timeout = 0;
  Cpf cpf;
};
CpfParse parse_send_data(std::span<const std::uint8_t> buf, SendData& out) noexcept;

// Writing: an item whose length is patched when it is ended.
class CpfItemWriter {
 public:
  CpfItemWriter(Writer& w, std::uint16_t type) noexcept;
  // Patches the item's length with the bytes written since the constructor.
  void end() noexcept;

 private:
  Writer& w_;
  std::size_t length_at_;
};

// A whole item from bytes already at hand.
void put_item(Writer& w, std::uint16_t type, std::span<const std::uint8_t> data) noexcept;

}  // namespace stepmod::enip
