#pragma once
// The control thread's end of the error reasons (docs/error-reasons.md): each new reason a module
// records is logged as a warning, naming the module and axis, and goes into the image's reason
// block with the next input publication.
#include <vector>

#include "ipc/shm_image.hpp"
#include "module/personality.hpp"

namespace stepmod::tools {

class ReasonPublisher {
 public:
  explicit ReasonPublisher(unsigned axes) : seen_(axes, 0) {}
  // After each scan (and input edge batch): new reasons logged and handed to `image`.
  void scan(const module::Personality& personality, ipc::ShmImage& image);

 private:
  std::vector<std::uint32_t> seen_;  // per axis: the reason sequence already published
};

// The text of `r` as a C string (its buffer is NUL-terminated by construction).
stepmod_reason_t to_image(const module::axis::ErrorReason& r) noexcept;

}  // namespace stepmod::tools
