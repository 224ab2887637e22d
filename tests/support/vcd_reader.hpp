#pragma once
// Reads a VCD file written by stepmodd (docs/interface.md section 5) back into per-wire change
// lists, the way an outside checker would: by wire name, with times in ns.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace stepmod::testing {

struct VcdChange {
  std::int64_t t = 0;
  int level = 0;
};

struct Vcd {
  std::string timescale;
  std::map<std::string, std::vector<VcdChange>> wires;  // by name, e.g. "axis1.step"

  // Times of the 0 -> 1 transitions of a wire.
  std::vector<std::int64_t> rising(const std::string& wire) const;
  // Level of a wire at the end of the file.
  int final_level(const std::string& wire) const;
};

// Throws std::runtime_error on a malformed file (unknown identifier, time going backwards).
Vcd read_vcd(const std::string& path);

}  // namespace stepmod::testing
