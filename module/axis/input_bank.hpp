#pragma once
// The discrete inputs of one axis as the module sees them: the electrical level of every line
// (from the machine's I/O at start-up, then from each InputEvent) and, per the configuration, which
// inputs are used and at which level they are active (decoded by each dialect into AxisConfig).
#include <array>
#include <cstdint>

#include "module/axis/axis_io.hpp"

namespace stepmod::module {

class InputBank {
 public:
  // Electrical levels as read at start-up.
  void init(AxisIo& io, unsigned axis) {
    for (unsigned i = 0; i < kInputLinesPerAxis; ++i) {
      const auto line = static_cast<InputLine>(i);
      level_[i] = io.has_input(axis, line) && io.read(axis, line);
    }
  }
  void set_level(InputLine l, bool level) noexcept { level_[idx(l)] = level; }
  bool level(InputLine l) const noexcept { return level_[idx(l)]; }

  // used: bit n = input n enabled (n = InputLine value 0..5); active_high: bit n = 1 if the
  // input is active when its line is high (N.O. contact), 0 if active when low (N.C.).
  void configure(std::uint16_t used, std::uint16_t active_high) noexcept {
    used_ = used;
    active_high_ = active_high;
  }
  bool used(InputLine l) const noexcept { return (used_ >> idx(l)) & 1u; }

  // Logical state: a used input at its active level. An unused input is never active (A27).
  bool active(InputLine l) const noexcept { return used(l) && active_at(l, level(l)); }
  // Whether an input would be active at the given electrical level (for edge classification).
  bool active_at(InputLine l, bool level) const noexcept {
    const bool high_active = (active_high_ >> idx(l)) & 1u;
    return level == high_active;
  }
  // Bits 0..5 = logical states of capture, external, home, E-stop, CW limit, CCW limit.
  std::uint16_t active_bits() const noexcept {
    std::uint16_t bits = 0;
    for (unsigned i = 0; i < kPanelInputs; ++i) {
      if (active(static_cast<InputLine>(i))) bits |= static_cast<std::uint16_t>(1u << i);
    }
    return bits;
  }

 private:
  static constexpr unsigned idx(InputLine l) noexcept { return static_cast<unsigned>(l); }
  std::array<bool, kInputLinesPerAxis> level_{};
  std::uint16_t used_ = 0;
  std::uint16_t active_high_ = 0;
};

}  // namespace stepmod::module
