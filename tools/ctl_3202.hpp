#pragma once
// stepmodctl's 3202 helpers: the blend profile from options or from a readable file, and the
// configuration bits from the configure flags. The commands themselves are plc/plc_3202.hpp.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "plc/profile.hpp"

namespace stepmod::tools::ctl {

struct BlendSyntaxError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One segment "LENGTH:SPEED:ACCEL[:const|tri|trap]" (numbers decimal, 0x.. or 16#..).
plc::BlendSegment parse_blend_segment(const std::string& s);
plc::AccelType parse_accel_type(const std::string& s);

// A blend profile file: one "key = value" per line; '#' at the start of a line or after a blank
// starts a comment (16#.. stays a number):
//   segment = 6000:5000:100000:tri    (2..16 times, in order)
//   final_decel = 100000
//   final_type = trap                 (const, tri or trap; default const)
plc::BlendProfile read_blend_file(const std::string& path);

}  // namespace stepmod::tools::ctl
