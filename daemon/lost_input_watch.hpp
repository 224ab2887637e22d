#pragma once
// Lost input events (gpio::Backend::lost_events): an input edge the module never saw (a home,
// limit or capture edge, an encoder count) leaves a homing, a registration or a position that
// cannot be trusted (issue 18 item 5, issue 19). Control thread.
#include <cstdint>
#include <vector>

#include "core/clock.hpp"

namespace stepmod::tools {

class ModuleStack;

class LostInputWatch {
 public:
  explicit LostInputWatch(ModuleStack& stack) : stack_(stack) {}

  // After each batch of input events: a new loss stops every moving axis as a PLC leaving Run
  // mode does (immediate stop, position invalid) and is logged.
  void check(Nanos now);
  // Health bit 5: from the loss until the PLC's next accepted motion on any axis.
  bool lasts() const noexcept;

 private:
  ModuleStack& stack_;
  std::uint64_t seen_ = 0;             // the backend's loss count already acted on
  std::vector<std::uint32_t> epochs_;  // each axis' motion epoch at the last loss
};

}  // namespace stepmod::tools
