#pragma once
// The adapter's one pseudo-random generator (xorshift32, seeded from getrandom() by the adapter):
// connection ids a peer cannot guess from the last one, and the spread of broadcast answers.
// Guards nothing cryptographic.
#include <cstdint>

namespace stepmod::enip {

class Xorshift32 {
 public:
  explicit Xorshift32(std::uint32_t seed) noexcept : state_(seed | 1u) {}  // never 0: 0 stays 0
  std::uint32_t next() noexcept {
    state_ ^= state_ << 13;
    state_ ^= state_ >> 17;
    state_ ^= state_ << 5;
    return state_;
  }

 private:
  std::uint32_t state_;
};

}  // namespace stepmod::enip
