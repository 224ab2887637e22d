#pragma once
// The 3602's row of the console (web/module_views.hpp): its functions in view_3602.cpp.
#include <memory>
#include <nlohmann/json.hpp>

#include "web/module_views.hpp"

namespace stepmod::web {

namespace view3602 {
UnitRegisters registers(const ImageWords& in, unsigned unit);
nlohmann::json status_words(const ImageWords& in, unsigned unit);
nlohmann::json config_bits();
std::unique_ptr<Controls> make_controls(plc::Port& port);
}  // namespace view3602

inline constexpr ModuleView kView3602{ModuleType::k3602, view3602::registers,
                                      view3602::status_words, view3602::config_bits,
                                      view3602::make_controls};

}  // namespace stepmod::web
