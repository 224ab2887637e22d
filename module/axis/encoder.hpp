#pragma once
// The encoder functions of one axis that steer by the count: the encoder move (a run whose
// deceleration starts when the encoder reaches the target), Preset Encoder, and diagnostic
// feedback (the register counts the axis' own steps). 3601 Ch.4.
#include <cstdint>

#include "module/axis/axis_state.hpp"

namespace stepmod::module::axis {

class Encoder {
 public:
  explicit Encoder(AxisState& ax) noexcept : ax_(ax) {}

  // An absolute/relative move with the encoder-move flag, its target, profile and CE-14 checks
  // already passed.
  void move(const AxisCommand& c, bool absolute);
  // Preset Encoder, the dialect's word rules already passed.
  void preset(const AxisCommand& c);
  // Every command-mode scan: diagnostic feedback counting, a stop that could not be queued yet.
  void scan();
  // After an encoder count change during an encoder move (`c`: the command image in force).
  void watch(const AxisCommand& c, Nanos t);  // t: the count change that may reach the target

 private:
  AxisState& ax_;
  std::int64_t target_ = 0;      // the count at which deceleration starts
  bool watch_ = false;           // the target is still being watched
  bool stop_pending_ = false;    // its stop could not be queued yet
  std::int64_t diag_steps_ = 0;  // diagnostic feedback: pulse count already counted
};

}  // namespace stepmod::module::axis
