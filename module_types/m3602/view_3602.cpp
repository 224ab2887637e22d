// The 3602 on the console: two axes, MSW/LSW status and configuration words, no encoder input.
#include <stdexcept>

#include "module_types/m3602/plc_3602.hpp"
#include "module_types/m3602/plc_interp_3602.hpp"
#include "module_types/m3602/plc_status_3602.hpp"
#include "module_types/m3602/view_3602.hpp"
#include "module_types/m3602/words_3602.hpp"
#include "web/bit_json.hpp"
#include "web/path_request.hpp"
#include "web/two_unit_controls.hpp"

namespace stepmod::web {
namespace {

class Controls3602 final : public TwoUnitControls<plc::Plc3602> {
 public:
  explicit Controls3602(plc::Port& port) : TwoUnitControls(port), interp_(port) {}

 protected:
  // The interpolated moves (on axis 1: both axes) and the general-purpose output.
  std::optional<plc::Outcome> module_command(const std::string& cmd, unsigned u,
                                             const nlohmann::json& req) override {
    if (cmd == "path") {
      if (u != 0) throw std::invalid_argument("a path is commanded on axis 1 (unit 0)");
      return interp_.move(path_request(req));
    }
    if (cmd == "gpo") return plc_.set_gpo(u, request_bool(req, "on"));
    return std::nullopt;
  }

  plc::Outcome configure(unsigned u, std::uint32_t bits, std::int32_t vs,
                         std::int16_t homing_timeout_s) override {
    return plc_.configure(u, static_cast<std::uint16_t>(bits >> 16),
                          static_cast<std::uint16_t>(bits & 0xFFFFu), vs, homing_timeout_s);
  }
  bool has_homing_timeout() const override { return true; }

 private:
  plc::Interp3602 interp_;
};

}  // namespace

template <>
UnitRegisters ViewOf<ModuleType::k3602>::registers(const ImageWords& in, unsigned unit) {
  const auto s = plc::m3602::decode_status(in, unit);
  return {s.position, 0, s.capture};  // the 3602 has no encoder input
}

template <>
nlohmann::json ViewOf<ModuleType::k3602>::status_words(const ImageWords& in, unsigned unit) {
  const auto s = plc::m3602::decode_status(in, unit);
  return nlohmann::json::array({word_json("Status Bits MSW", s.msw, words::m3602::kStatusMswBits),
                                word_json("Status Bits LSW", s.lsw, words::m3602::kStatusLswBits)});
}

template <>
nlohmann::json ViewOf<ModuleType::k3602>::config_bits() {
  return {{"msw", table_json(words::m3602::kConfigMswBits)},
          {"lsw", table_json(words::m3602::kConfigLswBits)}};
}

template <>
nlohmann::json ViewOf<ModuleType::k3602>::config_of(const ImageWords& w) {
  namespace ow = words::m3602::out_word;
  return {
      {"msw", w.w[ow::kMsw] & 0xFFFF},
      {"lsw", w.w[ow::kLsw] & 0xFFFF},
      {"start_speed", words::decode_3602(w.w[ow::kStartingSpeedMsw], w.w[ow::kStartingSpeedLsw])},
      {"homing_timeout", w.w[ow::kHomingTimeout]}};
}

template <>
std::unique_ptr<Controls> ViewOf<ModuleType::k3602>::make_controls(plc::Port& port) {
  return std::make_unique<Controls3602>(port);
}

}  // namespace stepmod::web
