#pragma once
// The words of motion shared by every request kind: direction, acceleration type, ramp.
#include <cstdint>

namespace stepmod::planner {

enum class Direction : std::int8_t { kCw = 1, kCcw = -1 };
inline constexpr int sign(Direction d) noexcept {
  return static_cast<int>(d);
}
inline constexpr Direction opposite(Direction d) noexcept {
  return d == Direction::kCw ? Direction::kCcw : Direction::kCw;
}

// The manuals' acceleration types (ch. 2). k = ramp time factor: 1, 2, 4/3.
enum class AccelShape : std::uint8_t { kConstant = 0, kTriangularS = 1, kTrapezoidalS = 2 };

struct Ramp {
  double rate = 0.0;  // steps/s^2, > 0
  AccelShape shape = AccelShape::kConstant;
};

}  // namespace stepmod::planner
