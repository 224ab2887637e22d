#include "tools/ctl_commands.hpp"

#include <thread>

#include "ipc/codec.hpp"
#include "module/m3601/words_3601.hpp"
#include "tools/ctl_status.hpp"

namespace stepmod::tools::ctl {

namespace m = module::m3601;

namespace {
// Errors that mean "the module rejected or failed this command" (status MSW).
constexpr std::uint16_t kCommandErrors =
    m::status_msw::kCommandError | m::status_msw::kInvalidProfile;
constexpr std::uint16_t kHomeErrors = kCommandErrors | m::status_msw::kHomeInvalid;

void put_split(ImageWords& w, unsigned msw_index, std::int64_t value) {
  const ipc::codec::WordPair p = ipc::codec::encode_3601(value);
  w.w[msw_index] = p.msw;
  w.w[msw_index + 1] = p.lsw;
}

void put_profile(ImageWords& w, const Profile& p) {
  put_split(w, m::out_word::kSpeedMsw, p.speed);
  w.w[m::out_word::kAccel] = p.accel;
  w.w[m::out_word::kDecel] = p.decel;
}
}  // namespace

Plc3601::Plc3601(ipc::Client& client, std::chrono::milliseconds timeout)
    : c_(client), timeout_(timeout) {
  if (client.type() != ModuleType::k3601) {
    throw ipc::IpcError("module '" + client.name() + "' is a " +
                        std::to_string(static_cast<unsigned>(client.type())) +
                        ", not a 3601: use 'raw set' to drive it");
  }
}

std::uint16_t Plc3601::accel_bits(AccelType t) {
  switch (t) {
    case AccelType::kConstant:
      return 0;
    case AccelType::kTriangularS:
      return m::cmd_lsw::kSCurve;
    case AccelType::kTrapezoidalS:
      return m::cmd_lsw::kSCurve | m::cmd_lsw::kTrapezoidalS;
  }
  return 0;
}

std::uint16_t Plc3601::pair_bits(AccelType t) {
  // Same code as the command LSW: low bit S-curve, high bit trapezoidal (digest 3.8).
  return accel_bits(t);
}

ImageWords Plc3601::outputs() const {
  ImageWords w;
  c_.read_outputs(w);
  return w;
}

bool Plc3601::settle() {
  // The scan running while we wrote may have taken its snapshot before the write; the one after
  // it certainly saw it. Heartbeat: we are the PLC while we drive the module (INTERFACE 3.2).
  c_.heartbeat();
  const std::uint64_t target = c_.scan_counter() + 2;
  const auto deadline = std::chrono::steady_clock::now() + timeout_;
  while (!c_.wait_scan_counter(target, std::chrono::milliseconds(50))) {
    c_.heartbeat();
    if (std::chrono::steady_clock::now() >= deadline) return false;
  }
  return true;
}

bool Plc3601::release_bits(unsigned word, std::uint16_t bits) {
  const ImageWords now = outputs();
  if ((static_cast<std::uint16_t>(now.w[word]) & bits) == 0) return true;
  c_.update_outputs([&](ImageWords& w) { w.w[word] &= ~static_cast<std::int32_t>(bits); });
  return settle();
}

Outcome Plc3601::finish(std::uint16_t error_mask, bool timed_out, const std::string& what) {
  Outcome o;
  c_.read_inputs(o.in);
  if (timed_out) {
    o.ok = false;
    o.timed_out = true;
    o.message = what + ": no answer from the module within " + std::to_string(timeout_.count()) +
                " ms (is stepmodd running?)";
    return o;
  }
  const auto msw = static_cast<std::uint16_t>(o.in.w[m::in_word::kStatusMsw]);
  if (msw & error_mask) {
    o.ok = false;
    o.message = what + ": " + set_bit_names(msw & error_mask, status_msw_names_3601());
  }
  return o;
}

Outcome Plc3601::edge_command(const ImageWords& words, std::uint16_t edge_bit,
                              std::uint16_t error_mask) {
  // A command bit left at 1 (by an earlier PLC program or an interrupted stepmodctl) would hide
  // our 0->1 edge: release every command bit first.
  if (!release_bits(m::out_word::kMsw, m::cmd_msw::kCommandMask)) {
    return finish(error_mask, true, "release");
  }
  c_.write_outputs(words);
  const bool seen = settle();
  // Edge-triggered: release the bit so that the next command is a new edge. Parameters stay,
  // as a PLC program leaves them.
  c_.update_outputs([&](ImageWords& w) { w.w[m::out_word::kMsw] &= ~edge_bit; });
  const bool released = settle();
  return finish(error_mask, !(seen && released), "command");
}

Outcome Plc3601::configure(std::uint16_t cfg_msw, std::uint16_t cfg_lsw, std::int32_t start_speed) {
  ImageWords w;
  w.w[m::out_word::kMsw] = static_cast<std::int16_t>(cfg_msw | m::cfg_msw::kConfigMode);
  w.w[m::out_word::kLsw] = static_cast<std::int16_t>(cfg_lsw);
  put_split(w, m::out_word::kTargetMsw, start_speed);
  c_.write_outputs(w);
  if (!settle()) return finish(0, true, "configure");
  // The verdict is read in configuration mode, where bit 13 reports this configuration.
  Outcome cfg = finish(m::status_msw::kConfigurationError, false, "configure");
  c_.write_outputs(ImageWords{});  // back to command mode, all words 0
  if (!settle()) return finish(0, true, "command mode");
  Outcome o = finish(m::status_msw::kConfigurationError, false, "configure");
  if (!cfg.ok) {
    o.ok = false;
    o.message = cfg.message;
  }
  return o;
}

Outcome Plc3601::move(bool absolute, std::int32_t target, const Profile& p, bool encoder_move) {
  ImageWords w;
  const std::uint16_t bit = absolute ? m::cmd_msw::kAbsoluteMove : m::cmd_msw::kRelativeMove;
  w.w[m::out_word::kMsw] = bit;
  w.w[m::out_word::kLsw] = accel_bits(p.type) | (encoder_move ? m::cmd_lsw::kEncoderMove : 0);
  put_split(w, m::out_word::kTargetMsw, target);
  put_profile(w, p);
  return edge_command(w, bit, kCommandErrors);
}

Outcome Plc3601::jog(bool cw, const Profile& p, std::chrono::milliseconds duration,
                     std::int32_t registration) {
  if (!release_bits(m::out_word::kMsw, m::cmd_msw::kCommandMask)) {
    return finish(kCommandErrors, true, "release");
  }
  ImageWords w;
  const std::uint16_t bit = cw ? m::cmd_msw::kManualCw : m::cmd_msw::kManualCcw;
  w.w[m::out_word::kMsw] = bit;
  w.w[m::out_word::kLsw] = accel_bits(p.type);
  put_split(w, m::out_word::kTargetMsw, registration);
  put_profile(w, p);
  c_.write_outputs(w);
  // Level-held: keep the bit for the duration, being the PLC's heartbeat meanwhile.
  const auto end = std::chrono::steady_clock::now() + duration;
  bool scanned = settle();
  while (scanned && std::chrono::steady_clock::now() < end) {
    c_.heartbeat();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  c_.update_outputs([&](ImageWords& o) { o.w[m::out_word::kMsw] &= ~bit; });
  if (!scanned || !settle()) return finish(kCommandErrors, true, "jog");
  const Outcome idle = wait_idle(timeout_ + std::chrono::seconds(30));
  if (idle.timed_out) return idle;
  return finish(kCommandErrors, false, "jog");
}

Outcome Plc3601::home(bool cw, const Profile& p) {
  ImageWords w;
  const std::uint16_t bit = cw ? m::cmd_msw::kFindHomeCw : m::cmd_msw::kFindHomeCcw;
  w.w[m::out_word::kMsw] = bit;
  // Homing is constant acceleration only and the target words must be 0 (digest 3.5).
  put_profile(w, p);
  // Keep the backplane proximity bit as the PLC left it: it is the PLC's input to homing.
  w.w[m::out_word::kLsw] = outputs().w[m::out_word::kLsw] & m::cmd_lsw::kBackplaneProximity;
  return edge_command(w, bit, kHomeErrors);
}

Outcome Plc3601::hold() {
  ImageWords w = outputs();  // parameters are ignored by Hold: leave them
  w.w[m::out_word::kMsw] = m::cmd_msw::kHold;
  return edge_command(w, m::cmd_msw::kHold, m::status_msw::kCommandError);
}

Outcome Plc3601::resume(const std::optional<Profile>& p) {
  ImageWords w = outputs();
  w.w[m::out_word::kMsw] = m::cmd_msw::kResume;
  if (p) {
    put_profile(w, *p);
    // S-curve bits must be supplied again with Resume (digest 3.5).
    w.w[m::out_word::kLsw] = (w.w[m::out_word::kLsw] & ~0x3) | accel_bits(p->type);
  }
  return edge_command(w, m::cmd_msw::kResume, kCommandErrors);
}

Outcome Plc3601::immediate_stop() {
  ImageWords w = outputs();
  w.w[m::out_word::kMsw] = m::cmd_msw::kImmediateStop;
  return edge_command(w, m::cmd_msw::kImmediateStop, m::status_msw::kCommandError);
}

Outcome Plc3601::preset_position(std::int32_t position) {
  ImageWords w;  // LSW and words 4..7 must be 0
  w.w[m::out_word::kMsw] = m::cmd_msw::kPresetPosition;
  put_split(w, m::out_word::kTargetMsw, position);
  return edge_command(w, m::cmd_msw::kPresetPosition, m::status_msw::kCommandError);
}

Outcome Plc3601::preset_encoder(std::int32_t value) {
  ImageWords w;
  w.w[m::out_word::kMsw] = m::cmd_msw::kPresetEncoder;
  put_split(w, m::out_word::kTargetMsw, value);
  return edge_command(w, m::cmd_msw::kPresetEncoder, m::status_msw::kCommandError);
}

Outcome Plc3601::reset_errors() {
  ImageWords w = outputs();
  w.w[m::out_word::kMsw] = m::cmd_msw::kResetErrors;
  w.w[m::out_word::kLsw] = 0;  // must be 0 with Reset Errors
  return edge_command(w, m::cmd_msw::kResetErrors, m::status_msw::kCommandError);
}

Outcome Plc3601::set_min_registration(std::int32_t distance) {
  if (!release_bits(m::out_word::kMsw, m::cmd_msw::kCommandMask) ||
      !release_bits(m::out_word::kLsw, m::cmd_lsw::kStoreMinRegistration)) {
    return finish(kCommandErrors, true, "release");
  }
  ImageWords w;
  w.w[m::out_word::kLsw] = m::cmd_lsw::kStoreMinRegistration;
  put_split(w, m::out_word::kTargetMsw, distance);
  c_.write_outputs(w);
  const bool seen = settle();
  c_.update_outputs([](ImageWords& o) { o.w[m::out_word::kLsw] = 0; });
  return finish(kCommandErrors, !(seen && settle()), "min-registration");
}

bool Plc3601::wait_status(std::uint16_t lsw_bit, bool want, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    ImageWords in;
    if (c_.read_inputs(in) &&
        ((static_cast<std::uint16_t>(in.w[m::in_word::kStatusLsw]) & lsw_bit) != 0) == want) {
      return true;
    }
    if (std::chrono::steady_clock::now() >= deadline) return false;
    c_.heartbeat();
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

Outcome Plc3601::blend_program(const BlendProfile& b) {
  constexpr std::uint16_t kProgram = m::cmd_lsw::kProgramBlend;
  constexpr std::uint16_t kTransmit = m::cmd_lsw::kBlendTransmit;
  if (!release_bits(m::out_word::kMsw, m::cmd_msw::kCommandMask) ||
      !release_bits(m::out_word::kLsw, kProgram | kTransmit)) {
    return finish(kCommandErrors, true, "release");
  }
  // Block 1: segment count, type pairs, final deceleration (digest 3.8).
  std::vector<ImageWords> blocks;
  ImageWords first;
  first.w[2] = static_cast<std::int32_t>(b.segments.size());
  std::uint16_t pairs_lo = 0;
  std::uint16_t pairs_hi = 0;
  for (std::size_t i = 0; i < b.segments.size() && i < 16; ++i) {
    const std::uint16_t bits = pair_bits(b.segments[i].type);
    if (i < 8) {
      pairs_lo = static_cast<std::uint16_t>(pairs_lo | bits << (2 * i));
    } else {
      pairs_hi = static_cast<std::uint16_t>(pairs_hi | bits << (2 * (i - 8)));
    }
  }
  first.w[3] = static_cast<std::int16_t>(pairs_hi);
  first.w[4] = static_cast<std::int16_t>(pairs_lo);
  first.w[5] = static_cast<std::int16_t>(pair_bits(b.final_type) << 14 | (b.final_decel & 0x3FFF));
  blocks.push_back(first);
  for (const BlendSegment& s : b.segments) {
    ImageWords blk;
    put_split(blk, 2, s.length);
    put_split(blk, 4, s.speed);
    blk.w[6] = s.accel;
    blocks.push_back(blk);
  }
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    ImageWords w = blocks[i];
    w.w[m::out_word::kLsw] = kProgram | kTransmit;
    c_.write_outputs(w);
    if (!wait_status(m::status_lsw::kBlendAcknowledge, true, timeout_)) {
      c_.write_outputs(ImageWords{});
      return finish(kCommandErrors, true, "blend block " + std::to_string(i + 1));
    }
    c_.update_outputs([&](ImageWords& o) { o.w[m::out_word::kLsw] = kProgram; });
    if (!wait_status(m::status_lsw::kBlendAcknowledge, false, timeout_)) {
      c_.write_outputs(ImageWords{});
      return finish(kCommandErrors, true, "blend block " + std::to_string(i + 1));
    }
  }
  c_.write_outputs(ImageWords{});  // program bit off: the profile is complete
  return finish(kCommandErrors, !settle(), "blend program");
}

Outcome Plc3601::blend_run(bool cw) {
  ImageWords w;  // every other word must be 0 with Run Blend
  const std::uint16_t bit = cw ? m::cmd_msw::kRunBlendCw : m::cmd_msw::kRunBlendCcw;
  w.w[m::out_word::kMsw] = bit;
  return edge_command(w, bit, kCommandErrors);
}

Outcome Plc3601::wait_idle(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  constexpr std::uint16_t kMoving = m::status_msw::kMovingCw | m::status_msw::kMovingCcw;
  for (;;) {
    ImageWords in;
    if (c_.read_inputs(in)) {
      const auto msw = static_cast<std::uint16_t>(in.w[m::in_word::kStatusMsw]);
      const auto lsw = static_cast<std::uint16_t>(in.w[m::in_word::kStatusLsw]);
      if ((msw & kMoving) == 0 && (lsw & m::status_lsw::kBlendRunning) == 0) {
        return finish(0, false, "wait-idle");
      }
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      Outcome o = finish(0, false, "wait-idle");
      o.ok = false;
      o.timed_out = true;
      o.message = "wait-idle: still moving after " + std::to_string(timeout.count()) + " ms";
      return o;
    }
    c_.heartbeat();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

Outcome Plc3601::status() {
  return finish(0, false, "status");
}

}  // namespace stepmod::tools::ctl
