#include "gpio/wired_backend.hpp"

namespace stepmod::gpio {

bool WiredBackend::has_input(unsigned axis, InputLine line) const noexcept {
  return axis < lines_.size() && lines_[axis].has_input(line);
}

bool WiredBackend::has_output(unsigned axis, OutputLine line) const noexcept {
  return axis < lines_.size() && lines_[axis].has_output(line);
}

LineOptions WiredBackend::line_options(unsigned axis, bool input, unsigned line) const noexcept {
  if (axis >= lines_.size()) return {};
  const AxisLines& a = lines_[axis];
  if (input) return line < kInputLinesPerAxis ? a.in_opt[line] : LineOptions{};
  return line < kOutputLinesPerAxis ? a.out_opt[line] : LineOptions{};
}

}  // namespace stepmod::gpio
