#pragma once
// The 3601's row of the console (web/module_views.hpp): its functions in view_3601.cpp.
#include <memory>
#include <nlohmann/json.hpp>

#include "web/module_views.hpp"

namespace stepmod::web {

namespace view3601 {
UnitRegisters registers(const ImageWords& in, unsigned unit);
nlohmann::json status_words(const ImageWords& in, unsigned unit);
nlohmann::json config_bits();
std::unique_ptr<Controls> make_controls(plc::Port& port);
}  // namespace view3601

inline constexpr ModuleView kView3601{ModuleType::k3601, view3601::registers,
                                      view3601::status_words, view3601::config_bits,
                                      view3601::make_controls};

}  // namespace stepmod::web
