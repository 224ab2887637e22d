#include "gpio/sim_backend.hpp"

#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>

namespace stepmod::gpio {

namespace {
// Inputs with nothing simulated driving them: the bias of the line decides their level.
std::uint16_t undriven_inputs(const SimAxisParams& p) {
  std::uint16_t m = input_bit(InputLine::kCapture) | input_bit(InputLine::kExternal) |
                    input_bit(InputLine::kEStop);
  if (!p.home_from) m |= input_bit(InputLine::kHome);
  if (!p.cw_limit_at) m |= input_bit(InputLine::kCwLimit);
  if (!p.ccw_limit_at) m |= input_bit(InputLine::kCcwLimit);
  if (p.encoder_ratio == 0.0) {
    m |= input_bit(InputLine::kEncA) | input_bit(InputLine::kEncB) | input_bit(InputLine::kEncZ);
  } else if (!p.marker_every || *p.marker_every <= 0) {
    m |= input_bit(InputLine::kEncZ);
  }
  return m;
}

std::vector<AxisLines> lines_of(std::span<const SimAxisSetup> axes) {
  std::vector<AxisLines> lines;
  for (const SimAxisSetup& a : axes) lines.push_back(a.lines);
  return lines;
}
}  // namespace

SimBackend::SimBackend(std::span<const SimAxisSetup> axes, std::size_t event_capacity)
    : WiredBackend(lines_of(axes)),
      control_wires_(std::make_unique<std::atomic<std::uint32_t>[]>(axes.size())) {
  machines_.reserve(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a) {
    std::uint16_t wired = 0;
    SimPulls pulls;
    const std::uint16_t undriven = undriven_inputs(axes[a].sim);
    for (unsigned i = 0; i < kInputLinesPerAxis; ++i) {
      if (!axes[a].lines.in[i]) continue;
      const auto bit = static_cast<std::uint16_t>(1u << i);
      wired |= bit;
      // An unconnected input with a pull resistor reads the pull's level on the wire; the module
      // sees it inverted when the line is active-low.
      const LineOptions& o = axes[a].lines.in_opt[i];
      if ((undriven & bit) == 0 || (o.bias != Bias::kPullUp && o.bias != Bias::kPullDown)) continue;
      pulls.mask |= bit;
      if ((o.bias == Bias::kPullUp) != o.active_low) pulls.levels |= bit;
    }
    std::uint32_t inverted = 0;
    for (unsigned o = 0; o < kOutputLinesPerAxis; ++o) {
      if (axes[a].lines.out_opt[o].active_low) inverted |= 1u << o;
    }
    active_low_outputs_.push_back(inverted);
    const std::size_t ring = axes[a].sim.event_ring != 0 ? axes[a].sim.event_ring : event_capacity;
    machines_.push_back(std::make_unique<SimMachine>(static_cast<std::uint8_t>(a), axes[a].sim,
                                                     wired, ring, pulls));
  }
  for (unsigned a = 0; a < axes.size(); ++a) {  // released and inactive at start
    set_enable(a, false);
    set_charge_pump(a, false);
  }
}

void SimBackend::write(unsigned axis, OutputLine line, bool level, Nanos t) noexcept {
  // An unwired output (GPO on a module without one) drives nothing; the drive only sees wired
  // step/dir lines, which the config requires anyway.
  if (!lines()[axis].has_output(line)) return;
  SimMachine& m = *machines_[axis];
  const std::uint64_t before = m.events_pushed();
  m.write(line, level, t);
  if (m.events_pushed() != before) notify_events();
}

void SimBackend::notify_events() noexcept {
  // The single producer of the sequence is the writing (pulse) thread: a load + store, no RMW.
  event_seq_.store(event_seq_.load(std::memory_order_relaxed) + 1, std::memory_order_seq_cst);
  // A system call only when someone sleeps, at most once per sleep: the simulated hardware's
  // edge interrupt, the sim's counterpart of the kernel waking a gpiod reader.
  if (waiting_.load(std::memory_order_seq_cst) && waiting_.exchange(false)) {
    syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&event_seq_), FUTEX_WAKE_PRIVATE, 1,
            nullptr, nullptr, 0);
  }
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
    if (n > 0 || out.empty()) {
      if (n > 0) last_events_ = monotonic_now();
      return n;
    }
    const Nanos now = monotonic_now();
    if (now >= deadline) return 0;
    if (now - last_events_ < kPollChunk) {
      // Events come faster than one per kPollChunk (a fast move with an encoder: up to 2 M/s):
      // a wake-up per event would make the pulse thread pay a system call per step. Poll in
      // kPollChunk steps instead, without asking for a wake-up, until they slow down.
      sleep_until(std::min(now + kPollChunk, deadline));
      continue;
    }
    const std::uint32_t seen = event_seq_.load(std::memory_order_seq_cst);
    waiting_.store(true, std::memory_order_seq_cst);
    // Events that came between the drain above and `seen`: take them without sleeping.
    bool pending = false;
    for (const auto& m : machines_) pending = pending || m->has_events();
    if (!pending) {
      const timespec ts = to_timespec(deadline);
      // Returns at the deadline, on a wake, at once if the sequence moved since `seen`, or on a
      // signal: the loop drains and decides again.
      syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&event_seq_), FUTEX_WAIT_BITSET_PRIVATE,
              seen, &ts, nullptr, FUTEX_BITSET_MATCH_ANY);
    }
    waiting_.store(false, std::memory_order_relaxed);
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
    set_enable(a, false);
    set_charge_pump(a, false);
  }
}

void SimBackend::set_pulse_format(unsigned axis, PulseFormat format) noexcept {
  if (axis < machines_.size()) machines_[axis]->set_pulse_format(format);
}

void SimBackend::force(unsigned axis, std::uint32_t mask, std::uint32_t levels,
                       Nanos now) noexcept {
  if (axis < machines_.size()) machines_[axis]->force(mask, levels, now);
}

void SimBackend::set_control_wire(unsigned axis, std::uint32_t bit, bool wire) noexcept {
  // One atomic read-modify-write: idle_outputs() may run on another thread than the control's.
  if (wire) {
    control_wires_[axis].fetch_or(bit, std::memory_order_relaxed);
  } else {
    control_wires_[axis].fetch_and(~bit, std::memory_order_relaxed);
  }
}

void SimBackend::set_enable(unsigned axis, bool asserted) noexcept {
  if (axis >= lines().size() || !lines()[axis].enable) return;
  set_control_wire(axis, kEnableLevelBit, asserted != lines()[axis].enable_opt.active_low);
}

void SimBackend::set_charge_pump(unsigned axis, bool active) noexcept {
  if (axis >= lines().size() || !lines()[axis].charge_pump) return;
  set_control_wire(axis, kChargePumpLevelBit, active != lines()[axis].charge_pump_opt.active_low);
}

}  // namespace stepmod::gpio
