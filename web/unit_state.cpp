#include "web/unit_state.hpp"

#include <string>

#include "web/module_views.hpp"
#include "web/sim_inputs.hpp"

namespace stepmod::web {
namespace {

nlohmann::json config_json(ModuleType type, const stepmod_unit_state_t& s) {
  if (s.config_seq == 0) return nullptr;
  ImageWords w;
  for (unsigned i = 0; i < STEPMOD_UNIT_CONFIG_WORDS; ++i) w.w[i] = s.config_words[i];
  nlohmann::json j = view_of(type).config_of(w);
  j["seq"] = s.config_seq;
  return j;
}

nlohmann::json inputs_json(std::uint32_t bits) {
  nlohmann::json lines = nlohmann::json::array();
  const auto bit = [bits](unsigned shift, unsigned i) { return ((bits >> (shift + i)) & 1u) != 0; };
  for (unsigned i = 0; i < kInputNames.size(); ++i) {
    lines.push_back({{"name", std::string(kInputNames[i])},
                     {"wired", bit(STEPMOD_UNIT_WIRED_SHIFT, i)},
                     {"used", bit(STEPMOD_UNIT_USED_SHIFT, i)},
                     {"level", bit(STEPMOD_UNIT_LEVELS_SHIFT, i)},
                     {"active", bit(STEPMOD_UNIT_ACTIVE_SHIFT, i)}});
  }
  return lines;
}

}  // namespace

nlohmann::json unit_state_json(ModuleType type, const std::optional<stepmod_unit_state_t>& s) {
  if (!s) return nullptr;
  return {{"config", config_json(type, *s)},
          {"inputs", inputs_json(s->inputs)},
          {"enable",
           {{"wired", (s->drive_enable & STEPMOD_UNIT_ENABLE_WIRED) != 0},
            {"asserted", (s->drive_enable & STEPMOD_UNIT_ENABLE_ASSERTED) != 0}}}};
}

}  // namespace stepmod::web
