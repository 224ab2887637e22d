#pragma once
// The name of an enumerator from a table written in enumerator order, for enums whose values are
// dense from a first value (0 unless said): one row per enumerator instead of a switch of
// case/return pairs. A value outside the table reads "?". The tables' sizes are checked against
// the enums' counts where they are written (static_assert).
#include <array>
#include <cstddef>
#include <string_view>

namespace stepmod {

template <typename Enum, std::size_t N>
constexpr std::string_view enum_name(Enum e, const std::array<std::string_view, N>& names,
                                     std::size_t first = 0) noexcept {
  const auto i = static_cast<std::size_t>(e);
  return i >= first && i - first < N ? names[i - first] : std::string_view("?");
}

}  // namespace stepmod
