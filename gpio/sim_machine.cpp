#include "gpio/sim_machine.hpp"

#include <algorithm>
#include <cmath>

namespace stepmod::gpio {
namespace {

constexpr std::uint8_t out_bit(OutputLine l) noexcept {
  return static_cast<std::uint8_t>(1u << static_cast<unsigned>(l));
}
constexpr std::uint16_t kEncoderMask =
    input_bit(InputLine::kEncA) | input_bit(InputLine::kEncB) | input_bit(InputLine::kEncZ);

// Positive remainder, for the quadrature phase and the marker of negative counts.
constexpr std::int64_t floor_mod(std::int64_t a, std::int64_t m) noexcept {
  const std::int64_t r = a % m;
  return r < 0 ? r + m : r;
}

}  // namespace

SimMachine::SimMachine(std::uint8_t axis, const SimAxisParams& params, std::uint16_t wired_inputs,
                       std::size_t event_capacity, SimPulls pulls)
    : axis_(axis),
      p_(params),
      wired_(static_cast<std::uint16_t>(wired_inputs & ((1u << kInputLinesPerAxis) - 1))),
      nc_(params.contacts_nc),
      pulls_(pulls),
      pos_(params.start_position),
      ring_(event_capacity) {
  // Initial levels: every panel input unactuated, then the switches and the encoder at the start
  // position. Capture, external and E-stop have no simulated actuator, so they rest at the
  // unactuated level of the configured contact type (an NC machine reads high at rest) until
  // the panel forces them.
  for (unsigned i = 0; i < kPanelInputs; ++i) {
    if (nc_) sim_in_ |= static_cast<std::uint16_t>(1u << i);
  }
  const auto actuated = [&](InputLine l, bool on) {
    if (on != nc_) {
      sim_in_ |= input_bit(l);
    } else {
      sim_in_ &= static_cast<std::uint16_t>(~input_bit(l));
    }
  };
  actuated(InputLine::kCwLimit, p_.cw_limit_at && pos_ >= *p_.cw_limit_at);
  actuated(InputLine::kCcwLimit, p_.ccw_limit_at && pos_ <= *p_.ccw_limit_at);
  actuated(InputLine::kHome,
           p_.home_from && p_.home_to && *p_.home_from <= pos_ && pos_ <= *p_.home_to);
  count_ = encoder_count_at(pos_);
  sim_in_ = static_cast<std::uint16_t>((sim_in_ & ~kEncoderMask) | encoder_levels(count_));
  sim_in_ = static_cast<std::uint16_t>((sim_in_ & ~pulls_.mask) | (pulls_.levels & pulls_.mask));
  sim_in_ &= wired_;

  seen_sim_ = sim_in_;
  reported_ = sim_in_;
  position_pub_.store(pos_, std::memory_order_relaxed);
  encoder_pub_.store(count_, std::memory_order_relaxed);
  sim_in_pub_.store(sim_in_, std::memory_order_relaxed);
}

std::int64_t SimMachine::encoder_count_at(std::int64_t position) const noexcept {
  if (p_.encoder_ratio == 0.0) return 0;
  const double x = p_.encoder_ratio * static_cast<double>(position);
  // Relative tolerance: 0.1 * 30 must count 3, not 2.9999999.
  return static_cast<std::int64_t>(std::floor(x + 1e-9 * std::max(1.0, std::fabs(x))));
}

// X4 quadrature: phase 0 (A0 B0), 1 (A1 B0), 2 (A1 B1), 3 (A0 B1). Counting up, A leads B; each
// count changes exactly one of them. Z is high while the count is a multiple of marker_every.
std::uint16_t SimMachine::encoder_levels(std::int64_t count) const noexcept {
  if (p_.encoder_ratio == 0.0) return 0;  // no encoder: the lines stay low
  std::uint16_t v = 0;
  const std::int64_t phase = floor_mod(count, 4);
  if (phase == 1 || phase == 2) v |= input_bit(InputLine::kEncA);
  if (phase == 2 || phase == 3) v |= input_bit(InputLine::kEncB);
  if (p_.marker_every && *p_.marker_every > 0 && floor_mod(count, *p_.marker_every) == 0) {
    v |= input_bit(InputLine::kEncZ);
  }
  return v;
}

void SimMachine::write(OutputLine line, bool level, Nanos t) noexcept {
  const std::uint8_t prev = out_;
  const std::uint8_t bit = out_bit(line);
  out_ = level ? static_cast<std::uint8_t>(out_ | bit) : static_cast<std::uint8_t>(out_ & ~bit);
  outputs_pub_.store(out_, std::memory_order_relaxed);
  if (prev == out_ || !level) return;  // the drive moves on rising edges only

  int delta = 0;
  if (format_.load(std::memory_order_relaxed) == static_cast<std::uint8_t>(PulseFormat::kStepDir)) {
    // Step/direction: dir high = CW = +1.
    if (line == OutputLine::kStep) delta = (out_ & out_bit(OutputLine::kDir)) ? +1 : -1;
  } else {
    // CW/CCW: the step line carries CW pulses, the dir line CCW pulses.
    if (line == OutputLine::kStep) delta = +1;
    if (line == OutputLine::kDir) delta = -1;
  }
  if (delta != 0) move(delta, t);
}

void SimMachine::move(int delta, Nanos t) noexcept {
  pos_ += delta;
  position_pub_.store(pos_, std::memory_order_relaxed);
  update_switches(t);

  const std::int64_t target = encoder_count_at(pos_);
  // One count at a time so that every A/B edge is seen, in the right order for the direction.
  while (count_ != target) {
    count_ += (target > count_) ? 1 : -1;
    const std::uint16_t lv = encoder_levels(count_);
    set_sim_input(InputLine::kEncA, lv & input_bit(InputLine::kEncA), t);
    set_sim_input(InputLine::kEncB, lv & input_bit(InputLine::kEncB), t);
    set_sim_input(InputLine::kEncZ, lv & input_bit(InputLine::kEncZ), t);
  }
  encoder_pub_.store(count_, std::memory_order_relaxed);
  sim_in_pub_.store(sim_in_, std::memory_order_relaxed);
}

void SimMachine::update_switches(Nanos t) noexcept {
  const bool cw = p_.cw_limit_at && pos_ >= *p_.cw_limit_at;
  const bool ccw = p_.ccw_limit_at && pos_ <= *p_.ccw_limit_at;
  const bool home = p_.home_from && p_.home_to && *p_.home_from <= pos_ && pos_ <= *p_.home_to;
  set_sim_input(InputLine::kCwLimit, cw != nc_, t);
  set_sim_input(InputLine::kCcwLimit, ccw != nc_, t);
  set_sim_input(InputLine::kHome, home != nc_, t);
}

void SimMachine::set_sim_input(InputLine line, bool level, Nanos t) noexcept {
  const std::uint16_t bit = input_bit(line);
  if ((wired_ & bit) == 0 || (pulls_.mask & bit) != 0) return;
  if (((sim_in_ & bit) != 0) == level) return;
  sim_in_ = level ? static_cast<std::uint16_t>(sim_in_ | bit)
                  : static_cast<std::uint16_t>(sim_in_ & ~bit);
  ++pushed_;
  if (!ring_.try_push(InputEvent{t, axis_, line, level})) {
    // Single writer: a load + store is enough and avoids a locked instruction.
    ring_lost_.store(ring_lost_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  }
}

// ---- consumer side ------------------------------------------------------------------------------

bool SimMachine::filter(const InputEvent& e, InputEvent& out) noexcept {
  const std::uint16_t bit = input_bit(e.line);
  seen_sim_ = e.level ? static_cast<std::uint16_t>(seen_sim_ | bit)
                      : static_cast<std::uint16_t>(seen_sim_ & ~bit);
  if (filter_mask_ & bit) return false;                   // forced: not visible
  if (((reported_ & bit) != 0) == e.level) return false;  // already reported (force release)
  reported_ ^= bit;
  const auto i = static_cast<unsigned>(e.line);
  out = e;
  out.t = std::max(e.t, last_t_[i]);
  last_t_[i] = out.t;
  return true;
}

const SimMachine::ForceChange* SimMachine::next_force() const noexcept {
  return forces_size_ > 0 ? &forces_[forces_head_] : nullptr;
}

// The force takes effect: the panel inputs whose effective level it changes get an edge each,
// stamped at the force (or just after the line's last edge, to keep each line in time order).
void SimMachine::stage_force(const ForceChange& f) noexcept {
  filter_mask_ = f.mask;
  for (unsigned i = 0; i < kPanelInputs; ++i) {
    const std::uint16_t bit = static_cast<std::uint16_t>(1u << i);
    if ((wired_ & bit) == 0) continue;
    const bool eff = (f.mask & bit) ? (f.levels & bit) != 0 : (seen_sim_ & bit) != 0;
    if (((reported_ & bit) != 0) == eff) continue;
    reported_ ^= bit;
    last_t_[i] = std::max(f.t, last_t_[i]);
    staged_[(staged_head_ + staged_size_++) % kPanelInputs] =
        InputEvent{last_t_[i], axis_, static_cast<InputLine>(i), eff};
  }
}

// Merges the simulated events and the panel's changes by time: a change takes effect once every
// simulated event stamped before it has been polled, so a backlog of encoder edges delays a
// forced E-stop edge (by no more than the backlog) but never loses or reorders it.
std::size_t SimMachine::poll(std::span<InputEvent> out) noexcept {
  std::size_t n = 0;
  while (n < out.size()) {
    if (staged_size_ > 0) {
      out[n++] = staged_[staged_head_];
      staged_head_ = (staged_head_ + 1) % kPanelInputs;
      --staged_size_;
      continue;
    }
    const InputEvent* e = ring_.peek();
    const ForceChange* f = next_force();
    if (f != nullptr && (e == nullptr || f->t < e->t)) {
      stage_force(*f);
      forces_head_ = (forces_head_ + 1) % kForceCapacity;
      --forces_size_;
      continue;
    }
    if (e == nullptr) break;
    const InputEvent sim = *e;
    ring_.pop();
    if (filter(sim, out[n])) ++n;
  }
  return n;
}

void SimMachine::force(std::uint32_t mask, std::uint32_t levels, Nanos now) noexcept {
  mask &= kPanelMask & wired_;
  levels &= mask;
  if (mask == requested_.mask && levels == requested_.levels) return;
  requested_ = ForceChange{mask, levels, now};
  force_mask_.store(mask, std::memory_order_relaxed);
  force_levels_.store(levels, std::memory_order_relaxed);
  if (forces_size_ == kForceCapacity) {
    // kForceCapacity changes unpolled: the newest replaces the last waiting one, whose edges
    // (if it had any of its own) are lost, and counted so (the daemon stops the axes).
    forces_[(forces_head_ + forces_size_ - 1) % kForceCapacity] = requested_;
    ++forces_lost_;
    return;
  }
  forces_[(forces_head_ + forces_size_++) % kForceCapacity] = requested_;
}

bool SimMachine::read(InputLine line) const noexcept {
  const std::uint16_t bit = input_bit(line);
  if ((wired_ & bit) == 0) return false;
  if (force_mask_.load(std::memory_order_relaxed) & bit) {
    return (force_levels_.load(std::memory_order_relaxed) & bit) != 0;
  }
  return (sim_in_pub_.load(std::memory_order_relaxed) & bit) != 0;
}

}  // namespace stepmod::gpio
