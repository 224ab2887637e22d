#pragma once
// Decoding of a module's input image for people (stepmodctl status/watch): every status bit by
// the name the module's bit table gives it (module_types/m3601/words_3601.hpp, m3602/words_3602.hpp,
// m3202/words_3202.hpp), positions as numbers in the module's own encoding (its manual's data
// format).
#include <cstdint>
#include <string>

#include "core/module_shape.hpp"
#include "ipc/health.hpp"
#include "ipc/sim_panel.hpp"
#include "plc/bit_names.hpp"

namespace stepmod::tools::ctl {

using plc::set_bit_names;

// The whole decoded input image, multi-line, for `type`.
std::string format_status(ModuleType type, const ImageWords& in);

// The daemon health words (docs/interface.md 3.3): flags by name, late-edge fault count and the
// worst lateness.
std::string format_health(const ipc::Health& h);

// The simulator panel (docs/interface.md 4): per axis the motor position, encoder count, output
// levels and forced inputs.
std::string format_panel(const ipc::SimPanelClient& p);

// One line per word: index, decimal, hex (word-size digits).
std::string format_words(const ImageWords& w, unsigned count, unsigned word_bytes);

}  // namespace stepmod::tools::ctl
