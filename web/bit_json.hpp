#pragma once
// A status word and a configuration bit table as the console page reads them: every named field
// of the module's bit tables (words/words_XXXX.hpp), shared by the per-module views.
#include <cstdint>
#include <nlohmann/json.hpp>

#include "plc/bit_names.hpp"

namespace stepmod::web {

// {"word": name, "value": word, "bits": [{"bit": 0, "name": "...", "value": 0}, ...]}
inline nlohmann::json word_json(const char* name, std::uint32_t word, BitTable table) {
  nlohmann::json bits = nlohmann::json::array();
  for (const NamedBit& b : table) {
    bits.push_back({{"bit", b.bit}, {"name", b.name}, {"value", plc::field_value(word, b)}});
  }
  return {{"word", name}, {"value", word}, {"bits", bits}};
}

// [{"bit": 0, "name": "..."}, ...]; a field of several bits has its "width" (the page offers
// every value of it: the 3602's two-bit CW/CCW input function, limit or E-stop).
inline nlohmann::json table_json(BitTable table) {
  nlohmann::json bits = nlohmann::json::array();
  for (const NamedBit& b : table) {
    nlohmann::json j = {{"bit", b.bit}, {"name", b.name}};
    if (b.width > 1) j["width"] = b.width;
    bits.push_back(std::move(j));
  }
  return bits;
}

}  // namespace stepmod::web
