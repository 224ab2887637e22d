// Config-file keys of the lines (docs/interface.md section 2); also the VCD wire suffixes (5).
#include "core/enum_names.hpp"
#include "gpio/backend.hpp"
#include "gpio/line_options.hpp"

namespace stepmod::gpio {

namespace {
// In enumerator order (core/lines.hpp, gpio/line_options.hpp).
constexpr std::array<std::string_view, kInputLinesPerAxis> kInputKeys = {
    "capture", "external", "home", "estop", "cw_limit", "ccw_limit", "enc_a", "enc_b", "enc_z"};
constexpr std::array<std::string_view, kOutputLinesPerAxis> kOutputKeys = {"step", "dir", "gpo"};
constexpr std::array<std::string_view, 4> kBiasNames = {"as-is", "pull-up", "pull-down",
                                                        "disabled"};
constexpr std::array<std::string_view, 3> kDriveNames = {"push-pull", "open-drain", "open-source"};
static_assert(static_cast<unsigned>(InputLine::kEncZ) + 1 == kInputKeys.size());
static_assert(static_cast<unsigned>(OutputLine::kGpo) + 1 == kOutputKeys.size());
static_assert(static_cast<unsigned>(Bias::kDisabled) + 1 == kBiasNames.size());
static_assert(static_cast<unsigned>(Drive::kOpenSource) + 1 == kDriveNames.size());
}  // namespace

std::string_view input_key(InputLine l) noexcept {
  return enum_name(l, kInputKeys);
}

std::string_view output_key(OutputLine l) noexcept {
  return enum_name(l, kOutputKeys);
}

std::string_view bias_name(Bias b) noexcept {
  return enum_name(b, kBiasNames);
}

std::string_view drive_name(Drive d) noexcept {
  return enum_name(d, kDriveNames);
}

}  // namespace stepmod::gpio
