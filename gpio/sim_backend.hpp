#pragma once
// Backend for `backend = "sim"`: one SimMachine per axis (docs/interface.md section 2 [axis.sim]),
// plus the accessors the simulator panel (section 4) needs.
#include <atomic>
#include <memory>
#include <span>
#include <vector>

#include "gpio/sim_machine.hpp"
#include "gpio/wired_backend.hpp"

namespace stepmod::gpio {

struct SimAxisSetup {
  AxisLines lines;  // which lines are configured (offsets are not used by the sim)
  SimAxisParams sim;
};

class SimBackend final : public WiredBackend {
 public:
  // `event_capacity`: per-axis input event ring (power of two).
  explicit SimBackend(std::span<const SimAxisSetup> axes,
                      std::size_t event_capacity = kDefaultSimEventRing);

  void write(unsigned axis, OutputLine line, bool level, Nanos t) noexcept override;
  bool read(unsigned axis, InputLine line) override;
  // Drains the machines' events; when there are none, sleeps until some arrive or `deadline`
  // passes. The sim has no file descriptor to block on: the sleep is a futex wait that write()
  // ends when it produced an event while a waiter sleeps (issue 12 item 8: polling every 50 us
  // during a move cost the control thread 13 % of a core at any step rate).
  std::size_t wait_events(std::span<InputEvent> out, Nanos deadline) override;
  std::uint64_t lost_events() const noexcept override;
  void idle_outputs() noexcept override;
  void set_pulse_format(unsigned axis, PulseFormat format) noexcept override;

  // Simulator panel. force() on the control thread (the thread calling wait_events).
  // The forced edges are stamped `now` (the daemon: the clock; virtual-time tests: their time).
  void force(unsigned axis, std::uint32_t mask, std::uint32_t levels, Nanos now) noexcept;
  void force(unsigned axis, std::uint32_t mask, std::uint32_t levels) noexcept {
    force(axis, mask, levels, monotonic_now());
  }
  std::int64_t position(unsigned axis) const noexcept { return machines_[axis]->position(); }
  std::int64_t encoder(unsigned axis) const noexcept { return machines_[axis]->encoder(); }
  // Wire levels (an active-low output's level inverted), as the panel shows them; bit 3 is the
  // drive-enable output (kEnableLevelBit), bit 4 the module's charge pump on the axis that
  // carries it (kChargePumpLevelBit).
  std::uint32_t output_levels(unsigned axis) const noexcept {
    return (machines_[axis]->output_levels() ^ active_low_outputs_[axis]) |
           control_wires_[axis].load(std::memory_order_relaxed);
  }
  static constexpr std::uint32_t kEnableLevelBit = 1u << 3;
  static constexpr std::uint32_t kChargePumpLevelBit = 1u << 4;
  void set_enable(unsigned axis, bool asserted) noexcept override;
  void set_charge_pump(unsigned axis, bool active) noexcept override;
  SimMachine& machine(unsigned axis) noexcept { return *machines_[axis]; }

  // Events closer together than this are polled for at this period instead of each waking the
  // waiter (see wait_events).
  static constexpr Nanos kPollChunk = 50 * kNsPerUs;

  // Wakes a thread sleeping in wait_events (what a GPIO event fd does for the gpiod backend).
  void notify_events() noexcept;

 private:
  // Futex word: +1 after every write() that produced input events. `waiting_`: a thread sleeps
  // (or is about to) in wait_events. Both seq_cst: the waiter stores waiting_ then loads the
  // sequence, the writer stores the sequence then loads waiting_; in the single total order one
  // of them sees the other, so a wake-up is never lost (the futex compares the sequence).
  std::atomic<std::uint32_t> event_seq_{0};
  std::atomic<bool> waiting_{false};
  Nanos last_events_ = 0;  // consumer: when wait_events last returned events
  std::vector<std::unique_ptr<SimMachine>> machines_;
  std::vector<std::uint32_t> active_low_outputs_;              // per axis, bit per OutputLine
  // Per axis: the control thread's wires, kEnableLevelBit | kChargePumpLevelBit (one writer at a
  // time: the control thread, or the main thread once it has ended).
  std::unique_ptr<std::atomic<std::uint32_t>[]> control_wires_;
  void set_control_wire(unsigned axis, std::uint32_t bit, bool wire) noexcept;
  unsigned next_axis_ = 0;  // round-robin start of wait_events, so no axis starves another
};

}  // namespace stepmod::gpio
