#pragma once
// One simulated axis (docs/interface.md section 2 [axis.sim], section 4): a drive and motor that
// follow the step/dir (or CW/CCW) outputs, limit and home switches at fixed positions, and a
// quadrature encoder with a marker. The motor moves only through `write()`, called by the pulse
// thread.
//
// Threads and why it is race-free without locks:
//  * Producer (pulse thread, or whoever writes outputs while it is stopped): `write()`. It owns
//    the motor state and the *simulated* switch/encoder levels, and pushes every change of a
//    wired input's simulated level into an SPSC ring, stamped with the write time. It never
//    looks at the panel's forcing, so it never races with it.
//  * Consumer (control thread): `poll()`, `force()`, `read()`. Forcing is applied here, on the
//    consumer side of the ring: the consumer keeps its own view of the simulated levels (from the
//    events it has drained) and of the levels it has reported. A simulated event on a forced line
//    only updates that view; forcing or releasing a line reports an event when the *effective*
//    level (forced level, or simulated level when not forced) changes. Because both happen on
//    one thread, the reported sequence of levels per line is always consistent (never two
//    rising edges in a row), whatever the pulse thread does meanwhile.
//  * Any thread: `position()`, `encoder()`, `output_levels()` (panel, relaxed atomics).
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "core/spsc_ring.hpp"
#include "gpio/backend.hpp"

namespace stepmod::gpio {

// The [axis.sim] table (same fields as tools::SimAxisConfig, kept here so gpio/ does not depend on
// config/; the daemon copies one into the other).
struct SimAxisParams {
  std::int64_t start_position = 0;
  std::optional<std::int64_t> cw_limit_at;  // absent: never actuated
  std::optional<std::int64_t> ccw_limit_at;
  std::optional<std::int64_t> home_from;  // home actuated in [home_from, home_to]; both needed
  std::optional<std::int64_t> home_to;
  bool contacts_nc = false;                  // "NO" (false): actuated = high; "NC": actuated = low
  double encoder_ratio = 1.0;                // X4 counts per step; sign = direction; 0 = none
  std::optional<std::int64_t> marker_every;  // Z period in encoder counts; absent/<=0 = no Z
  // (Last, so that positional initializers of the fields above keep their meaning.)
  // Input event FIFO of this axis' simulated lines (power of two; 0: kDefaultSimEventRing).
  // Like a GPIO line's kernel FIFO (16 events): when it overflows, events are lost, which the
  // daemon treats as a lost-input fault. A small one lets a test provoke that.
  std::size_t event_ring = 0;
};

// The default event FIFO: 65,536 events (1 MiB) per axis. The simulated machine's consumer, the
// daemon's control thread, is not raised to real-time priority (the simulation runs on desks
// and CI machines beside other work), so its FIFO rides out scheduling stalls instead: over
// three seconds of an X1 encoder's edges at 20,000 steps/s. 4,096 (0.2 s) lost edges under
// ordinary load and stopped the examples' moves.
inline constexpr std::size_t kDefaultSimEventRing = 65536;

inline constexpr std::uint16_t input_bit(InputLine l) noexcept {
  return static_cast<std::uint16_t>(1u << static_cast<unsigned>(l));
}
inline constexpr std::uint16_t kPanelMask = (1u << kPanelInputs) - 1;

// Inputs held by a pull resistor because nothing simulated drives them: their (logical) levels.
struct SimPulls {
  std::uint16_t mask = 0;
  std::uint16_t levels = 0;
};

class SimMachine {
 public:
  // `wired_inputs`: bit per InputLine; an unwired input stays low and never produces events.
  // `event_capacity`: size of the event ring (power of two).
  // `pulls`: inputs that rest at their pull resistor's level (and stay there).
  SimMachine(std::uint8_t axis, const SimAxisParams& params, std::uint16_t wired_inputs,
             std::size_t event_capacity = kDefaultSimEventRing, SimPulls pulls = {});
  SimMachine(const SimMachine&) = delete;
  SimMachine& operator=(const SimMachine&) = delete;

  // --- producer (pulse thread): no allocation, no lock, no system call -------------------------
  void write(OutputLine line, bool level, Nanos t) noexcept;

  // --- consumer (control thread) -------------------------------------------------------------
  // Moves up to out.size() events into `out` (forced changes and simulated changes, with forced
  // lines filtered); returns the count.
  std::size_t poll(std::span<InputEvent> out) noexcept;
  // Consumer: something is waiting for poll() (a simulated or a forced event).
  bool has_events() const noexcept {
    return !ring_.empty() || staged_size_ > 0 || forces_size_ > 0;
  }
  // Panel forcing (docs/interface.md section 4): bit i of `mask` forces panel input i (0 capture ..
  // 5 CCW limit) to bit i of `levels`; a cleared bit gives the line back to the simulation.
  // `now` stamps the events this causes. Must be called on the consumer's thread (every scan;
  // an unchanged force costs nothing). read() sees it at once; poll() delivers its events in
  // time order with the simulated ones, however many of those wait (as a real E-stop line's
  // edge is not lost behind an encoder's: each line has its own kernel FIFO).
  void force(std::uint32_t mask, std::uint32_t levels, Nanos now) noexcept;
  // Present electrical level: forced level, else the simulated level now; false when unwired.
  bool read(InputLine line) const noexcept;
  // Producer side (the writing thread): events pushed so far, to tell whether a write() made any.
  std::uint64_t events_pushed() const noexcept { return pushed_; }
  // Events lost: ring full (producer) plus panel changes merged away because kForceCapacity
  // changes waited unpolled (the consumer reads this; the producer only adds to ring_lost_).
  std::uint64_t lost_events() const noexcept {
    return ring_lost_.load(std::memory_order_relaxed) + forces_lost_;
  }

  // --- any thread ------------------------------------------------------------------------------
  void set_pulse_format(PulseFormat f) noexcept {
    format_.store(static_cast<std::uint8_t>(f), std::memory_order_relaxed);
  }
  std::int64_t position() const noexcept { return position_pub_.load(std::memory_order_relaxed); }
  std::int64_t encoder() const noexcept { return encoder_pub_.load(std::memory_order_relaxed); }
  // bit 0 step/CW, bit 1 dir/CCW, bit 2 GPO (panel "output levels now")
  std::uint32_t output_levels() const noexcept {
    return outputs_pub_.load(std::memory_order_relaxed);
  }
  std::uint16_t wired_inputs() const noexcept { return wired_; }
  std::uint8_t axis() const noexcept { return axis_; }

  // Encoder count for a motor position: floor(ratio * position), so that the count, the A/B
  // phase and the markers are a function of the machine position (no drift over long moves).
  std::int64_t encoder_count_at(std::int64_t position) const noexcept;

 private:
  void move(int delta, Nanos t) noexcept;
  void update_switches(Nanos t) noexcept;
  void set_sim_input(InputLine line, bool level, Nanos t) noexcept;
  std::uint16_t encoder_levels(std::int64_t count) const noexcept;
  bool filter(const InputEvent& e, InputEvent& out) noexcept;  // consumer: sim event -> effective
  // A panel change waiting for the simulated events stamped before it to be polled.
  struct ForceChange {
    std::uint32_t mask = 0;
    std::uint32_t levels = 0;
    Nanos t = 0;
  };
  const ForceChange* next_force() const noexcept;
  void stage_force(const ForceChange& f) noexcept;  // its edges into staged_, in effect from now

  // configuration (immutable)
  const std::uint8_t axis_;
  const SimAxisParams p_;
  const std::uint16_t wired_;
  const bool nc_;
  const SimPulls pulls_;

  // producer-owned
  std::uint8_t out_ = 0;      // output levels
  std::int64_t pos_ = 0;      // motor position
  std::int64_t count_ = 0;    // encoder count
  std::uint16_t sim_in_ = 0;  // simulated input levels (wired lines only)
  SpscRing<InputEvent> ring_;
  std::uint64_t pushed_ = 0;

  // consumer-owned
  // Panel changes not yet in effect for poll() (a person's or a test's: a few per second).
  static constexpr std::size_t kForceCapacity = 64;
  std::array<ForceChange, kForceCapacity> forces_{};
  std::size_t forces_head_ = 0, forces_size_ = 0;
  std::uint64_t forces_lost_ = 0;
  ForceChange requested_{};  // the last force() asked for
  // The edges of the force in effect (at most one per panel input), not yet polled.
  std::array<InputEvent, kPanelInputs> staged_{};
  std::size_t staged_head_ = 0, staged_size_ = 0;
  std::uint32_t filter_mask_ = 0;  // the force in effect for the simulated events polled now
  std::uint16_t seen_sim_ = 0;     // simulated levels as of the events drained so far
  std::uint16_t reported_ = 0;     // effective levels as last reported to the consumer
  std::array<Nanos, kInputLinesPerAxis> last_t_{};  // keeps each line's events in time order

  // shared
  std::atomic<std::uint8_t> format_{static_cast<std::uint8_t>(PulseFormat::kStepDir)};
  std::atomic<std::uint32_t> force_mask_{0};
  std::atomic<std::uint32_t> force_levels_{0};
  alignas(kCacheLine) std::atomic<std::int64_t> position_pub_{0};
  std::atomic<std::int64_t> encoder_pub_{0};
  std::atomic<std::uint32_t> outputs_pub_{0};
  std::atomic<std::uint16_t> sim_in_pub_{0};
  std::atomic<std::uint64_t> ring_lost_{0};
};

}  // namespace stepmod::gpio
