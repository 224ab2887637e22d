#pragma once
// stepmodctl's shared command-line plumbing: exit codes, the usage error, and the parsers every
// dialect uses for its options (numbers in the PLC's notations, directions, acceleration types,
// input names), so that a bad value gets the same message on every module. A UsageError is
// thrown before any word is written: bad input never reaches the image.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "plc/move_profile.hpp"
#include "tools/ctl_command.hpp"
#include "words/shared_config_bits.hpp"

namespace stepmod::tools::ctl {

inline constexpr int kExitOk = 0;
inline constexpr int kExitModuleError = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitUnreachable = 3;

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Decimal, 0x.. or 16#.. (PLC notation) hexadecimal, with a sign. `what` names the option.
std::int64_t parse_number(const std::string& s, const std::string& what);
// The same, refused (UsageError) outside lo..hi; `words` says what cannot carry it.
std::int64_t parse_in_range(const std::string& s, const std::string& what, std::int64_t lo,
                            std::int64_t hi, const std::string& words);
// Checks an already parsed value the same way.
void check_range(std::int64_t v, const std::string& what, std::int64_t lo, std::int64_t hi,
                 const std::string& words);

// What a module's words carry, for the messages: "the 3601's two words".
struct Limits {
  std::int64_t lo;
  std::int64_t hi;
  const char* words;
};
std::int32_t parse_limited(const std::string& s, const std::string& what, const Limits& l);

// A module's ranges for --speed and for --accel/--decel.
struct ProfileLimits {
  Limits speed;
  Limits rate;
};
// --speed/--accel/--decel/--scurve as a profile; each of the three must be given.
plc::Profile parse_profile(const ProfileArgs& p, const ProfileLimits& l);
// A move's profile for the commands where it is optional (resume): none if no option is given.
std::optional<plc::Profile> parse_optional_profile(const ProfileArgs& p, const ProfileLimits& l);

// + / cw / CW is true (clockwise), - / ccw / CCW false.
bool parse_direction(const std::string& s);
// "" / const / constant, tri / triangular, trap / trapezoidal.
plc::AccelType parse_accel_type(const std::string& s);

// The simulator panel's and configure's input names in InputLine order:
// capture, external, home, estop, cw_limit, ccw_limit.
inline constexpr const char* kInputNames[] = {"capture", "external", "home",
                                              "estop",   "cw_limit", "ccw_limit"};
unsigned input_index(const std::string& name);

// configure's flags for the configuration bits that the 3601 and the 3202 name alike, at the
// module's positions (words/shared_config_bits.hpp); --cw-ccw clears Step+Direction Output.
std::uint32_t shared_config_bits(const ConfigureArgs& a, const words::SharedConfigMasks& m);

}  // namespace stepmod::tools::ctl
