#include "web/image_json.hpp"

#include "plc/bit_names.hpp"
#include "plc/status_3202.hpp"
#include "plc/status_3601.hpp"
#include "plc/status_3602.hpp"
#include "registry/module_registry.hpp"
#include "words/words_3202.hpp"
#include "words/words_3601.hpp"
#include "words/words_3602.hpp"

namespace stepmod::web {
namespace {

nlohmann::json word_json(const char* name, std::uint32_t word, BitTable table) {
  nlohmann::json bits = nlohmann::json::array();
  for (const NamedBit& b : table) {
    bits.push_back({{"bit", b.bit}, {"name", b.name}, {"value", plc::field_value(word, b)}});
  }
  return {{"word", name}, {"value", word}, {"bits", bits}};
}

nlohmann::json table_json(BitTable table) {
  nlohmann::json bits = nlohmann::json::array();
  for (const NamedBit& b : table) bits.push_back({{"bit", b.bit}, {"name", b.name}});
  return bits;
}

}  // namespace

UnitRegisters registers_of(ModuleType type, const ImageWords& in, unsigned unit) {
  switch (type) {
    case ModuleType::k3601: {
      const auto s = plc::m3601::decode_status(in);
      return {s.position, s.encoder, s.capture};
    }
    case ModuleType::k3602: {
      const auto s = plc::m3602::decode_status(in, unit);
      return {s.position, 0, s.capture};  // the 3602 has no encoder input
    }
    case ModuleType::k3202:
      break;
  }
  const auto s = plc::m3202::decode_status(in, unit);
  return {s.position, s.encoder, s.capture};
}

nlohmann::json unit_json(ModuleType type, const ImageWords& in, unsigned unit) {
  nlohmann::json words = nlohmann::json::array();
  if (type == ModuleType::k3601) {
    const auto s = plc::m3601::decode_status(in);
    words.push_back(word_json("Status Word MSW", s.msw, words::m3601::kStatusMswBits));
    words.push_back(word_json("Status Word LSW", s.lsw, words::m3601::kStatusLswBits));
  } else if (type == ModuleType::k3602) {
    const auto s = plc::m3602::decode_status(in, unit);
    words.push_back(word_json("Status Bits MSW", s.msw, words::m3602::kStatusMswBits));
    words.push_back(word_json("Status Bits LSW", s.lsw, words::m3602::kStatusLswBits));
  } else {
    const auto s = plc::m3202::decode_status(in, unit);
    words.push_back(word_json("Status", s.word, words::m3202::kStatusBits));
  }
  const UnitRegisters r = registers_of(type, in, unit);
  return {{"unit", unit},
          {"words", words},
          {"position", r.position},
          {"encoder", r.encoder},
          {"capture", r.capture}};
}

nlohmann::json module_json(ModuleType type) {
  const ModuleShape shape = shape_of(type);
  const module::axis::ModuleRules& r = *registry::row_of(type).rules;
  nlohmann::json cfg;
  if (type == ModuleType::k3601) {
    cfg = {{"msw", table_json(words::m3601::kConfigMswBits)},
           {"lsw", table_json(words::m3601::kConfigLswBits)}};
  } else if (type == ModuleType::k3602) {
    cfg = {{"msw", table_json(words::m3602::kConfigMswBits)},
           {"lsw", table_json(words::m3602::kConfigLswBits)}};
  } else {  // one configuration DINT per channel: the page sends it whole ("bits")
    cfg = {{"dint", table_json(words::m3202::kConfigBits)}};
  }
  // The same ramp by default on every module: 100 steps/ms/s = 100,000 steps/s^2.
  const bool per_s2 = r.accel_word_unit == 1;
  return {{"type", static_cast<unsigned>(type)},
          {"units", shape.axes},
          {"config_bits", cfg},
          {"ranges",
           {{"speed_max", r.speed_max},
            {"starting_speed_min", r.starting_speed_min},
            {"starting_speed_max", r.starting_speed_max},
            {"accel_min", r.accel_min / r.accel_word_unit},
            {"accel_max", r.accel_max / r.accel_word_unit},
            {"accel_unit", per_s2 ? "steps/s²" : "steps/ms/s"},
            {"accel_default", per_s2 ? 100'000 : 100},
            {"target_min", r.target_min},
            {"target_max", r.target_max}}}};
}

}  // namespace stepmod::web
