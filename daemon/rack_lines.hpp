#pragma once
// The lines of every module of a rack as one backend, for the rack's one step output: its axis
// n is axis n - first of the module that holds it (the modules' axes in rack order). A write
// costs one table look-up more than the module's own backend; a rack of one is given that
// backend instead (daemon/stack.cpp). Everything else a backend does (inputs, events, enables)
// stays with each module's own backend and its control thread: waiting for events here is an
// error.
#include <span>
#include <vector>

#include "gpio/backend.hpp"

namespace stepmod::tools {

class RackLines final : public gpio::Backend {
 public:
  // Each backend must outlive this.
  explicit RackLines(std::span<gpio::Backend* const> modules);

  unsigned axes() const noexcept override { return static_cast<unsigned>(axes_.size()); }
  void write(unsigned axis, OutputLine line, bool level, Nanos t) noexcept override {
    const Axis& a = axes_[axis];
    a.backend->write(a.local, line, level, t);
  }
  bool has_input(unsigned axis, InputLine line) const noexcept override;
  bool has_output(unsigned axis, OutputLine line) const noexcept override;
  bool read(unsigned axis, InputLine line) override;
  std::size_t wait_events(std::span<gpio::InputEvent> out, Nanos deadline) override;
  std::uint64_t lost_events() const noexcept override;
  void idle_outputs() noexcept override;
  void set_enable(unsigned axis, bool asserted) noexcept override;
  void set_charge_pump(unsigned axis, bool active) noexcept override;
  gpio::LineOptions line_options(unsigned axis, bool input, unsigned line) const noexcept override;
  void set_pulse_format(unsigned axis, gpio::PulseFormat format) noexcept override;

 private:
  struct Axis {
    gpio::Backend* backend;
    unsigned local;
  };
  std::vector<gpio::Backend*> modules_;
  std::vector<Axis> axes_;  // by rack axis
};

}  // namespace stepmod::tools
