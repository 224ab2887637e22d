#include "daemon/lost_input_watch.hpp"

#include <spdlog/spdlog.h>

#include "daemon/module_stack.hpp"
#include "module/axis/error_items.hpp"

namespace stepmod::tools {

// Losses: the kernel's per-line event FIFO (seen by sequence-number gaps with libgpiod 2, by
// repeated edge directions with 1.6) or the simulated machine's event ring.
void LostInputWatch::check(Nanos now) {
  const std::uint64_t lost = stack_.backend().lost_events();
  if (lost == seen_) return;
  const std::uint64_t fresh = lost - seen_;
  seen_ = lost;
  const unsigned axes = stack_.shape().axes;
  unsigned moving = 0;
  for (unsigned a = 0; a < axes; ++a) moving += stack_.motion(a).busy() ? 1u : 0u;
  stack_.personality().stop_every_axis(module::axis::items::kPiInputLost, now);
  epochs_.assign(axes, 0);
  for (unsigned a = 0; a < axes; ++a) epochs_[a] = stack_.motion(a).epoch();
  spdlog::error(
      "{} input event(s) lost ({} in all): {} moving axis/axes stopped, position invalid "
      "(re-home); a homing or registration may have missed its edge",
      fresh, lost, moving);
}

bool LostInputWatch::lasts() const noexcept {
  if (epochs_.empty()) return false;
  for (unsigned a = 0; a < epochs_.size(); ++a) {
    if (stack_.motion(a).epoch() != epochs_[a]) return false;
  }
  return true;
}

}  // namespace stepmod::tools
