// 3601 blend moves: the block-by-block programming handshake and Run Blend (3601 manual Ch.4
// "Blend Move", Ch.5 "Blend Move Programming"; digest 3.8, 7.10).
//
// Programming (digest 7.10 handshake): with the command MSW = 0 the PLC holds LSW bit 8
// (program) for the whole cycle and raises LSW bit 9 (transmit) once per block. Each transmit
// rising edge reads one block, checks it and sets the acknowledge (status LSW bit 9); the
// acknowledge follows transmit back to 0. Every check is made on the block that brings its data,
// so an error is reported with that block's acknowledge. Clearing the program bit ends the cycle:
// the profile is stored only if the cycle had no error and brought exactly the declared number of
// segment blocks (A21c).
#include <cmath>

#include "module/m3601/params_3601.hpp"
#include "module/m3601/personality_3601.hpp"
#include "module/m3601/words_3601.hpp"
#include "planner/profile.hpp"

namespace stepmod::module::m3601 {

namespace {

constexpr int kMinSegments = 2;
constexpr int kMaxSegments = 16;
constexpr std::int64_t kMaxBlendLength = 8'388'607;  // digest 7.10 rule 2 (3601-IP-20)

// First programming block (digest 3.8).
constexpr unsigned kSegmentCountWord = 2;
constexpr unsigned kPairs9To16Word = 3;
constexpr unsigned kPairs1To8Word = 4;
constexpr unsigned kFinalDecelWord = 5;

// Acceleration-type pair of segment n (1..16): word 4 holds segments 1..8, word 3 segments
// 9..16, two bits each, segment 1 (or 9) in bits 1:0 (digest 3.8).
planner::AccelShape segment_shape(const ImageWords& first, int n) {
  const auto word = static_cast<std::uint16_t>(first.w[n <= 8 ? kPairs1To8Word : kPairs9To16Word]);
  const int shift = 2 * ((n - 1) % 8);
  const unsigned pair = (word >> shift) & 0x3u;
  // A22: the low bit selects S-curve; binary 10 (low bit 0) is constant, as the manual's general
  // rule "least significant bit reset => constant" says.
  if (!(pair & 0x1u)) return planner::AccelShape::kConstant;
  return (pair & 0x2u) ? planner::AccelShape::kTrapezoidalS : planner::AccelShape::kTriangularS;
}

// Distances are compared with a hair of tolerance: a transition that exactly fills its segment
// (the "touch" case) is legal, and floating rounding must not turn it into an error.
bool fits(double needed, double length) {
  return needed <= length + 1e-6 * (1.0 + length);
}

}  // namespace

void Personality3601::blend_programming_scan(const ImageWords& out) {
  // The Hold's CE (3601-CE-23) was cleared by Reset Errors: a CE raised later has another reason
  // and must not clear itself at the blend's end.
  if (!status_.command_error) blend_hold_error_ = false;

  const bool program = (lsw_ & cmd_lsw::kProgramBlend) != 0;
  const bool transmit = (lsw_ & cmd_lsw::kBlendTransmit) != 0;
  const bool transmit_rose = transmit && !(prev_lsw_ & cmd_lsw::kBlendTransmit);
  // Routine step 4: the acknowledge follows the transmit bit back to 0.
  if (!transmit) blend_ack_ = false;

  if (!program) {
    if (blend_cycle_) {
      // Routine step 6: the cycle ends. A21c: fewer segment blocks than declared = not
      // programmed (Run Blend then raises CE-20); a block too many was already an IP error.
      blend_cycle_ = false;
      if (!blend_spoiled_ && blend_blocks_ > 0 &&
          blend_blocks_ == 1u + static_cast<unsigned>(blend_pending_.count)) {
        blend_profile_ = blend_pending_;
        blend_stored_ = true;
      }
    }
    return;
  }
  if (!blend_cycle_) {
    blend_cycle_ = true;
    blend_spoiled_ = false;
    blend_blocks_ = 0;
    blend_total_ = 0;
    blend_pending_ = planner::BlendSpec{};
  }
  if (!transmit_rose) return;

  // Routine step 2: every block is acknowledged, a rejected one too (A21d, 3601-IP-21), so that
  // the PLC's handshake never waits forever; the error bits tell it the block was refused.
  blend_ack_ = true;
  const bool first = blend_blocks_ == 0;
  ++blend_blocks_;
  if (blend_spoiled_) return;  // the cycle already failed: the rest is read and ignored

  if (first && activity_ == Activity::kBlend) {
    // 3601-CE-22: programming started while a blend runs. The cycle is refused (the stored
    // profile, which the running blend came from, is kept) and the blend is brought down with
    // its final-segment deceleration.
    blend_spoiled_ = true;
    reject();
    blend_hold_error_ = false;  // this CE does not clear itself
    if (stop_cause_ == StopCause::kNone) {
      stop_cause_ = StopCause::kHold;  // a controlled stop; blend_motion_ended gives its outcome
      motion_.stop(move_decel_);
    }
    return;
  }
  if (status_.command_error) {
    // 3601-CE-L1: while CE is set the module takes no new operation; a block is not stored and
    // the profile is reported invalid (3601-IP-21) so that a PLC checking only IP sees it too.
    blend_spoiled_ = true;
    status_.invalid_profile = true;
    return;
  }
  if (first) {
    // A new profile replaces the stored one from its first block on (digest 7.10 rule 7).
    blend_stored_ = false;
  }
  // Word 0 of every block is the command MSW, which must be 0 (digest 3.8).
  const bool msw_ok = out.w[out_word::kMsw] == 0;
  const bool ok = first ? blend_first_block(out) : blend_segment_block(out);
  if (!ok || !msw_ok) {
    blend_spoiled_ = true;
    status_.invalid_profile = true;  // 3601-IP-21: any error in a block
  }
}

bool Personality3601::blend_first_block(const ImageWords& out) {
  bool ok = true;
  // 3601-IP-04: 2..16 segments.
  const std::int32_t count = static_cast<std::int16_t>(out.w[kSegmentCountWord]);
  if (count < kMinSegments || count > kMaxSegments) {
    ok = false;
  } else {
    blend_pending_.count = static_cast<std::uint8_t>(count);
    for (int n = 1; n <= count; ++n) {
      blend_pending_.segments[static_cast<std::size_t>(n - 1)].ramp.shape = segment_shape(out, n);
    }
  }
  // Word 5: final deceleration, type in bits 15-14, value in bits 13-0 (digest 3.8).
  const auto w5 = static_cast<std::uint16_t>(out.w[kFinalDecelWord]);
  const unsigned type = w5 >> 14;
  const std::int32_t value = w5 & 0x3FFF;
  switch (type) {
    case 0b00:
      blend_pending_.final_decel.shape = planner::AccelShape::kConstant;
      break;
    case 0b01:
      blend_pending_.final_decel.shape = planner::AccelShape::kTriangularS;
      break;
    case 0b11:
      blend_pending_.final_decel.shape = planner::AccelShape::kTrapezoidalS;
      break;
    default:
      ok = false;
      break;  // 3601-IP-19, A22: type 10 is invalid for the final decel
  }
  if (value == 0) {
    // 3601-CE-24 / IP-07, A21a: no final deceleration value -> CE (Ch.5) and IP (Ch.6 #7).
    status_.command_error = true;
    ok = false;
  } else if (!rate_in_range(value)) {
    ok = false;  // 3601-IP-02: outside 1..2000
  } else {
    blend_pending_.final_decel.rate = rate_from_word(value);
  }
  // Words 6 and 7 are 0 in the first block.
  if (out.w[out_word::kAccel] != 0 || out.w[out_word::kDecel] != 0) ok = false;
  return ok;
}

bool Personality3601::blend_segment_block(const ImageWords& out) {
  const int n = static_cast<int>(blend_blocks_) - 1;  // this block's segment, 1-based
  // A21c: a segment block beyond the declared count is an error.
  if (n > blend_pending_.count) return false;
  bool ok = true;
  planner::BlendSegment& seg = blend_pending_.segments[static_cast<std::size_t>(n - 1)];

  // 3601-IP-20: the length is positive, its LSW within 0..999, and the lengths add up to at most
  // 8,388,607 (Ch.5 "Segment Length Restrictions").
  const auto length =
      ipc::codec::decode_3601_unsigned(out.w[out_word::kTargetMsw], out.w[out_word::kTargetLsw]);
  if (!length || *length <= 0) {
    ok = false;
  } else {
    seg.length = *length;
    blend_total_ += *length;
    if (blend_total_ > kMaxBlendLength) ok = false;
  }
  // Target speed Vs..1,000,000 (3601-IP-02 range; below Vs: 3601-CE-05 / IP-01, which name blend
  // moves among the moves that may not run below the starting speed).
  const auto speed = speed_words(out);
  if (!speed || *speed > kMaxSpeed) {
    ok = false;
  } else if (*speed < cfg_.starting_speed) {
    status_.command_error = true;
    ok = false;
  } else {
    seg.speed = static_cast<double>(*speed);
  }
  // Word 6: the accel/decel that reaches this segment's speed, 1..2000 (3601-IP-02).
  const std::int32_t rate = static_cast<std::int16_t>(out.w[out_word::kAccel]);
  if (!rate_in_range(rate)) {
    ok = false;
  } else {
    seg.ramp.rate = rate_from_word(rate);
  }
  if (out.w[out_word::kDecel] != 0) ok = false;  // word 7 is 0
  if (!ok) return false;

  // Digest 7.10 rules 3-5, checked as soon as the segment's data is here: segment 1 starts at
  // Vs, segment i at V(i-1).
  const double vs = cfg_.starting_speed;
  const double v_prev =
      n == 1 ? vs : blend_pending_.segments[static_cast<std::size_t>(n - 2)].speed;
  // 3601-IP-06: two consecutive segments with the same speed.
  if (n > 1 && seg.speed == v_prev) return false;
  // 3601-IP-05: the segment must reach its speed inside its length (k |Vi^2 - Vi-1^2| / 2Ai).
  double needed = planner::ramp_distance(v_prev, seg.speed, seg.ramp);
  // A21b: the last segment also holds the final deceleration to Vs, which ends exactly at the
  // sum of the lengths.
  if (n == blend_pending_.count) {
    needed += planner::ramp_distance(seg.speed, vs, blend_pending_.final_decel);
  }
  return fits(needed, static_cast<double>(seg.length));
}

// Run Blend + (MSW bit 12) / - (bit 13): 3601 manual Ch.4 "Blend Move".
void Personality3601::command_run_blend(const ImageWords& out, planner::Direction dir) {
  // 3601-CE-03: a move while another is in progress; the running move is unaffected.
  if (moving()) {
    reject();
    return;
  }
  // 3601-CE-20: no profile stored (never programmed, an incomplete or failed cycle, or erased by
  // a configuration).
  if (!blend_stored_) {
    reject();
    return;
  }
  // 3601-CE-21: target, speed, accel and decel words must be 0.
  if (!words_zero(out, out_word::kTargetMsw, out_word::kDecel)) {
    reject();
    return;
  }
  // 3601-CE-15: the command LSW must be 0 with Run Blend.
  if (lsw_ != 0) {
    reject();
    return;
  }
  if (inputs_block_start(dir)) return;  // A15
  planner::BlendSpec spec = blend_profile_;
  spec.dir = dir;  // + = CW, - = CCW; a profile never reverses (digest 7.10 rule 6)
  spec.vs = cfg_.starting_speed;
  if (motion_.start_blend(spec) == 0) {
    reject();  // the planner queue is full: refuse rather than lose the command
    return;
  }
  // A new move clears the previous move's outcome (3601-MC-03, HLD-C1, IE-C1, STP-C1). The
  // position need not be valid: PI is left as it is (digest 7.10 rule 6).
  clear_move_outcome();
  activity_ = Activity::kBlend;
  dir_ = dir;
  move_decel_ = spec.final_decel;  // CE-22 brings the blend down with it
  stop_cause_ = StopCause::kNone;
  blend_hold_error_ = false;
}

void Personality3601::blend_hold() {
  // 3601-CE-23: a blend cannot be held. CE is set, the blend runs on to its end and CE then
  // clears by itself. Only a CE set here clears itself: Hold reaches this point only with CE = 0
  // (3601-CE-L1), and a CE raised later for another reason cancels the self-clear (see
  // blend_programming_scan and the CE-22 branch).
  reject();
  blend_hold_error_ = true;
}

void Personality3601::blend_motion_ended(StopCause cause) {
  switch (cause) {
    case StopCause::kNone:
      status_.move_complete = true;  // 3601-MC-01
      break;
    case StopCause::kImmediate:
    case StopCause::kFault:
      status_.stopped = true;  // 3601-STP-02/03/04: E-stop, Immediate Stop, limit
      break;
    default:
      // Brought down by programming (3601-CE-22): neither MC (the move did not complete,
      // 3601-MC-02) nor Stopped (3601-STP-N1: not after blends); CE says why.
      break;
  }
  // 3601-CE-23 / CE-L3: the Hold's CE clears when the blend ends. Decision: at any end of the
  // blend (completed, or stopped by a limit or the E-stop, which report through IE), since the
  // error concerned only this blend; a CE raised for another reason is left set.
  if (blend_hold_error_) status_.command_error = false;
  blend_hold_error_ = false;
}

void Personality3601::blend_erase() {
  // Digest 7.10 rule 7: a configuration erases the profile (3601-CE-20) and ends any cycle.
  blend_stored_ = false;
  blend_cycle_ = false;
  blend_spoiled_ = false;
  blend_blocks_ = 0;
  blend_total_ = 0;
  blend_ack_ = false;
  blend_hold_error_ = false;
}

std::uint16_t Personality3601::blend_status_lsw() const noexcept {
  std::uint16_t lsw = 0;
  // 3601-LSW-01: bit 8 for the whole blend (its deceleration included), bit 9 = acknowledge.
  if (activity_ == Activity::kBlend) lsw |= status_lsw::kBlendRunning;
  if (blend_ack_) lsw |= status_lsw::kBlendAcknowledge;
  return lsw;
}

}  // namespace stepmod::module::m3601
