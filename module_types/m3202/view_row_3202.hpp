#pragma once
// The 3202's row of the console (web/module_views.hpp): its functions in view_3202.cpp.
#include <memory>
#include <nlohmann/json.hpp>

#include "web/module_views.hpp"

namespace stepmod::web {

namespace view3202 {
UnitRegisters registers(const ImageWords& in, unsigned unit);
nlohmann::json status_words(const ImageWords& in, unsigned unit);
nlohmann::json config_bits();
std::unique_ptr<Controls> make_controls(plc::Port& port);
}  // namespace view3202

inline constexpr ModuleView kView3202{ModuleType::k3202, view3202::registers,
                                      view3202::status_words, view3202::config_bits,
                                      view3202::make_controls};

}  // namespace stepmod::web
