#pragma once
// Which chip lines one axis uses: the `[[axis]]` line keys of docs/interface.md section 2, without
// the rest of the configuration, so that gpio/ does not depend on config/. The daemon copies
// config::AxisSection::out/in (config/config.hpp) into this. An absent offset means "not wired".
#include <optional>

#include "gpio/backend.hpp"
#include "gpio/line_options.hpp"

namespace stepmod::gpio {

struct AxisLines {
  std::optional<unsigned> out[kOutputLinesPerAxis];  // indexed by OutputLine
  std::optional<unsigned> in[kInputLinesPerAxis];    // indexed by InputLine
  LineOptions out_opt[kOutputLinesPerAxis];          // electrical options, by OutputLine
  LineOptions in_opt[kInputLinesPerAxis];            // by InputLine
  // Drive-enable output (an extension: the AMCI modules have none). Written by the control
  // thread (Backend::set_enable), never by the pulse thread.
  std::optional<unsigned> enable;
  LineOptions enable_opt;
  // The module's charge-pump output (an extension, [charge_pump] line): one per module, carried
  // by its first axis' lines (the backends request lines axis by axis). Written by the control
  // thread (Backend::set_charge_pump).
  std::optional<unsigned> charge_pump;
  LineOptions charge_pump_opt;

  bool has_output(OutputLine l) const noexcept { return out[static_cast<unsigned>(l)].has_value(); }
  bool has_input(InputLine l) const noexcept { return in[static_cast<unsigned>(l)].has_value(); }
};

}  // namespace stepmod::gpio
