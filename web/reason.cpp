#include "web/reason.hpp"

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

#include "web/reason_help.hpp"

namespace stepmod::web {
namespace {
constexpr unsigned kOffReasons = 448;
constexpr unsigned kStride = 64;
constexpr unsigned kText = 56;

template <typename T>
T relaxed(const unsigned char* p) {
  return std::atomic_ref<T>(*reinterpret_cast<T*>(const_cast<unsigned char*>(p)))
      .load(std::memory_order_acquire);
}
}  // namespace

nlohmann::json reason_json(const stepmod_image_t& img, unsigned unit,
                           std::int64_t accel_word_unit) {
  if (unit >= 2) return nlohmann::json::object();
  const auto* base = reinterpret_cast<const unsigned char*>(&img);
  const unsigned char* block = base + kOffReasons + static_cast<std::size_t>(kStride) * unit;
  const auto* seq = &img.input_seq;
  for (int attempt = 0; attempt < 1000; ++attempt) {
    if (attempt > 0 && attempt % 32 == 0) std::this_thread::yield();
    const std::uint32_t s0 = relaxed<std::uint32_t>(reinterpret_cast<const unsigned char*>(seq));
    if (s0 & 1u) continue;
    const auto rseq = relaxed<std::uint32_t>(block);
    const auto item = relaxed<std::uint32_t>(block + 4);
    std::string text;
    for (unsigned i = 0; i < kText; ++i) {
      const char c = static_cast<char>(relaxed<unsigned char>(block + 8 + i));
      if (c == '\0') break;
      text.push_back(c);
    }
    if (relaxed<std::uint32_t>(reinterpret_cast<const unsigned char*>(seq)) == s0) {
      const bool cut = text.size() + 1 >= kText;
      return {{"seq", rseq},
              {"item", item},
              {"text", in_form_units(text, accel_word_unit)},
              {"cut", cut}};
    }
  }
  return nlohmann::json::object();
}

}  // namespace stepmod::web
