#pragma once
// The console row of module type `T` (web/module_views.hpp), the same for every type: its four
// functions are ViewOf<T>'s, which the type's folder defines (module_types/mXXXX/view_XXXX.cpp,
// as `template <> UnitRegisters ViewOf<ModuleType::kXXXX>::registers(...)`). A module type adds
// no row of its own: module_types/CMakeLists.txt lists kViewOf<T> for every type.
#include <memory>
#include <nlohmann/json.hpp>

#include "web/module_views.hpp"

namespace stepmod::web {

template <ModuleType T>
struct ViewOf {
  static UnitRegisters registers(const ImageWords& in, unsigned unit);
  static nlohmann::json status_words(const ImageWords& in, unsigned unit);
  static nlohmann::json config_bits();
  static std::unique_ptr<Controls> make_controls(plc::Port& port);
};

template <ModuleType T>
inline constexpr ModuleView kViewOf{T, ViewOf<T>::registers, ViewOf<T>::status_words,
                                    ViewOf<T>::config_bits, ViewOf<T>::make_controls};

}  // namespace stepmod::web
