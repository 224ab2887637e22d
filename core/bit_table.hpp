#pragma once
// A named bit (or bit field) of a module word, as a manual's table lists it. Each module's
// dialect writes its words down once as constexpr tables of these (module_types/m3601/words_3601.hpp,
// ...); the code's bit constants are looked up in the tables by name at compile time, and
// stepmodctl shows the same names. Header-only, no dependencies: the PLC side includes it.
#include <cstdint>
#include <span>
#include <string_view>

namespace stepmod {

struct NamedBit {
  unsigned bit;           // lowest bit of the field
  std::string_view name;  // as in the manual
  unsigned width = 1;     // bits in the field (2 for the 3602's CW/CCW input function)
};

// A word's field table, in bit order.
using BitTable = std::span<const NamedBit>;

// The mask of the field called `name` in `table`. Used in constant expressions only: a name
// that is not in the table does not compile (the throw is not a constant expression).
template <typename Word, typename Table>
consteval Word mask_of(const Table& table, std::string_view name) {
  for (const NamedBit& b : table) {
    if (b.name == name) return static_cast<Word>(((1ull << b.width) - 1) << b.bit);
  }
  throw "mask_of: no field of this name in the table";
}

// The word index called `name` in a table of word indices.
struct NamedWord {
  unsigned index;
  std::string_view name;
};

template <typename Table>
consteval unsigned index_of(const Table& table, std::string_view name) {
  for (const NamedWord& w : table) {
    if (w.name == name) return w.index;
  }
  throw "index_of: no word of this name in the table";
}

// The lowest bit of the field called `name` (a shift for a run of fields in manual order).
template <typename Table>
consteval unsigned bit_of(const Table& table, std::string_view name) {
  for (const NamedBit& b : table) {
    if (b.name == name) return b.bit;
  }
  throw "bit_of: no field of this name in the table";
}

// The 16-bit modules' words (3601, 3602): their dialects' constants are written with these two.
namespace bits16 {
template <typename Table>
consteval std::uint16_t field(const Table& t, std::string_view name) {
  return mask_of<std::uint16_t>(t, name);
}
// The bits of a 16-bit word that no field of `t` names: the manual's reserved bits.
template <typename Table>
consteval std::uint16_t unnamed(const Table& t) {
  std::uint16_t named = 0;
  for (const NamedBit& b : t) {
    named = static_cast<std::uint16_t>(named | ((1u << b.width) - 1) << b.bit);
  }
  return static_cast<std::uint16_t>(~named);
}
}  // namespace bits16

// The 32-bit modules' words (3202): the same two, over DINTs.
namespace bits32 {
template <typename Table>
consteval std::uint32_t field(const Table& t, std::string_view name) {
  return mask_of<std::uint32_t>(t, name);
}
template <typename Table>
consteval std::uint32_t unnamed(const Table& t) {
  std::uint32_t named = 0;
  for (const NamedBit& b : t) named |= static_cast<std::uint32_t>(((1ull << b.width) - 1) << b.bit);
  return ~named;
}
}  // namespace bits32

}  // namespace stepmod
