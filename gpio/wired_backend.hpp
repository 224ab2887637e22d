#pragma once
// What every backend answers alike from its configured lines (an AxisLines per axis): how many
// axes, which lines are wired and their electrical options. SimBackend and GpiodBackend derive
// from it and keep only what they do with the lines.
#include <vector>

#include "gpio/axis_lines.hpp"
#include "gpio/backend.hpp"

namespace stepmod::gpio {

class WiredBackend : public Backend {
 public:
  unsigned axes() const noexcept final { return static_cast<unsigned>(lines_.size()); }
  bool has_input(unsigned axis, InputLine line) const noexcept final;
  bool has_output(unsigned axis, OutputLine line) const noexcept final;
  LineOptions line_options(unsigned axis, bool input, unsigned line) const noexcept final;

 protected:
  explicit WiredBackend(std::vector<AxisLines> lines) : lines_(std::move(lines)) {}
  // Fixed at construction: read by any thread without a lock.
  const std::vector<AxisLines>& lines() const noexcept { return lines_; }

 private:
  const std::vector<AxisLines> lines_;
};

}  // namespace stepmod::gpio
