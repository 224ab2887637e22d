#pragma once
// The module layer's I/O (module/axis/axis_io.hpp) on the daemon's GPIO backend: the backend's
// input events converted to the module's, its lines' start-up levels, and the pulse format for
// a simulated drive. Control thread.
#include "gpio/backend.hpp"
#include "module/axis/axis_io.hpp"

namespace stepmod::tools {

inline module::InputEvent to_module_event(const gpio::InputEvent& e) noexcept {
  return {e.t, e.axis, e.line, e.level};
}

class BackendAxisIo final : public module::AxisIo {
 public:
  explicit BackendAxisIo(gpio::Backend& backend) noexcept : backend_(backend) {}

  bool has_input(unsigned axis, InputLine line) const noexcept override {
    return backend_.has_input(axis, line);
  }
  bool read(unsigned axis, InputLine line) override { return backend_.read(axis, line); }
  void set_pulse_format(unsigned axis, bool step_dir) noexcept override {
    backend_.set_pulse_format(axis,
                              step_dir ? gpio::PulseFormat::kStepDir : gpio::PulseFormat::kCwCcw);
  }

 private:
  gpio::Backend& backend_;
};

}  // namespace stepmod::tools
