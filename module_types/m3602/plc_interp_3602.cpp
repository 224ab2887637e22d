#include "module_types/m3602/plc_interp_3602.hpp"

#include <string>

#include "plc/bit_names.hpp"
#include "module_types/m3602/plc_status_3602.hpp"
#include "module_types/m3602/plc_words_3602.hpp"
#include "module_types/m3602/words_3602.hpp"
#include "plc/command_answer.hpp"

namespace stepmod::plc {

namespace m = words::m3602;
namespace iw = words::m3602::interp_word;

namespace {
constexpr auto kCommandErrors =
    static_cast<std::uint16_t>(command_errors(error_bits_of(m::kStatusMswBits)));
}  // namespace

std::uint16_t m3602::interpolation_bits(const PathMove3602& p) {
  using M = PathMove3602::Method;
  std::uint16_t bits = p.absolute ? m::cmd_lsw::kAbsoluteCoordinates : 0;
  switch (p.method) {
    case M::kLinear:
      return bits | m::cmd_lsw::kLinear;
    case M::kViaPoint:
      return bits | m::cmd_lsw::kViaPoint;
    case M::kCentreCw:
      return bits | m::cmd_lsw::kCwCircular;
    case M::kCentreCcw:
      return bits | m::cmd_lsw::kCcwCircular;
    case M::kRadiusCw:
      return bits | m::cmd_lsw::kRadiusMethod | m::cmd_lsw::kCwCircular;
    case M::kRadiusCcw:
      return bits | m::cmd_lsw::kRadiusMethod | m::cmd_lsw::kCcwCircular;
  }
  return bits;
}

void m3602::put_interpolated(ImageWords& w, const PathMove3602& p, bool command_bits,
                             std::uint16_t gpo) {
  using M = PathMove3602::Method;
  for (auto& word : w.w) word = 0;
  const std::uint16_t lsw = accel_bits(p.profile.type) | (gpo & m::cmd_lsw::kGpo) |
                            (command_bits ? interpolation_bits(p) : 0);
  w.w[iw::kLsw] = static_cast<std::int16_t>(lsw);
  put_split(w, 0, iw::kSpeedMsw, p.profile.speed);
  w.w[iw::kAccel] = static_cast<std::int16_t>(p.profile.accel);
  w.w[iw::kDecel] = static_cast<std::int16_t>(p.profile.decel);
  put_split(w, 0, iw::kEndXMsw, p.end_x);
  put_split(w, 0, iw::kEndYMsw, p.end_y);
  if (p.method == M::kRadiusCw || p.method == M::kRadiusCcw) {
    put_split(w, 0, iw::kPointXMsw, p.radius);
  } else if (p.method != M::kLinear) {
    put_split(w, 0, iw::kPointXMsw, p.point_x);
    put_split(w, 0, iw::kPointYMsw, p.point_y);
  }
}

Interp3602::Interp3602(Port& port, std::chrono::milliseconds timeout, Sequencing seq,
                       std::chrono::milliseconds settle)
    : port_(port), axes_(port, timeout, seq), timeout_(timeout), seq_(seq), settle_(settle) {}

Outcome Interp3602::finish(bool timed_out, const char* what) {
  Outcome o;
  if (!read_answer(port_, timed_out, what, timeout_, o)) return o;
  // Every interpolated error is reported on axis 1 (3602-CE-I1).
  const std::uint16_t msw = m3602::decode_status(o.in, 0).msw;
  if (msw & kCommandErrors) {
    o.ok = false;
    o.message = std::string(what) + ": " + set_bit_names(msw & kCommandErrors, m::kStatusMswBits);
    // With axis 1's reason when it is one of these bits' (docs/error-reasons.md): the refusal
    // names its item, as a single-axis command's does.
    const auto r = port_.reason(0);
    if (r && !r->text.empty() && (r->list() == 2 || r->list() == 3)) o.message += ": " + r->text;
  }
  return o;
}

Outcome Interp3602::move(const PathMove3602& p) {
  const auto gpo = static_cast<std::uint16_t>(port_.outputs().w[iw::kLsw]) & m::cmd_lsw::kGpo;
  // 1. The data with the command bits clear (a bit left set from before is released with it).
  port_.update_outputs([&](ImageWords& w) { m3602::put_interpolated(w, p, false, gpo); });
  // 2. The bits once the data have stood >= settle and the module has scanned them.
  port_.pass(settle_);
  if (!port_.wait_scans(seq_.release_scans)) return finish(true, "interpolated data");
  port_.update_outputs([&](ImageWords& w) { m3602::put_interpolated(w, p, true, gpo); });
  const bool seen = port_.wait_scans(seq_.hold_scans);
  // 3. Released: the data stay, the bits go (the next command needs a new 0->1 edge).
  port_.update_outputs([&](ImageWords& w) { m3602::put_interpolated(w, p, false, gpo); });
  const bool released = port_.wait_scans(seq_.release_scans);
  return finish(!(seen && released), "interpolated move");
}

Outcome Interp3602::hold() {
  return axes_.pulse(0, m::cmd_msw::kHold, 0, 0, 0, 0, 0);
}

Outcome Interp3602::resume(const Profile& p) {
  // Interpolation bits 0 (3602-CE-03 otherwise); the Resume block's layout (A39).
  return axes_.pulse(0, m::cmd_msw::kResume, m3602::accel_bits(p.type), 0, p.speed,
                     static_cast<std::int16_t>(p.accel), static_cast<std::int16_t>(p.decel));
}

Outcome Interp3602::immediate_stop() {
  return axes_.pulse(0, m::cmd_msw::kImmediateStop, 0, 0, 0, 0, 0);
}

Outcome Interp3602::wait_done(std::chrono::nanoseconds timeout) {
  const bool done = port_.wait_inputs(
      [](const ImageWords& in) {
        return m3602::decode_status(in, 0).has(m::status_msw::kStopped) &&
               m3602::decode_status(in, 1).has(m::status_msw::kStopped);
      },
      timeout);
  return finish(!done, "wait-done");
}

}  // namespace stepmod::plc
