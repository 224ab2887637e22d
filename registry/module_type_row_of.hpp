#pragma once
// The registry row of a module type (registry/module_registry.hpp), the same for every type: made
// from its personality class `M` (module_types/mXXXX/module_XXXX.hpp), which names its type
// (M::kShape, module/shared/axes_personality.hpp), its rules (M::kRules) and the error items only
// it has (M::kOwnItems, if any). A module type adds
// no row of its own: module_types/CMakeLists.txt lists kRowOf<M> for every type.
#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <string_view>
#include <utility>

#include "registry/module_registry.hpp"

namespace stepmod::registry {

namespace detail {

// The decimal digits of `n` (> 0), as the config file writes a module type ("3601").
template <unsigned N>
inline constexpr auto kDigits = [] {
  std::size_t count = 0;
  for (unsigned v = N; v != 0; v /= 10) ++count;
  std::array<char, 10> d{};
  unsigned v = N;
  for (std::size_t i = count; i-- > 0; v /= 10) d[i] = static_cast<char>('0' + v % 10);
  return std::pair{d, count};
}();

template <unsigned N>
constexpr std::string_view digits() noexcept {
  return {kDigits<N>.first.data(), kDigits<N>.second};
}

// A personality of class `M` over its axes' motion ports, in axis order.
template <typename M>
std::unique_ptr<module::Personality> make(module::AxisIo& io,
                                          std::span<planner::MotionPort* const> axes) {
  return [&]<std::size_t... I>(std::index_sequence<I...>) {
    return std::make_unique<M>(io, *axes[I]...);
  }(std::make_index_sequence<M::kAxes>{});
}

// The error items only type `M` has (M::kOwnItems), none when it names none.
template <typename M>
constexpr std::span<const module::axis::Item* const> own_items() noexcept {
  if constexpr (requires { M::kOwnItems; }) {
    return M::kOwnItems;
  } else {
    return {};
  }
}

}  // namespace detail

template <typename M>
inline constexpr ModuleTypeRow kRowOf{
    .type = M::kShape.type,
    .name = detail::digits<static_cast<unsigned>(M::kShape.type)>(),
    .shape = M::kShape,
    .rules = &M::kRules,
    .make_personality = detail::make<M>,
    .own_items = detail::own_items<M>(),
};

}  // namespace stepmod::registry
