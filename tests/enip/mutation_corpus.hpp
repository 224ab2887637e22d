#pragma once
// The deterministic mutation corpus of the EtherNet/IP tests (docs/ethernetip-design.md, "Fuzz
// plan"): valid packets (encapsulation frames, CIP requests, an O→T packet) and the edits made
// to them from a fixed seed (bytes flipped, overwritten, inserted, cut). The parser test runs
// them through the layers; the socket test sends them to a running daemon.
#include <cstdint>
#include <random>
#include <vector>

#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip::test {

using Bytes = std::vector<std::uint8_t>;

inline Bytes mutate(Bytes b, std::mt19937& rng) {
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = b.empty() ? 0 : rng() % b.size();
    switch (rng() % 5) {
      case 0:
        if (!b.empty()) b[at] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
        break;
      case 1:
        if (!b.empty()) b[at] = static_cast<std::uint8_t>(rng());
        break;
      case 2:
        b.insert(b.begin() + static_cast<long>(at), static_cast<std::uint8_t>(rng()));
        break;
      case 3:
        b.resize(at);
        break;
      default:
        if (!b.empty()) b[at] = (rng() % 2) != 0 ? 0xFF : 0x00;
        break;
    }
  }
  return b;
}

inline const Bytes kForwardOpen =
    hex("03 7d 00000000 78563412 3412 3333 37130000 03 000000 10270000 1648 10270000 1248 01"
        "09 34 04 0000 0000 0000 00 00 20 04 24 97 2c 96 2c 64");

inline std::vector<Bytes> mutation_seeds() {
  const Bytes reg = hex("6500 0400 00000000 00000000 0000000000000000 00000000 0100 0000");
  const Bytes rr_head =
      hex("6f00 4c00 01000000 00000000 0000000000000000 00000000"
          "00000000 0a00 0200 0000 0000 b200 3c00 54 02 20 06 24 01");
  return {reg,
          cat(reg, cat(rr_head, kForwardOpen)),
          cat(reg, hex("6f00 2400 01000000 00000000 0000000000000000 00000000"
                       "00000000 0a00 0200 0000 0000 b200 1400"
                       "52 02 20 06 24 01 07 f9 0600 01 02 20 01 24 01 01 00 01 00")),
          hex("6300 0000 00000000 00000000 0000000000000000 00000000"),
          kForwardOpen,
          hex("03 7d 3412 3333 37130000 03 00 01 00 20 02 24 01"),
          hex("0200 0280 0800 d0c0b0a0 05000000 b100 1600 0200 01000000"
              "0100 0200 0300 0400 0500 0600 0700 0800"),
          hex("34 04 ffff 2b00 110e 81 01 20 04 24 97 2c 96 2c 64 80 01 aa bb 12 02 31 32"),
          cat(hex("52 02 20 06 24 01 07 f9 18 00 10 03 20 04 24 96 30 03"),
              hex("0000 0000 0000 0000 0000 0000 0000 0000 01 00 01 00"))};
}

}  // namespace stepmod::enip::test
