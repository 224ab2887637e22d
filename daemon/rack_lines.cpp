#include "daemon/rack_lines.hpp"

#include <stdexcept>

namespace stepmod::tools {

RackLines::RackLines(std::span<gpio::Backend* const> modules)
    : modules_(modules.begin(), modules.end()) {
  for (gpio::Backend* b : modules_) {
    for (unsigned a = 0; a < b->axes(); ++a) axes_.push_back({b, a});
  }
}

bool RackLines::has_input(unsigned axis, InputLine line) const noexcept {
  return axes_[axis].backend->has_input(axes_[axis].local, line);
}

bool RackLines::has_output(unsigned axis, OutputLine line) const noexcept {
  return axes_[axis].backend->has_output(axes_[axis].local, line);
}

bool RackLines::read(unsigned axis, InputLine line) {
  return axes_[axis].backend->read(axes_[axis].local, line);
}

std::size_t RackLines::wait_events(std::span<gpio::InputEvent> /*out*/, Nanos /*deadline*/) {
  throw std::logic_error("a rack's input events are each module's: wait on its own backend");
}

std::uint64_t RackLines::lost_events() const noexcept {
  std::uint64_t lost = 0;
  for (const gpio::Backend* b : modules_) lost += b->lost_events();
  return lost;
}

void RackLines::idle_outputs() noexcept {
  for (gpio::Backend* b : modules_) b->idle_outputs();
}

void RackLines::set_enable(unsigned axis, bool asserted) noexcept {
  axes_[axis].backend->set_enable(axes_[axis].local, asserted);
}

void RackLines::set_charge_pump(unsigned axis, bool active) noexcept {
  axes_[axis].backend->set_charge_pump(axes_[axis].local, active);
}

gpio::LineOptions RackLines::line_options(unsigned axis, bool input, unsigned line) const noexcept {
  return axes_[axis].backend->line_options(axes_[axis].local, input, line);
}

void RackLines::set_pulse_format(unsigned axis, gpio::PulseFormat format) noexcept {
  axes_[axis].backend->set_pulse_format(axes_[axis].local, format);
}

}  // namespace stepmod::tools
