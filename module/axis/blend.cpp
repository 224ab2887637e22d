// Blend moves: the block-by-block programming handshake and Run Blend (3601 manual Ch.4 "Blend
// Move", Ch.5 "Blend Move Programming").
//
// Programming (3601 Ch.5 "Blend Move Programming", the flags decoded by the dialect): with no
// command set the PLC holds the program flag for the whole cycle and raises the transmit flag once
// per block. Each transmit rising edge reads one block (decoded by the dialect), checks it and sets
// the acknowledge; the acknowledge follows transmit back to 0. Every check is made on the block
// that brings its data, so an error is reported with that block's acknowledge. Clearing the program
// bit ends the cycle: the profile is stored only if the cycle had no error and brought exactly the
// declared number of segment blocks (A21c).
#include <cmath>

#include "module/axis/blend.hpp"
#include "planner/profile.hpp"

namespace stepmod::module::axis {

namespace {

constexpr int kMinSegments = 2;
constexpr int kMaxSegments = 16;

// Distances are compared with a hair of tolerance: a transition that exactly fills its segment
// (the "touch" case) is legal, and floating rounding must not turn it into an error.
bool fits(double needed, double length) {
  return needed <= length + 1e-6 * (1.0 + length);
}

}  // namespace

void Blend::programming_scan(const AxisCommand& c, const AxisCommand& prev) {
  // The Hold's CE (3601-CE-23) was cleared by Reset Errors: a CE raised later has another reason
  // and must not clear itself at the blend's end.
  if (!ax_.latches().command_error) hold_error_ = false;

  const bool program = c.blend_program;
  const bool transmit = c.blend_transmit;
  const bool transmit_rose = transmit && !prev.blend_transmit;
  // Routine step 4: the acknowledge follows the transmit bit back to 0.
  if (!transmit) ack_ = false;

  if (!program) {
    if (cycle_) end_cycle();
    return;
  }
  if (!cycle_) {
    cycle_ = true;
    spoiled_ = false;
    blocks_ = 0;
    total_ = 0;
    pending_ = planner::BlendSpec{};
  }
  if (transmit_rose) read_block(c);
}

// Routine step 6: the cycle ends. A21c: fewer segment blocks than declared = not programmed (Run
// Blend then raises CE-20); a block too many was already an IP error.
void Blend::end_cycle() {
  cycle_ = false;
  if (!spoiled_ && blocks_ > 0 && blocks_ == 1u + static_cast<unsigned>(pending_.count)) {
    profile_ = pending_;
    stored_ = true;
  }
}

// One block, on a transmit rising edge.
void Blend::read_block(const AxisCommand& c) {
  // Routine step 2: every block is acknowledged, a rejected one too (A21d, 3601-IP-21), so that
  // the PLC's handshake never waits forever; the error bits tell it the block was refused.
  ack_ = true;
  const bool first = blocks_ == 0;
  ++blocks_;
  if (spoiled_) return;  // the cycle already failed: the rest is read and ignored

  if (first && ax_.activity() == Activity::kBlend) {
    // 3601-CE-22: programming started while a blend runs. The cycle is refused (the stored
    // profile, which the running blend came from, is kept) and the blend is brought down with
    // its final-segment deceleration.
    spoiled_ = true;
    bring_down();
    return;
  }
  if (ax_.latches().command_error) {
    // 3601-CE-L1: while CE is set the module takes no new operation; a block is not stored and
    // the profile is reported invalid (3601-IP-21) so that a PLC checking only IP sees it too.
    spoiled_ = true;
    ax_.fire(AxisEvent::kProfileInvalid);
    ax_.note(items::kBlendBlockError, "blend block refused: Command Error is set");
    return;
  }
  if (first) {
    // A new profile replaces the stored one from its first block on (3601 Ch.4 "Blend Move").
    stored_ = false;
  }
  // No command may be set in a block (3601 Ch.5 "Blend Move Programming").
  const bool no_command = c.commands.empty();
  const bool ok = first ? first_block(c.blend_first) : segment_block(c.blend_segment);
  if (!ok || !no_command) {
    spoiled_ = true;
    ax_.fire(AxisEvent::kProfileInvalid);  // 3601-IP-21: any error in a block
    if (!reason_noted_) ax_.note(items::kBlendBlockError, "blend block %u refused", blocks_);
  }
  reason_noted_ = false;
}

bool Blend::first_block(const BlendFirstBlock& b) {
  bool ok = true;
  // 3601-IP-04: 2..16 segments.
  const std::int32_t count = b.segments;
  if (count < kMinSegments || count > kMaxSegments) {
    ax_.note(items::kBlendSegmentCount, "%d blend segments (2..16)", static_cast<int>(count));
    reason_noted_ = true;
    ok = false;
  } else {
    pending_.count = static_cast<std::uint8_t>(count);
    for (int n = 1; n <= count; ++n) {
      pending_.segments[static_cast<std::size_t>(n - 1)].ramp.shape =
          b.shapes[static_cast<std::size_t>(n - 1)];
    }
  }
  // The final deceleration's type: 3601-IP-19, A22 (type 10 is invalid for the final decel).
  if (b.final_shape) {
    pending_.final_decel.shape = *b.final_shape;
  } else {
    ok = false;
  }
  const std::int64_t value = b.final_decel;
  if (value == 0) {
    // 3601-CE-24 / IP-07, A21a: no final deceleration value -> CE (Ch.5) and IP (Ch.6 #7).
    ax_.reject(items::kBlendNoFinalDecel, "blend profile without a final deceleration");
    reason_noted_ = true;
    ok = false;
  } else if (!ax_.rate_in_range(value)) {
    ok = false;  // 3601-IP-02: outside the module's accel range
  } else {
    pending_.final_decel.rate = static_cast<double>(value);
  }
  // The words the first block leaves empty are 0 (3601 Ch.5 "Blend Move Programming").
  if (!b.unused_words_zero) ok = false;
  return ok;
}

bool Blend::segment_block(const BlendSegmentBlock& b) {
  const int n = static_cast<int>(blocks_) - 1;  // this block's segment, 1-based
  // A21c: a segment block beyond the declared count is an error.
  if (n > pending_.count) return false;
  bool ok = true;
  planner::BlendSegment& seg = pending_.segments[static_cast<std::size_t>(n - 1)];

  // 3601-IP-20: the length is positive and encodable, and the lengths add up to at most the
  // module's maximum (3601: 8,388,607; Ch.5 "Segment Length Restrictions").
  const auto& length = b.length;
  if (!length || *length <= 0 || *length > ax_.rules.blend_segment_max) {
    ok = false;
  } else {
    seg.length = *length;
    total_ += *length;
    if (total_ > ax_.rules.blend_length_max) ok = false;
  }
  // Target speed Vs..1,000,000 (3601-IP-02 range; below Vs: 3601-CE-05 / IP-01, which name blend
  // moves among the moves that may not run below the starting speed).
  const auto& speed = b.speed;
  if (!ax_.speed_in_range(speed)) {
    ok = false;
  } else if (*speed < ax_.cfg.starting_speed) {
    ax_.reject(items::kVpBelowVs, "blend segment speed %d is below Vs %d", static_cast<int>(*speed),
               static_cast<int>(ax_.cfg.starting_speed));
    reason_noted_ = true;
    ok = false;
  } else {
    seg.speed = static_cast<double>(*speed);
  }
  // The accel/decel that reaches this segment's speed (3601-IP-02: the module's accel range).
  if (!ax_.rate_in_range(b.rate)) {
    ok = false;
  } else {
    seg.ramp.rate = static_cast<double>(b.rate);
  }
  if (!b.unused_words_zero) ok = false;  // 3601 Ch.5 "Blend Move Programming"
  if (!ok) return false;

  // 3601 Ch.5 "Segment Length Restrictions", checked as soon as the segment's data is here: segment
  // 1 starts at Vs, segment i at V(i-1).
  const double vs = ax_.cfg.starting_speed;
  const double v_prev = n == 1 ? vs : pending_.segments[static_cast<std::size_t>(n - 2)].speed;
  // 3601-IP-06: two consecutive segments with the same speed.
  if (n > 1 && seg.speed == v_prev) return false;
  // 3601-IP-05: the segment must reach its speed inside its length (k |Vi^2 - Vi-1^2| / 2Ai).
  double needed = planner::ramp_distance(v_prev, seg.speed, seg.ramp);
  // A21b: the last segment also holds the final deceleration to Vs, which ends exactly at the
  // sum of the lengths.
  if (n == pending_.count) {
    needed += planner::ramp_distance(seg.speed, vs, pending_.final_decel);
  }
  return fits(needed, static_cast<double>(seg.length));
}

bool Blend::program(const BlendFirstBlock& first, std::span<const BlendSegmentBlock> segments) {
  if (ax_.activity() == Activity::kBlend) {
    bring_down();  // 3202-CE-19 (as 3601-CE-22): the stored profile of the running blend is kept
    return false;
  }
  // A new profile replaces the stored one (3601 Ch.4 "Blend Move"): a refused one leaves none.
  stored_ = false;
  cycle_ = false;
  pending_ = planner::BlendSpec{};
  total_ = 0;
  blocks_ = 1;
  bool ok = first_block(first);
  for (std::size_t n = 0; ok && n < pending_.count; ++n) {
    blocks_ = static_cast<unsigned>(n) + 2;
    ok = n < segments.size() && segment_block(segments[n]);
  }
  blocks_ = 0;
  if (!ok) {
    ax_.fire(AxisEvent::kProfileInvalid);
    if (!reason_noted_) ax_.note(items::kBlendBlockError, "blend profile refused");
    reason_noted_ = false;
    return false;
  }
  profile_ = pending_;
  stored_ = true;
  return true;
}

// Run Blend + / -: 3601 manual Ch.4 "Blend Move". The dialect's word rules (3601-CE-21: target,
// speed, accel and decel words 0; 3601-CE-15: command LSW 0) were checked at dispatch.
void Blend::run(planner::Direction dir) {
  // 3601-CE-03: a move while another is in progress; the running move is unaffected.
  if (ax_.moving()) {
    ax_.reject(items::kMoveWhileMoving, "Run Blend while a motion is running");
    return;
  }
  // 3601-CE-20: no profile stored (never programmed, an incomplete or failed cycle, or erased by
  // a configuration).
  if (!stored_) {
    ax_.reject(items::kBlendNotStored);
    return;
  }
  if (ax_.inputs_block_start(dir)) return;  // A15
  planner::BlendSpec spec = profile_;
  spec.dir = dir;  // + = CW, - = CCW; a profile never reverses (3601 Ch.4)
  spec.vs = ax_.cfg.starting_speed;
  if (ax_.motion.start_blend(spec) == 0) {
    ax_.reject(
        items::kPlannerFull);  // the planner queue is full: refuse rather than lose the command
    return;
  }
  // A new move clears the previous move's outcome (3601-MC-03, HLD-C1, IE-C1, STP-C1). The
  // position need not be valid: PI is left as it is (3601 Ch.4 "Blend Move").
  ax_.clear_move_outcome();
  ax_.fire(AxisEvent::kBlendStarted);
  ax_.dir = dir;
  ax_.move_decel = spec.final_decel;  // CE-22 brings the blend down with it
  hold_error_ = false;
}

void Blend::hold() {
  // 3601-CE-23: a blend cannot be held. CE is set, the blend runs on to its end and CE then
  // clears by itself. Only a CE set here clears itself: Hold reaches this point only with CE = 0
  // (3601-CE-L1), and a CE raised later for another reason cancels the self-clear (see
  // programming_scan and the CE-22 branch).
  ax_.reject(items::kHoldDuringBlend);
  hold_error_ = true;
}

// The outcome (MC, Stopped, or neither after CE-22) is the table's (docs/axis-states.md).
void Blend::motion_ended() {
  // 3601-CE-23 / CE-L3: the Hold's CE clears when the blend ends. Decision: at any end of the
  // blend (completed, or stopped by a limit or the E-stop, which report through IE), since the
  // error concerned only this blend; a CE raised for another reason is left set.
  if (hold_error_) ax_.fire(AxisEvent::kCommandErrorCleared);
  hold_error_ = false;
}

// Programming while the blend runs (3601-CE-22, 3202-CE-19): CE, and the blend is brought down
// with its final deceleration; neither MC (the move did not complete, 3601-MC-02) nor Stopped
// (3601-STP-N1: not after blends) follows, CE says why.
void Blend::bring_down() {
  ax_.reject(items::kBlendWhileBlending);
  hold_error_ = false;  // this CE does not clear itself
  if (ax_.fire(AxisEvent::kBlendBroughtDown)) ax_.motion.stop(ax_.move_decel);
}

void Blend::erase() {
  // 3601-CE-20: a configuration erases the profile and ends any cycle.
  stored_ = false;
  cycle_ = false;
  spoiled_ = false;
  blocks_ = 0;
  total_ = 0;
  ack_ = false;
  hold_error_ = false;
}

}  // namespace stepmod::module::axis
