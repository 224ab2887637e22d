#include "tools/ctl_args.hpp"

namespace stepmod::tools::ctl {

std::int64_t parse_number(const std::string& s, const std::string& what) {
  std::string t = s;
  bool neg = false;
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) {
    neg = t[0] == '-';
    t.erase(0, 1);
  }
  int base = 10;
  if (t.rfind("0x", 0) == 0 || t.rfind("0X", 0) == 0) {
    base = 16;
    t.erase(0, 2);
  } else if (t.rfind("16#", 0) == 0) {
    base = 16;
    t.erase(0, 3);
  }
  std::size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(t, &used, base);
  } catch (const std::exception&) {
    used = 0;
  }
  // A sign after the prefix ("0x-5") would be accepted by stoll: refuse it.
  if (t.empty() || used != t.size() || t[0] == '-' || t[0] == '+') {
    throw UsageError(what + ": '" + s + "' is not a number");
  }
  return neg ? -v : v;
}

void check_range(std::int64_t v, const std::string& what, std::int64_t lo, std::int64_t hi,
                 const std::string& words) {
  if (v < lo || v > hi) {
    throw UsageError(what + ": " + std::to_string(v) + " does not fit " + words + " (" +
                     std::to_string(lo) + ".." + std::to_string(hi) + ")");
  }
}

std::int64_t parse_in_range(const std::string& s, const std::string& what, std::int64_t lo,
                            std::int64_t hi, const std::string& words) {
  const std::int64_t v = parse_number(s, what);
  check_range(v, what, lo, hi, words);
  return v;
}

std::int32_t parse_limited(const std::string& s, const std::string& what, const Limits& l) {
  return static_cast<std::int32_t>(parse_in_range(s, what, l.lo, l.hi, l.words));
}

plc::Profile parse_profile(const ProfileArgs& p, const ProfileLimits& l) {
  if (p.speed.empty() || p.accel.empty() || p.decel.empty()) {
    throw UsageError("--speed, --accel and --decel are all needed");
  }
  return {parse_limited(p.speed, "--speed", l.speed), parse_limited(p.accel, "--accel", l.rate),
          parse_limited(p.decel, "--decel", l.rate), parse_accel_type(p.scurve)};
}

std::optional<plc::Profile> parse_optional_profile(const ProfileArgs& p, const ProfileLimits& l) {
  if (!p.given()) {
    if (!p.scurve.empty()) throw UsageError("--scurve needs --speed, --accel and --decel");
    return std::nullopt;
  }
  return parse_profile(p, l);
}

bool parse_direction(const std::string& s) {
  if (s == "+" || s == "cw" || s == "CW") return true;
  if (s == "-" || s == "ccw" || s == "CCW") return false;
  throw UsageError("direction must be + (cw) or - (ccw), not '" + s + "'");
}

plc::AccelType parse_accel_type(const std::string& s) {
  if (s.empty() || s == "const" || s == "constant") return plc::AccelType::kConstant;
  if (s == "tri" || s == "triangular") return plc::AccelType::kTriangularS;
  if (s == "trap" || s == "trapezoidal") return plc::AccelType::kTrapezoidalS;
  throw UsageError("acceleration type must be const, tri or trap, not '" + s + "'");
}

unsigned input_index(const std::string& name) {
  for (unsigned i = 0; i < std::size(kInputNames); ++i) {
    if (name == kInputNames[i]) return i;
  }
  throw UsageError(
      "input must be one of capture, external, home, estop, cw_limit, ccw_limit, not '" + name +
      "'");
}

std::uint32_t shared_config_bits(const ConfigureArgs& a, const words::SharedConfigMasks& m) {
  std::uint32_t bits = 0;
  bits |= a.capture ? m.capture : 0;
  bits |= a.external ? m.external : 0;
  bits |= a.home ? m.home : 0;
  bits |= a.estop ? m.estop : 0;
  bits |= a.cw_limit ? m.cw_limit : 0;
  bits |= a.ccw_limit ? m.ccw_limit : 0;
  bits |= a.proximity ? m.proximity : 0;
  bits |= a.encoder ? m.encoder : 0;
  bits |= a.diagnostic ? m.diagnostic : 0;
  bits |= a.cw_ccw ? 0 : m.step_dir;
  bits |= a.marker ? m.marker : 0;
  return bits;
}

}  // namespace stepmod::tools::ctl
