#pragma once
// stepmodctl's blend profile input, the same for every module: segments from options or a
// readable file. The ranges each module's words can carry are checked by its dialect
// (tools/ctl_36xx.cpp, ctl_3202.cpp); here only "is it a 32-bit number".
#include <string>
#include <vector>

#include "plc/move_profile.hpp"
#include "tools/ctl_args.hpp"

namespace stepmod::tools::ctl {

// One segment "LENGTH:SPEED:ACCEL[:const|tri|trap]" (numbers decimal, 0x.. or 16#..).
plc::BlendSegment parse_blend_segment(const std::string& s);

// A blend profile file: one "key = value" per line; '#' at the start of a line or after a blank
// starts a comment (16#.. stays a number):
//   segment = 6000:5000:100000:tri    (2..16 times, in order)
//   final_decel = 100000
//   final_type = trap                 (const, tri or trap; default const)
plc::BlendProfile read_blend_file(const std::string& path);

// `blend program`'s options: the file if one is named (then no --segment), else the segments.
plc::BlendProfile blend_from_options(const std::string& file,
                                     const std::vector<std::string>& segments,
                                     const std::string& final_decel, const std::string& final_type);

}  // namespace stepmod::tools::ctl
