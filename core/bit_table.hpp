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

// A word type's field mask and reserved bits (the bits of the word no field of a table names:
// the manual's reserved bits), as callables so that one definition serves every word type.
template <typename Word>
struct FieldOf {
  template <typename Table>
  consteval Word operator()(const Table& t, std::string_view name) const {
    return mask_of<Word>(t, name);
  }
};
template <typename Word>
struct UnnamedOf {
  template <typename Table>
  consteval Word operator()(const Table& t) const {
    Word named = 0;
    for (const NamedBit& b : t) named = static_cast<Word>(named | ((1ull << b.width) - 1) << b.bit);
    return static_cast<Word>(~named);
  }
};

// The dialects' constants are written with these two: the 16-bit modules' words (3601, 3602) and
// the 32-bit modules' DINTs (3202).
namespace bits16 {
inline constexpr FieldOf<std::uint16_t> field{};
inline constexpr UnnamedOf<std::uint16_t> unnamed{};
}  // namespace bits16
namespace bits32 {
inline constexpr FieldOf<std::uint32_t> field{};
inline constexpr UnnamedOf<std::uint32_t> unnamed{};
}  // namespace bits32

}  // namespace stepmod
