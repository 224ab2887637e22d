#pragma once
// Decoding of a module's input image for people (stepmodctl status/watch): every status bit by
// name, positions as numbers in the module's own encoding (digest MODULES.md 2).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ipc/health.hpp"
#include "module/personality.hpp"

namespace stepmod::tools::ctl {

struct BitName {
  unsigned bit;
  std::string_view name;
};

// Status bit names per module type, in bit order (digest 3.10/3.11, 4.10/4.11, 5.7).
const std::vector<BitName>& status_msw_names_3601();
const std::vector<BitName>& status_lsw_names_3601();
const std::vector<BitName>& config_msw_names_3601();
const std::vector<BitName>& status_msw_names_3602();
const std::vector<BitName>& status_lsw_names_3602();
const std::vector<BitName>& status_names_3202();

// Names of the set bits of `word`, space-separated ("-" when none).
std::string set_bit_names(std::uint32_t word, const std::vector<BitName>& names);

// The whole decoded input image, multi-line, for `type`.
std::string format_status(ModuleType type, const ImageWords& in);

// The daemon health words (INTERFACE.md 3.3): flags by name, late-edge fault count and the
// worst lateness.
std::string format_health(const ipc::Health& h);

// One line per word: index, decimal, hex (word-size digits).
std::string format_words(const ImageWords& w, unsigned count, unsigned word_bytes);

}  // namespace stepmod::tools::ctl
