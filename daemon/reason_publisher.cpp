#include "daemon/reason_publisher.hpp"

#include <spdlog/spdlog.h>

#include <cstring>

namespace stepmod::tools {

stepmod_reason_t to_image(const module::axis::ErrorReason& r) noexcept {
  stepmod_reason_t out{};
  out.seq = r.seq;
  out.item = r.code;
  static_assert(sizeof out.text == module::axis::kReasonTextSize);
  std::memcpy(out.text, r.text.data(), sizeof out.text);
  out.text[sizeof out.text - 1] = '\0';
  return out;
}

void ReasonPublisher::scan(const module::Personality& personality, ipc::ShmImage& image) {
  const ModuleShape& shape = personality.shape();
  const char* unit = shape.unit_noun;
  for (unsigned a = 0; a < seen_.size(); ++a) {
    const module::axis::ErrorReason r = personality.reason(a);
    if (r.seq == seen_[a]) continue;
    seen_[a] = r.seq;
    const stepmod_reason_t img = to_image(r);
    image.set_reason(a, img);
    spdlog::warn("module {} {} {}: {}", static_cast<unsigned>(shape.type), unit, a + 1, img.text);
  }
}

}  // namespace stepmod::tools
