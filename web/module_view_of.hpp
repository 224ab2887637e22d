#pragma once
// The console row of module type `T` (web/module_views.hpp), the same for every type: its five
// functions are ViewOf<T>'s, which the type's folder defines (module_types/mXXXX/view_XXXX.cpp,
// as `template <> UnitRegisters ViewOf<ModuleType::kXXXX>::registers(...)`). A module type adds
// no row of its own: module_types/CMakeLists.txt lists kViewOf<T> for every type, and includes the
// type's module_types/mXXXX/view_XXXX.hpp, which declares those definitions
// (STEPMOD_DECLARE_VIEW_OF).
#include <memory>
#include <nlohmann/json.hpp>

#include "web/module_views.hpp"

namespace stepmod::web {

template <ModuleType T>
struct ViewOf {
  static UnitRegisters registers(const ImageWords& in, unsigned unit);
  static nlohmann::json status_words(const ImageWords& in, unsigned unit);
  static nlohmann::json config_bits();
  static nlohmann::json config_of(const ImageWords& words);
  static std::unique_ptr<Controls> make_controls(plc::Port& port);
};

// Declares the explicit specializations of ViewOf<T>'s functions that type T's folder defines. An
// explicit specialization must be declared before its first use in every translation unit that
// uses it (kViewOf<T> below), or the program is ill-formed: each type's view_XXXX.hpp says this
// once, and its view_XXXX.cpp includes that header too, so that the definitions are checked
// against it.
#define STEPMOD_DECLARE_VIEW_OF(T)                                     \
  template <>                                                          \
  UnitRegisters ViewOf<T>::registers(const ImageWords&, unsigned);     \
  template <>                                                          \
  nlohmann::json ViewOf<T>::status_words(const ImageWords&, unsigned); \
  template <>                                                          \
  nlohmann::json ViewOf<T>::config_bits();                             \
  template <>                                                          \
  nlohmann::json ViewOf<T>::config_of(const ImageWords&);              \
  template <>                                                          \
  std::unique_ptr<Controls> ViewOf<T>::make_controls(plc::Port&)

template <ModuleType T>
inline constexpr ModuleView kViewOf{T,
                                    ViewOf<T>::registers,
                                    ViewOf<T>::status_words,
                                    ViewOf<T>::config_bits,
                                    ViewOf<T>::config_of,
                                    ViewOf<T>::make_controls};

}  // namespace stepmod::web
