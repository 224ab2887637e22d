#pragma once
// What a PLC program asks of a move, in the manuals' units, before any dialect encodes it.
#include <cstdint>
#include <string>
#include <vector>

#include "core/module_shape.hpp"

namespace stepmod::plc {

enum class AccelType { kConstant, kTriangularS, kTrapezoidalS };

struct Profile {
  std::int32_t speed = 0;  // steps/s
  std::int32_t accel = 0;  // steps/ms/s (3601), 1..2000
  std::int32_t decel = 0;  // steps/ms/s (3601), 1..2000
  AccelType type = AccelType::kConstant;
};

struct BlendSegment {
  std::int32_t length = 0;  // steps, > 0
  std::int32_t speed = 0;   // steps/s
  std::int32_t accel = 0;   // steps/ms/s used to reach `speed`
  AccelType type = AccelType::kConstant;
};

struct BlendProfile {
  std::vector<BlendSegment> segments;  // 2..16
  std::int32_t final_decel = 0;        // steps/ms/s
  AccelType final_type = AccelType::kConstant;
};

// What a command produced.
struct Outcome {
  bool ok = true;          // no error bit for this command, no timeout
  bool timed_out = false;  // the module did not scan or did not answer a handshake
  std::string message;     // error bits by name (and the module's reason), or the timeout, when !ok
  std::string note;        // ok, but worth saying: an error bit still set from before
  ImageWords in;           // input image after the command
};

}  // namespace stepmod::plc
