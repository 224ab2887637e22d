#include "gpio/sim_backend.hpp"

#include <algorithm>

namespace stepmod::gpio {

SimBackend::SimBackend(std::span<const SimAxisSetup> axes, std::size_t event_capacity) {
  machines_.reserve(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a) {
    std::uint16_t wired = 0;
    for (unsigned i = 0; i < kInputLinesPerAxis; ++i) {
      if (axes[a].lines.in[i]) wired |= static_cast<std::uint16_t>(1u << i);
    }
    machines_.push_back(std::make_unique<SimMachine>(static_cast<std::uint8_t>(a), axes[a].sim,
                                                     wired, event_capacity));
    lines_.push_back(axes[a].lines);
  }
}

void SimBackend::write(unsigned axis, OutputLine line, bool level, Nanos t) noexcept {
  // An unwired output (GPO on a module without one) drives nothing; the drive only sees wired
  // step/dir lines, which the config requires anyway.
  if (!lines_[axis].has_output(line)) return;
  machines_[axis]->write(line, level, t);
}

bool SimBackend::has_input(unsigned axis, InputLine line) const noexcept {
  return axis < lines_.size() && lines_[axis].has_input(line);
}

bool SimBackend::has_output(unsigned axis, OutputLine line) const noexcept {
  return axis < lines_.size() && lines_[axis].has_output(line);
}

bool SimBackend::read(unsigned axis, InputLine line) {
  return machines_[axis]->read(line);
}

std::size_t SimBackend::wait_events(std::span<InputEvent> out, Nanos deadline) {
  const auto n_axes = static_cast<unsigned>(machines_.size());
  for (;;) {
    std::size_t n = 0;
    for (unsigned k = 0; k < n_axes && n < out.size(); ++k) {
      n += machines_[(next_axis_ + k) % n_axes]->poll(out.subspan(n));
    }
    if (n_axes > 0) next_axis_ = (next_axis_ + 1) % n_axes;
    if (n > 0 || out.empty()) return n;
    const Nanos now = monotonic_now();
    if (now >= deadline) return 0;
    sleep_until(std::min(now + kPollChunk, deadline));
  }
}

std::uint64_t SimBackend::lost_events() const noexcept {
  std::uint64_t n = 0;
  for (const auto& m : machines_) n += m->lost_events();
  return n;
}

void SimBackend::idle_outputs() noexcept {
  const Nanos now = monotonic_now();
  for (unsigned a = 0; a < machines_.size(); ++a) {
    for (unsigned l = 0; l < kOutputLinesPerAxis; ++l) {
      write(a, static_cast<OutputLine>(l), false, now);
    }
  }
}

void SimBackend::set_pulse_format(unsigned axis, PulseFormat format) noexcept {
  if (axis < machines_.size()) machines_[axis]->set_pulse_format(format);
}

void SimBackend::force(unsigned axis, std::uint32_t mask, std::uint32_t levels,
                       Nanos now) noexcept {
  if (axis < machines_.size()) machines_[axis]->force(mask, levels, now);
}

}  // namespace stepmod::gpio
