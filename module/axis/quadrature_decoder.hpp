#pragma once
// X4 quadrature decoding of encoder A/B edges (3601/3202 encoder input: every edge of A or B is
// one count; the sense of rotation follows from which channel leads).
#include <cstdint>

namespace stepmod::module {

class QuadratureDecoder {
 public:
  void reset(bool a, bool b) noexcept { state_ = code(a, b); }

  // Applies the new levels of A and B after one edge; returns the count change (-1, 0, +1).
  // A two-step jump (both channels changed at once: a missed edge) cannot tell the sense and
  // counts nothing, as a hardware decoder flags an error instead of guessing.
  int update(bool a, bool b) noexcept {
    const std::uint8_t next = code(a, b);
    // + counts when A leads B: (A,B) 00 -> 10 -> 11 -> 01 -> 00, i.e. codes 0 -> 1 -> 3 -> 2.
    static constexpr int kDelta[4][4] = {
        // to:  00  01  10  11
        {0, +1, -1, 0},  // from 00
        {-1, 0, 0, +1},  // from 01
        {+1, 0, 0, -1},  // from 10
        {0, -1, +1, 0},  // from 11
    };
    const int d = kDelta[state_][next];
    if (d == 0 && next != state_) ++errors_;
    state_ = next;
    return d;
  }
  std::uint64_t errors() const noexcept { return errors_; }

 private:
  // Code: bit 0 = A, bit 1 = B.
  static std::uint8_t code(bool a, bool b) noexcept {
    return static_cast<std::uint8_t>((b ? 2 : 0) | (a ? 1 : 0));
  }
  std::uint8_t state_ = 0;
  std::uint64_t errors_ = 0;
};

}  // namespace stepmod::module
