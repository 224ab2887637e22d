#include "tools/ctl_summary.hpp"

#include "tools/ctl_dialects.hpp"

namespace stepmod::tools::ctl {

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

std::vector<std::string> AxisSummary::error_list() const {
  std::vector<std::string> names;
  const auto add = [&names](bool on, const char* name) {
    if (on) names.emplace_back(name);
  };
  add(cfg_error, "Configuration Error");
  add(command_error, "Command Error");
  add(invalid_profile, "Invalid Profile");
  add(input_error, "Input Error");
  add(home_invalid, "Home Invalid");
  add(position_invalid, "Position Invalid");
  return names;
}

std::string AxisSummary::error_names() const {
  std::string s;
  for (const std::string& n : error_list()) s += (s.empty() ? "" : ", ") + n;
  return s;
}

AxisSummary summary_from_word(std::uint32_t w, std::span<const SummaryBit> bits) {
  AxisSummary s;
  for (const SummaryBit& b : bits) {
    if (b.flag != nullptr && (w & b.mask) != 0) s.*b.flag = true;
  }
  return s;
}

std::vector<AxisSummary> summarize(ModuleType type, const ImageWords& in) {
  return ctl_row_of(type).summarize(in);
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
