// The 3601 on the console: one axis, MSW/LSW status and configuration words, an encoder.
#include "module_types/m3601/view_3601.hpp"
#include "module_types/m3601/plc_3601.hpp"
#include "module_types/m3601/plc_status_3601.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "web/bit_json.hpp"

namespace stepmod::web {
namespace {

class Controls3601 final : public Controls {
 public:
  explicit Controls3601(plc::Port& port) : plc_(port) {}
  void release_jogs() override { plc_.jog_release(); }

 protected:
  plc::Outcome move(unsigned, bool a, std::int32_t t, const plc::Profile& p) override {
    return plc_.move(a, t, p);
  }
  plc::Outcome jog_press(unsigned, bool cw, const plc::Profile& p) override {
    return plc_.jog_press(cw, p);
  }
  plc::Outcome jog_release(unsigned) override { return plc_.jog_release(); }
  plc::Outcome home(unsigned, bool cw, const plc::Profile& p) override { return plc_.home(cw, p); }
  plc::Outcome hold(unsigned) override { return plc_.hold(); }
  plc::Outcome resume(unsigned) override { return plc_.resume(std::nullopt); }
  plc::Outcome stop(unsigned) override { return plc_.immediate_stop(); }
  plc::Outcome reset(unsigned) override { return plc_.reset_errors(); }
  plc::Outcome preset(unsigned, std::int32_t p) override { return plc_.preset_position(p); }
  plc::Outcome configure(unsigned, std::uint32_t bits, std::int32_t vs, std::int16_t) override {
    return plc_.configure(static_cast<std::uint16_t>(bits >> 16),
                          static_cast<std::uint16_t>(bits & 0xFFFFu), vs);
  }
  unsigned units() const override { return 1; }

 private:
  plc::Plc3601 plc_;
};

}  // namespace

template <>
UnitRegisters ViewOf<ModuleType::k3601>::registers(const ImageWords& in, unsigned) {
  const auto s = plc::m3601::decode_status(in);
  return {s.position, s.encoder, s.capture};
}

template <>
nlohmann::json ViewOf<ModuleType::k3601>::status_words(const ImageWords& in, unsigned) {
  const auto s = plc::m3601::decode_status(in);
  return nlohmann::json::array({word_json("Status Word MSW", s.msw, words::m3601::kStatusMswBits),
                                word_json("Status Word LSW", s.lsw, words::m3601::kStatusLswBits)});
}

template <>
nlohmann::json ViewOf<ModuleType::k3601>::config_bits() {
  return {{"msw", table_json(words::m3601::kConfigMswBits)},
          {"lsw", table_json(words::m3601::kConfigLswBits)}};
}

template <>
nlohmann::json ViewOf<ModuleType::k3601>::config_of(const ImageWords& w) {
  namespace ow = words::m3601::out_word;
  const auto vs = words::decode_3601(w.w[ow::kTargetMsw], w.w[ow::kTargetLsw]);
  return {{"msw", w.w[ow::kMsw] & 0xFFFF},
          {"lsw", w.w[ow::kLsw] & 0xFFFF},
          {"start_speed", vs ? nlohmann::json(*vs) : nlohmann::json(nullptr)}};
}

template <>
std::unique_ptr<Controls> ViewOf<ModuleType::k3601>::make_controls(plc::Port& port) {
  return std::make_unique<Controls3601>(port);
}

}  // namespace stepmod::web
