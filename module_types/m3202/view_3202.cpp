// The 3202 on the console: two channels, one status DINT and one configuration DINT each.
#include "module_types/m3202/view_3202.hpp"
#include "module_types/m3202/plc_3202.hpp"
#include "module_types/m3202/plc_status_3202.hpp"
#include "module_types/m3202/words_3202.hpp"
#include "web/bit_json.hpp"
#include "web/two_unit_controls.hpp"

namespace stepmod::web {
namespace {

// The 3202's two channels: steps/s^2 rates, one configuration DINT (bit 31, the mode, is added
// by plc/), jog = the manual-move bits held.
class Controls3202 final : public TwoUnitControls<plc::Plc3202> {
 public:
  using TwoUnitControls::TwoUnitControls;

 protected:
  std::uint32_t config_bits(const nlohmann::json& req) const override {
    return static_cast<std::uint32_t>(request_int(req, "bits", 0, 0x7FFFFFFF));
  }
  plc::Outcome configure(unsigned u, std::uint32_t bits, std::int32_t vs, std::int16_t) override {
    return plc_.configure(u, bits, vs);
  }
};

}  // namespace

template <>
UnitRegisters ViewOf<ModuleType::k3202>::registers(const ImageWords& in, unsigned unit) {
  const auto s = plc::m3202::decode_status(in, unit);
  return {s.position, s.encoder, s.capture};
}

template <>
nlohmann::json ViewOf<ModuleType::k3202>::status_words(const ImageWords& in, unsigned unit) {
  const auto s = plc::m3202::decode_status(in, unit);
  return nlohmann::json::array({word_json("Status", s.word, words::m3202::kStatusBits)});
}

// One configuration DINT per channel: the page sends it whole ("bits").
template <>
nlohmann::json ViewOf<ModuleType::k3202>::config_bits() {
  return {{"dint", table_json(words::m3202::kConfigBits)}};
}

template <>
nlohmann::json ViewOf<ModuleType::k3202>::config_of(const ImageWords& w) {
  namespace ow = words::m3202::out_word;
  return {{"bits", static_cast<std::uint32_t>(w.w[ow::kCommand])},
          {"start_speed", w.w[ow::kTarget]}};
}

template <>
std::unique_ptr<Controls> ViewOf<ModuleType::k3202>::make_controls(plc::Port& port) {
  return std::make_unique<Controls3202>(port);
}

}  // namespace stepmod::web
