#include "tools/ctl_summary.hpp"

#include "module/m3202/words_3202.hpp"
#include "module/m3601/words_3601.hpp"
#include "module/m3602/words_3602.hpp"
#include "plc/status_3202.hpp"
#include "plc/status_3601.hpp"
#include "plc/status_3602.hpp"

namespace stepmod::tools::ctl {

namespace {

// A status word's bits, whichever module: the dialect's constants.
struct Bits {
  std::uint32_t cfg_mode, cw, ccw, hold, stopped, at_home, complete;
  std::uint32_t cfg, ce, ip, ie, hi, pi;
};
#define STEPMOD_BITS_OF(ns)                                                                    \
  Bits {                                                                                       \
    ns::kConfigMode, ns::kMovingCw, ns::kMovingCcw, ns::kHoldState, ns::kStopped, ns::kAtHome, \
        ns::kMoveComplete, ns::kConfigurationError, ns::kCommandError, ns::kInvalidProfile,    \
        ns::kInputError, ns::kHomeInvalid, ns::kPositionInvalid                                \
  }
constexpr Bits k3601 = STEPMOD_BITS_OF(module::m3601::status_msw);
constexpr Bits k3602 = STEPMOD_BITS_OF(module::m3602::status_msw);
constexpr Bits k3202 = STEPMOD_BITS_OF(module::m3202::status_bit);
#undef STEPMOD_BITS_OF

AxisSummary from_word(std::uint32_t w, const Bits& b) {
  AxisSummary s;
  s.configuration_mode = (w & b.cfg_mode) != 0;
  s.moving_cw = (w & b.cw) != 0;
  s.moving_ccw = (w & b.ccw) != 0;
  s.hold = (w & b.hold) != 0;
  s.stopped = (w & b.stopped) != 0;
  s.at_home = (w & b.at_home) != 0;
  s.move_complete = (w & b.complete) != 0;
  s.cfg_error = (w & b.cfg) != 0;
  s.command_error = (w & b.ce) != 0;
  s.invalid_profile = (w & b.ip) != 0;
  s.input_error = (w & b.ie) != 0;
  s.home_invalid = (w & b.hi) != 0;
  s.position_invalid = (w & b.pi) != 0;
  return s;
}

}  // namespace

std::string AxisSummary::state() const {
  if (configuration_mode) return "configuration";
  if (moving_cw) return "moving cw";
  if (moving_ccw) return "moving ccw";
  if (blend_running) return "blend";
  if (hold) return "hold";
  if (at_home) return "at home";
  if (move_complete) return "complete";
  if (stopped) return "stopped";
  return "idle";
}

std::string AxisSummary::error_names() const {
  std::string s;
  const auto add = [&s](bool on, const char* name) {
    if (on) s += (s.empty() ? "" : ", ") + std::string(name);
  };
  add(cfg_error, "Configuration Error");
  add(command_error, "Command Error");
  add(invalid_profile, "Invalid Profile");
  add(input_error, "Input Error");
  add(home_invalid, "Home Invalid");
  add(position_invalid, "Position Invalid");
  return s;
}

std::vector<AxisSummary> summarize(ModuleType type, const ImageWords& in) {
  std::vector<AxisSummary> out;
  switch (type) {
    case ModuleType::k3601: {
      const plc::m3601::Status st = plc::m3601::decode_status(in);
      AxisSummary s = from_word(st.msw, k3601);
      s.blend_running = st.has_lsw(module::m3601::status_lsw::kBlendRunning);
      s.position = st.position;
      out.push_back(s);
      break;
    }
    case ModuleType::k3602:
      for (unsigned a = 0; a < 2; ++a) {
        const plc::m3602::Status st = plc::m3602::decode_status(in, a);
        AxisSummary s = from_word(st.msw, k3602);
        s.blend_running = st.has_lsw(module::m3602::status_lsw::kBlendRunning);
        s.position = st.position;
        out.push_back(s);
      }
      break;
    case ModuleType::k3202:
      for (unsigned c = 0; c < 2; ++c) {
        const plc::m3202::Status st = plc::m3202::decode_status(in, c);
        AxisSummary s = from_word(st.word, k3202);
        s.blend_running = st.has(module::m3202::status_bit::kBlendRunning);
        s.position = st.position;
        out.push_back(s);
      }
      break;
  }
  return out;
}

MotionEnd judge_end(const AxisSummary& s, Motion kind, const stepmod_reason_t& reason) {
  // The reason of a bit still set (an older one belongs to a bit since cleared).
  const std::string why = s.has_list(reason.item / 100u % 100u) ? reason_text(reason) : "";
  const std::string errors = s.error_names();
  const std::string with_reason = errors + (why.empty() ? "" : ": " + why);
  if (s.at_home && kind != Motion::kMove && kind != Motion::kJog) return {true, "at home"};
  if (s.move_complete && kind != Motion::kHome) return {true, "move complete"};
  // Faults and refusals first (Input Error is cleared by every start: it is this motion's).
  if (s.input_error || s.command_error || s.invalid_profile || s.home_invalid || s.cfg_error) {
    return {false, "ended with " + with_reason};
  }
  if (s.hold) return {false, "held (Hold State), not complete"};
  if (s.stopped) {
    // A jog ends Stopped by design; an immediate stop also leaves Position Invalid.
    if (kind == Motion::kJog) return {true, "stopped"};
    return {false, "stopped before its end" +
                       (s.position_invalid ? " (" + with_reason + ")" : std::string())};
  }
  if (s.position_invalid) return {false, "ended with " + with_reason};
  return {false, kind == Motion::kHome ? "idle, not at home" : "idle without Move Complete"};
}

}  // namespace stepmod::tools::ctl
